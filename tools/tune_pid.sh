#!/bin/sh
# tune_pid.sh - the PID tuning steps of docs/linuxcnc.md, measured on the
# virtual machine: runs configs/nc_files/hexaglide_short.ngc once per gain
# set (the same gains on all six joints, set with halcmd over the INI's) and
# prints the max |joint.N.f-error| over the program and the max PID output.
# Usage: tools/tune_pid.sh ["P I D FF1 FF2" ...]   (default: the documented steps)
cd "$(dirname "$0")/.." || exit 1
mkdir -p out/tune
[ $# -gt 0 ] || set -- "0.53 0 0 0 0" "5 0 0.04 0 0" "5 100 0.04 0 0" \
                       "5 100 0.04 0.0221 0" "5 100 0.04 0.0221 0.00023" \
                       "20 400 0.1 0.0221 0.00023"
printf '%-34s %10s %10s %8s\n' "P I D FF1 FF2" "max_ferr_mm" "end_ferr_mm" "max_V"
for g in "$@"; do
    set -- $g
    setp=""
    for j in 0 1 2 3 4 5; do
        setp="$setp;pid.$j.Pgain $1;pid.$j.Igain $2;pid.$j.Dgain $3;pid.$j.FF1 $4;pid.$j.FF2 $5"
    done
    tag=tune_$(echo "$g" | tr ' .' '_p')
    HG_SETP="$setp" HG_SCENARIO=run HG_TAG=$tag HG_OUT=$PWD/out/tune \
    HG_PROGRAM=$PWD/configs/nc_files/hexaglide_short.ngc \
        timeout -k 20 300 tools/hg_linuxcnc.sh >out/tune/$tag.log 2>&1
    /usr/bin/python3 - "out/tune/$tag.csv" "$g" <<'PY'
import sys
import numpy as np
path, g = sys.argv[1], sys.argv[2]
try:
    names = open(path).readline().strip().split(",")
    d = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
except Exception as ex:
    print("%-34s failed: %s" % (g, ex)); sys.exit(0)
col = lambda n: d[:, names.index(n)]
run = col("halui.program.is-running") > 0.5
if not run.any():
    print("%-34s program did not run (see the .log: e.g. following-error trip while homing)" % g)
    sys.exit(0)
fe = max(np.abs(col("joint.%d.f-error" % j)[run]).max() for j in range(6))
end = max(abs(col("joint.%d.f-error" % j)[run][-1]) for j in range(6))
v = max(np.abs(col("pid.%d.output" % j)[run]).max() for j in range(6))
print("%-34s %10.4f %10.4f %8.2f" % (g, fe, end, v))
PY
done
