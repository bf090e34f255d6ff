#!/bin/sh
# run_bench.sh - run every build/bench/bench_* program and summarize.
# Each program prints its own report plus machine lines
#   BENCH <name> median_us=<x> p99_us=<y> [flops=<n>] [iters=<n>]
# which are gathered into one table at the end.
cd "$(dirname "$0")/.." || exit 1
out=build/bench/results.txt
: > "$out"
failed=""
for b in build/bench/bench_*; do
    [ -x "$b" ] || continue
    echo "== $(basename "$b")"
    echo "exit (none)" >"$out.rc"
    { "$b"; echo "exit $?" >"$out.rc"; } | tee -a "$out" | grep -v '^BENCH '
    [ "$(cat "$out.rc")" = "exit 0" ] || failed="$failed $(basename "$b") ($(cat "$out.rc"))"
done
rm -f "$out.rc"
# the default board step inside HAL (uspace, a 1 ms thread; sampled in the
# thread by LinuxCNC's sampler, read by halsampler after the thread stops)
# against the same step hot (bench_dynamics board MODEL) measured just
# before and just after it, so that both see the same load on the cores;
# needs the modules of this build installed (make install), else it says so
echo "== in HAL: bench/hal_step_time.sh (the default step, glue included)"
mod=motenc_hexaglide_dyns_virtual.so
inst=$(ls /usr/lib/linuxcnc/modules/$mod 2>/dev/null)
if ! command -v halrun >/dev/null 2>&1; then
    echo "not measured: LinuxCNC's halrun is not installed"
elif [ -z "$inst" ] || ! cmp -s "$inst" "build/rt/$mod"; then
    echo "not measured: the installed $mod is not this build's (run make install, then make bench)"
else
    # HAL runs under the global LinuxCNC lock (one uspace HAL per host); a
    # caller that holds it already sets HG_LCNC_LOCKED=1
    lock="flock -w 1800 /tmp/hg-lcnc.lock"
    [ -n "$HG_LCNC_LOCKED" ] && lock=""
    echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg) (other work on the cores moves both numbers)"
    for model in reduced-cartesian fused-cartesian; do
        hot1=$(build/bench/bench_dynamics board $model | sed -n 's/^BENCH board_[a-z-]* median_us=\([0-9.]*\).*/\1/p')
        line=$($lock sh -c "cmp -s '$inst' 'build/rt/$mod' && bench/hal_step_time.sh $model 2000 ||
                             echo 'HALTIME the installed module changed meanwhile: not measured'" | grep '^HALTIME')
        hot2=$(build/bench/bench_dynamics board $model | sed -n 's/^BENCH board_[a-z-]* median_us=\([0-9.]*\).*/\1/p')
        echo "$line (hot board step before and after: $hot1, $hot2 us)"
        med=$(echo "$line" | sed -n 's/.*median_ns=\([0-9]*\).*/\1/p')
        p99=$(echo "$line" | sed -n 's/.*p99_ns=\([0-9]*\).*/\1/p')
        [ -n "$med" ] && [ -n "$hot1" ] && [ -n "$hot2" ] &&
            echo "BENCH hal_$model median_us=$(awk -v m="$med" 'BEGIN { printf "%.3f", m / 1000 }') p99_us=$(awk -v m="$p99" 'BEGIN { printf "%.3f", m / 1000 }') hot_us=$(awk -v a="$hot1" -v b="$hot2" 'BEGIN { printf "%.3f", (a + b) / 2 }') in_hal_over_hot=$(awk -v m="$med" -v a="$hot1" -v b="$hot2" 'BEGIN { printf "%.2f", m / 1000 / ((a + b) / 2) }')" | tee -a "$out"
    done
fi
echo "== tune on a 29 s trajectory: bench/bench_tune.sh (BENCH_TUNE=0 skips it)"
{ bench/bench_tune.sh; echo "exit $?" >"$out.rc"; } | tee -a "$out" | grep -v '^BENCH '
[ "$(cat "$out.rc")" = "exit 0" ] || failed="$failed bench_tune.sh ($(cat "$out.rc"))"
rm -f "$out.rc"
echo
echo "== summary (microseconds per call on this machine; see docs/benchmarks.md)"
grep '^BENCH ' "$out" | sed 's/^BENCH //' | column -t
if [ -n "$failed" ]; then
    echo "run_bench.sh: failed:$failed (their reports above say what failed)"
    exit 1
fi
