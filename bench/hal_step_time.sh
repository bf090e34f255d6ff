#!/bin/bash
# hal_step_time.sh - median step-time-ns of the virtual board's dynamics
# funct inside HAL (uspace, 1 ms servo thread), the board sinking with the
# drives off. Needs the modules installed: run it under the install lock,
#   flock /tmp/hg-modules.lock sh -c 'make -s install && bench/hal_step_time.sh reduced-cartesian'
# Usage: bench/hal_step_time.sh MODEL [SAMPLES] [setp NAME VALUE]...
# Prints: HALTIME model=<m> <setp...> median_ns=<x> p90_ns=<y> samples=<n>
. "$(dirname "$0")/../tests/hal/hal_env.sh"   # re-runs this script in its own namespaces
model=${1:-reduced-cartesian}; shift
n=${1:-200}; shift
B=motenc.0; X=motenc-hexaglide.0
h() { halcmd "$@"; }
g() { halcmd getp "$1"; }
s() { halcmd setp "$1" "$2"; }
/usr/lib/linuxcnc/realtime start >/dev/null 2>&1 || { echo "HALTIME realtime start failed"; exit 1; }
h loadrt threads name1=servo period1=1000000 || exit 1
h loadrt motenc_hexaglide_dyns_virtual model="$model" || exit 1
for f in encoder-read digital-in-read adc-read dac-write dynamics digital-out-write misc-update; do
    h addf $B.$f servo || exit 1
done
h setp $B.out-07 1
extra=""
while [ "$1" = setp ]; do
    s "$X.$2" "$3" || { echo "HALTIME setp $2 $3 refused"; exit 1; }
    extra="$extra $2=$3"; shift 3
done
s $X.estop-button 1
h start
sleep 0.3
times=$(for i in $(seq "$n"); do g $X.step-time-ns; sleep 0.01; done | sort -n)
h stop
med=$(echo "$times" | sed -n "$(( (n + 1) / 2 ))p")
p90=$(echo "$times" | sed -n "$(( n * 9 / 10 ))p")
echo "HALTIME model=$model$extra median_ns=$med p90_ns=$p90 samples=$n fault=$(g $X.fault)"
