#!/bin/bash
# hal_step_time.sh - step-time-ns of the virtual board's dynamics funct
# inside HAL (uspace, 1 ms servo thread, the stock addf order), the board
# sinking with the drives off, sampled without disturbing it: LinuxCNC's
# stock sampler component records the pin in the same servo thread, every
# period, into a FIFO deep enough for the whole run, and halsampler reads
# the FIFO only after the thread has stopped (no process runs beside the
# thread while it is measured). The first WARMUP periods are dropped.
# Needs the modules installed: run it under the global lock,
#   flock /tmp/hg-lcnc.lock sh -c 'make -s install && bench/hal_step_time.sh reduced-cartesian'
# Usage: bench/hal_step_time.sh MODEL [SAMPLES] [setp NAME VALUE]...
# (HG_HAL_SAMPLES=FILE also keeps the samples, in period order)
# Prints: HALTIME model=<m> <setp...> median_ns=<x> p90_ns=<y> p99_ns=<z> max_ns=<w> samples=<n> fault=<f>
. "$(dirname "$0")/../tests/hal/hal_env.sh"   # re-runs this script in its own namespaces
model=${1:-reduced-cartesian}; shift
n=${1:-2000}; shift
warm=300
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
h loadrt sampler depth=$((warm + n + 1000)) cfg=u || exit 1
h addf sampler.0 servo || exit 1         # after dynamics: this period's step time
h net step-time $X.step-time-ns sampler.0.pin.0 || exit 1
h setp $B.out-07 1
extra=""
while [ "$1" = setp ]; do
    s "$X.$2" "$3" || { echo "HALTIME setp $2 $3 refused"; exit 1; }
    extra="$extra $2=$3"; shift 3
done
s $X.estop-button 1
h start
# wait (sleeping) until the FIFO holds the run; nothing else reads HAL meanwhile
for i in $(seq 600); do
    sleep 0.5
    [ "$(g sampler.0.curr-depth)" -ge $((warm + n)) ] && break
done
h stop
out=$(mktemp)
timeout 60 halsampler -n $((warm + n)) > "$out"
if grep -q overrun "$out"; then echo "HALTIME model=$model$extra fifo overrun"; rm -f "$out"; exit 1; fi
tail -n +$((warm + 1)) "$out" | awk '{print $1}' > "$out.run"
[ -n "$HG_HAL_SAMPLES" ] && cp "$out.run" "$HG_HAL_SAMPLES"   # the samples in period order
times=$(sort -n "$out.run")
rm -f "$out" "$out.run"
got=$(echo "$times" | grep -c .)
at() { echo "$times" | sed -n "$1p"; }
med=$(at $(( (got + 1) / 2 ))); p90=$(at $(( got * 9 / 10 ))); p99=$(at $(( got * 99 / 100 ))); mx=$(at "$got")
echo "HALTIME model=$model$extra median_ns=$med p90_ns=$p90 p99_ns=$p99 max_ns=$mx samples=$got fault=$(g $X.fault)"
