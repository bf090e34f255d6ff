#!/bin/sh
# fuzz.sh - bounded-time fuzzing of the kinematics, the parameter set, the
# command-line arguments, the dynamics step, the board and the record reader
# (tests/fuzz/fuzz_*.c).
# fuzz_dynamics and fuzz_board share one target's budget (RUNS/2 each).
# With clang: libFuzzer + ASan + UBSan. Without: gcc, ASan + UBSan and a
# seeded random driver (tests/fuzz/standalone_driver.c).
# Usage: tools/fuzz.sh [RUNS per target, default 1000000] [MAX_SECONDS per target, default 900]
# FUZZ_BUDGET=test (tests/check/test_fuzz, inside make test): a fixed share
# per target instead, about 5 minutes on 2 cores (measured: each target's
# inputs/s printed): 500,000 inputs for the kinematics, 300,000 for the
# record reader, 30,000 for the dynamics step (up to 16 steps each), 50,000 parameter sets (each
# runs the stability check), 15,000 CLI runs and 5,000 board input sequences
# (each steps the flexible trains' substeps); make fuzz runs the million.
# Prints "ok - ..."/"not ok - ..." per target with inputs tried and inputs per second.
cd "$(dirname "$0")/.." || exit 1
if [ "$1" = --run ]; then MODE=run; NAME=$2; else MODE=all; RUNS=${1:-1000000}; MAXT=${2:-900}; fi
OUT=build/fuzz
mkdir -p "$OUT"
CORE="$(ls src/hg_*.c src/generated/*.c) src/cli/cmd_kins.c src/cli/cmd_sim.c src/cli/cli_parse.c src/cli/cli_board.c src/cli/cli_ini.c src/cli/cli_tree.c"
INC="-Isrc -Isrc/generated -Isrc/cli -Itests/fuzz"
SAN="-fsanitize=address,undefined -fno-sanitize-recover=all"
# a fuzzer that passes the wrong type fuzzes nothing: such warnings are errors here
SAN="$SAN -Werror=incompatible-pointer-types -Werror=implicit-function-declaration -Werror=int-conversion"
if [ -n "$ENGINE" ]; then :   # set by the parent run
elif command -v clang >/dev/null && echo 'int LLVMFuzzerTestOneInput(const char*d,long n){return 0;}' |
        clang -x c -fsanitize=fuzzer - -o "$OUT/probe" 2>/dev/null; then
    ENGINE=libFuzzer
else
    ENGINE=standalone
fi
[ $MODE = all ] && echo "# fuzz engine: $ENGINE, $([ "$FUZZ_BUDGET" = test ] && echo "make test's budget" || echo "$RUNS inputs") per target, at most $MAXT s each, ${FUZZ_JOBS:-2} at a time"
JOBS=${FUZZ_JOBS:-2}

# build_core: compile the project's sources once, instrumented for fuzzing
build_core() {
    mkdir -p "$OUT/obj"
    objs=""
    for c in $CORE; do
        o="$OUT/obj/$(echo "$c" | tr '/' '_' | sed 's/\.c$/.o/')"
        # rebuild when the source or any header of src/ is newer than the object
        if [ ! -f "$o" ] || [ "$c" -nt "$o" ] || [ -n "$(find src -name '*.h' -newer "$o" | head -1)" ]; then
            if [ $ENGINE = libFuzzer ]; then
                clang -std=gnu99 -O2 -g $SAN -fsanitize=fuzzer-no-link $INC -c -o "$o" "$c" || return 1
            else
                gcc -std=gnu99 -O2 -g $SAN $INC -c -o "$o" "$c" || return 1
            fi
        fi
        objs="$objs $o"
    done
    CORE_OBJS=$objs
}

# build_target NAME: link tests/fuzz/NAME.c with the engine and sanitizers
build_target() {
    if [ $ENGINE = libFuzzer ]; then
        clang -std=gnu99 -O2 -g $SAN -fsanitize=fuzzer $INC -o "$OUT/$1" "tests/fuzz/$1.c" $CORE_OBJS -lm
    else
        gcc -std=gnu99 -O2 -g $SAN $INC -o "$OUT/$1" "tests/fuzz/$1.c" tests/fuzz/standalone_driver.c $CORE_OBJS -lm
    fi
}

# runs_for NAME: inputs for this target (the dynamics step and the board share one budget)
runs_for() {
    if [ "$FUZZ_BUDGET" = test ]; then
        case $1 in fuzz_kinematics) echo 500000 ;; fuzz_record) echo 300000 ;; fuzz_dynamics) echo 30000 ;;
            fuzz_params) echo 50000 ;; fuzz_cli) echo 15000 ;; fuzz_board) echo 5000 ;; *) echo 100000 ;; esac
    else
        case $1 in fuzz_dynamics|fuzz_board) echo $((RUNS / 2)) ;; *) echo "$RUNS" ;; esac
    fi
}

# run_target NAME: fuzz it and print one ok / not ok line
run_target() {
    name=$1
    RUNS=$(runs_for "$name")
    mkdir -p "$OUT/corpus-$name"
    # tests/fuzz/seeds/NAME: inputs that once broke a property, run first every time (read, not written)
    seeds=""; [ -d "tests/fuzz/seeds/$name" ] && seeds="$PWD/tests/fuzz/seeds/$name"
    start=$(date +%s.%N)
    if [ $ENGINE = libFuzzer ]; then
        mask=0; [ "$name" = fuzz_cli ] && mask=3   # the CLI talks; keep libFuzzer's own report
        (cd "$OUT" && "./$name" -runs="$RUNS" -max_total_time="$MAXT" -max_len=512 -seed=1 \
            -close_fd_mask=$mask -print_final_stats=1 "corpus-$name" $seeds >"$name.log" 2>&1)
        rc=$?
        runs=$(grep -a -o 'stat::number_of_executed_units: *[0-9]*' "$OUT/$name.log" | grep -o '[0-9]*$' | tail -1)
    else
        "$OUT/$name" -runs="$RUNS" 2>"$OUT/$name.err" | tail -1 >"$OUT/$name.log"
        rc=$?
        runs=$(grep -o 'Done [0-9]*' "$OUT/$name.log" | grep -o '[0-9]*')
    fi
    secs=$(echo "$(date +%s.%N) - $start" | bc)
    runs=${runs:-0}
    rate=$(echo "$runs / $secs" | bc)
    if [ $rc -eq 0 ] && [ "$runs" -ge "$RUNS" ]; then
        echo "ok - $name: $runs inputs in ${secs%.*} s ($rate inputs/s), no crash, no NaN, all refusals coded"
    elif [ $rc -eq 0 ]; then
        echo "not ok - $name: only $runs of $RUNS inputs in the $MAXT s budget ($rate inputs/s)"
    else
        echo "not ok - $name: $(cat "$OUT/$name.log" "$OUT/$name.err" 2>/dev/null | grep -a -m1 -E 'property violated|ERROR|runtime error|deadly signal') (log $OUT/$name.log; crash input in $OUT/)"
    fi
}

if [ $MODE = run ]; then run_target "$NAME"; exit 0; fi

status=0
targets=""
if ! build_core 2>"$OUT/core.build.log"; then
    echo "not ok - fuzz: building the project's sources failed: $(grep -m3 error "$OUT/core.build.log" | tr '\n' ' ')"
    exit 1
fi
for src in tests/fuzz/fuzz_*.c; do
    name=$(basename "$src" .c)
    if build_target "$name" 2>"$OUT/$name.build.log"; then
        targets="$targets $name"
    else
        echo "not ok - $name: build failed: $(head -3 "$OUT/$name.build.log" | tr '\n' ' ')"; status=1
    fi
done
export ENGINE RUNS MAXT FUZZ_BUDGET
# JOBS targets at a time (one per core)
for name in $targets; do echo "$name"; done | xargs -P "$JOBS" -I{} "$0" --run {} >"$OUT/results.txt"
cat "$OUT/results.txt"
grep -q '^not ok' "$OUT/results.txt" && status=1
exit $status
