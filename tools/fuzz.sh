#!/bin/sh
# fuzz.sh - bounded-time fuzzing of the kinematics, the parameter set, the
# command-line arguments and the dynamics step (tests/fuzz/fuzz_*.c).
# With clang: libFuzzer + ASan + UBSan. Without: gcc, ASan + UBSan and a
# seeded random driver (tests/fuzz/standalone_driver.c).
# Usage: tools/fuzz.sh [RUNS per target, default 1000000] [MAX_SECONDS per target, default 900]
# Prints "ok - ..."/"not ok - ..." per target with inputs tried and inputs per second.
cd "$(dirname "$0")/.." || exit 1
RUNS=${1:-1000000}
MAXT=${2:-900}
OUT=build/fuzz
mkdir -p "$OUT"
CORE="$(ls src/hg_*.c src/generated/*.c) src/cli/cmd_kins.c src/cli/cmd_sim.c src/cli/cli_parse.c"
INC="-Isrc -Isrc/generated -Isrc/cli -Itests/fuzz"
SAN="-fsanitize=address,undefined -fno-sanitize-recover=all"
if command -v clang >/dev/null && echo 'int LLVMFuzzerTestOneInput(const char*d,long n){return 0;}' |
        clang -x c -fsanitize=fuzzer - -o "$OUT/probe" 2>/dev/null; then
    ENGINE=libFuzzer
else
    ENGINE=standalone
fi
echo "# fuzz engine: $ENGINE, $RUNS inputs per target, at most $MAXT s each"
status=0
for src in tests/fuzz/fuzz_*.c; do
    name=$(basename "$src" .c)
    bin="$OUT/$name"
    if [ $ENGINE = libFuzzer ]; then
        clang -std=gnu99 -O1 -g $SAN -fsanitize=fuzzer $INC -o "$bin" "$src" $CORE -lm 2>"$OUT/$name.build.log"
    else
        gcc -std=gnu99 -O1 -g $SAN $INC -o "$bin" "$src" tests/fuzz/standalone_driver.c $CORE -lm 2>"$OUT/$name.build.log"
    fi
    if [ $? -ne 0 ]; then
        echo "not ok - $name: build failed: $(head -3 "$OUT/$name.build.log" | tr '\n' ' ')"; status=1; continue
    fi
    mkdir -p "$OUT/corpus-$name"
    start=$(date +%s.%N)
    if [ $ENGINE = libFuzzer ]; then
        mask=0; [ "$name" = fuzz_cli ] && mask=3   # the CLI talks; keep libFuzzer's own report
        (cd "$OUT" && "./$name" -runs="$RUNS" -max_total_time="$MAXT" -max_len=512 -seed=1 -close_fd_mask=$mask \
            -print_final_stats=1 "corpus-$name" >"$name.log" 2>&1)
    else
        "$bin" -runs="$RUNS" 2>/dev/null | tail -1 >"$OUT/$name.log" 
    fi
    rc=$?
    secs=$(echo "$(date +%s.%N) - $start" | bc)
    if [ $ENGINE = libFuzzer ]; then
        runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$OUT/$name.log" | grep -o '[0-9]*$')
    else
        runs=$(grep -o 'Done [0-9]*' "$OUT/$name.log" | grep -o '[0-9]*')
    fi
    runs=${runs:-0}
    rate=$(echo "$runs / $secs" | bc)
    if [ $rc -eq 0 ] && [ "$runs" -ge "$RUNS" ]; then
        echo "ok - $name: $runs inputs in ${secs%.*} s ($rate inputs/s), no crash, no NaN, all refusals coded"
    elif [ $rc -eq 0 ]; then
        echo "not ok - $name: only $runs of $RUNS inputs in the $MAXT s budget ($rate inputs/s)"; status=1
    else
        echo "not ok - $name: $(grep -m1 -E 'property violated|ERROR|runtime error|deadly signal' "$OUT/$name.log") (log $OUT/$name.log; crash input in $OUT/)"; status=1
    fi
done
exit $status
