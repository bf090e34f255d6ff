#!/bin/sh
# run_bench.sh - run every build/bench/bench_* program and summarize.
# Each program prints its own report plus machine lines
#   BENCH <name> median_us=<x> p99_us=<y> [flops=<n>] [iters=<n>]
# which are gathered into one table at the end.
cd "$(dirname "$0")/.." || exit 1
out=build/bench/results.txt
: > "$out"
for b in build/bench/bench_*; do
    [ -x "$b" ] || continue
    echo "== $(basename "$b")"
    "$b" | tee -a "$out" | grep -v '^BENCH '
done
# the default board step inside HAL (uspace, a 1 ms thread) against the same
# step hot (bench_dynamics' board_<model>), measured in this one run; needs
# the modules of this build installed (make install), else it says so
echo "== in HAL: bench/hal_step_time.sh (the default step, glue included)"
mod=motenc_hexaglide_dyns_virtual.so
inst=$(ls /usr/lib/linuxcnc/modules/$mod 2>/dev/null)
if ! command -v halrun >/dev/null 2>&1; then
    echo "not measured: LinuxCNC's halrun is not installed"
elif [ -z "$inst" ] || ! cmp -s "$inst" "build/rt/$mod"; then
    echo "not measured: the installed $mod is not this build's (run make install, then make bench)"
else
    for model in reduced-cartesian fused-cartesian; do
        line=$(bench/hal_step_time.sh "$model" 300 | grep '^HALTIME')
        echo "$line"
        med=$(echo "$line" | sed -n 's/.*median_ns=\([0-9]*\).*/\1/p')
        hot=$(sed -n "s/^BENCH board_$model median_us=\([0-9.]*\).*/\1/p" "$out")
        [ -n "$med" ] && [ -n "$hot" ] &&
            echo "BENCH hal_$model median_us=$(awk -v m="$med" 'BEGIN { printf "%.3f", m / 1000 }') in_hal_over_hot=$(awk -v m="$med" -v h="$hot" 'BEGIN { printf "%.2f", m / 1000 / h }')" | tee -a "$out"
    done
fi
echo
echo "== summary (microseconds per call on this machine; see docs/benchmarks.md)"
grep '^BENCH ' "$out" | sed 's/^BENCH //' | column -t
