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
echo
echo "== summary (microseconds per call on this machine; see docs/benchmarks.md)"
grep '^BENCH ' "$out" | sed 's/^BENCH //' | column -t
