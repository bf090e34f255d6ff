#!/bin/sh
# profile_step.sh [--baseline] [PERIODS] - where the default step's time
# goes: callgrind instruction counts (repeatable, unlike wall time on a
# shared VM) of bench/profile_step.c's two workloads, hg_step alone under
# the servo motion and the whole board step, by stage
# (bench/profile_stages.py). --baseline profiles commit d20d9e5's code
# instead (bench/baseline.sh builds it from git into build/baseline).
# PERIODS profiled steps (default 10000) after 2000 warm-up ones; then
# (today only) the offline closed loop per period (bench/profile_loop.c).
# Needs valgrind (make profile installs it).
cd "$(dirname "$0")/.." || exit 1
tree=today; bin=build/bench/profile_step
if [ "$1" = --baseline ]; then
    tree=d20d9e5; shift
    flags="-std=gnu99 -O2 -g -ffp-contract=off -fno-builtin-sin -fno-builtin-cos -fno-builtin-sincos $HOST_ARCH"
    bench/baseline.sh build/baseline "${CC:-gcc}" $flags || exit 1
    bin=build/baseline/profile_step
    "${CC:-gcc}" $flags -Ibuild/baseline/src -Ibuild/baseline/src/generated -o "$bin" bench/profile_step.c \
        $(ls build/baseline/obj/*.o | grep -v engine_shim) -lm || exit 1
else
    make -s "$bin" || exit 1
fi
n=${1:-10000}
command -v valgrind >/dev/null || { echo "profile_step.sh: valgrind is not installed (make profile installs it)"; exit 1; }
for mode in step board; do
    root=profiled_step; [ $mode = board ] && root=profiled_board
    out=build/bench/callgrind.$tree.$mode
    mkdir -p build/bench
    echo "== $tree: $mode (callgrind --toggle-collect=$root: hg_step or hg_board_step under the servo motion)"
    valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect=$root --separate-callers=12 \
        --compress-strings=no --compress-pos=no "$bin" $mode "$n" 2>/dev/null || exit 1
    /usr/bin/python3 bench/profile_stages.py "$out" "$n" | sed "s/^BENCH profile_board_step/BENCH profile_${tree}_$mode/"
done
[ $tree = today ] || exit 0
# the offline closed loop (hg_loop in hg_batch_run: pids and board), per period (bench/profile_loop.c)
make -s build/bench/profile_loop || exit 1
for w in "flexible 2000 0" "flexible_tool 2000 0" "rigid 2000 0" "flexible 2000 1500" "flexible_rk4 2000 0" \
    "flexible_rk4 2000 1500"; do
    set -- $w
    out=build/bench/callgrind.loop.$1.$3
    echo "== today: loop $1, 2 runs of $2 periods after $3 at rest (callgrind --toggle-collect=hg_loop_run_stop)"
    valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect=hg_loop_run_stop \
        build/bench/profile_loop "$1" "$2" "$3" 2>/dev/null || exit 1
    awk -v w="$1_$3" -v n=$((2 * ($2 + $3))) '/^summary:/ { printf "BENCH profile_loop_%s instr_per_period=%d\n", w, $2 / n }' "$out"
done
