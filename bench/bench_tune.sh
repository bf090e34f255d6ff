#!/bin/sh
# bench_tune.sh - issue 23's tune goal: `hexaglide tune` with every option at its
# default on a 29 s trajectory (the generated move three times over, cut at
# 29,000 periods), on 2 threads; prints tune's log and
#   BENCH tune_29s wall_s=<x> goal_s=90 periods=<search periods of both sweeps>
# BENCH_TUNE=0 skips it (it takes minutes).
cd "$(dirname "$0")/.." || exit 1
[ "${BENCH_TUNE:-1}" = 0 ] && { echo "not measured: BENCH_TUNE=0"; exit 0; }
d=build/bench
/usr/bin/python3 - "$d/traj29.txt" <<'PY' || exit 1
import sys; sys.path.insert(0, "tools")
import numpy as np, hexaglide_tune as ht
cfg = ht.read_config("configs/hexaglide.ini")
m = ht.generated_move(cfg.axes, None, "configs/hexaglide.ini")
np.savetxt(sys.argv[1], np.vstack([m, m, m])[:29000], fmt="%.9f")
PY
t0=$(date +%s.%N)
build/hexaglide tune --trajectory "$d/traj29.txt" --jobs 2 >"$d/tune29.ini" 2>"$d/tune29.log"
rc=$?
t1=$(date +%s.%N)
grep -v ': generation ' "$d/tune29.log"
[ $rc -eq 0 ] || { echo "tune exit $rc ($d/tune29.log)"; exit 1; }
periods=$(sed -n 's/.*, \([0-9]*\) servo periods run.*/\1/p' "$d/tune29.log" | awk '{ s += $1 } END { print s }')
echo "BENCH tune_29s wall_s=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') goal_s=90 periods=$periods"
