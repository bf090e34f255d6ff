#!/bin/sh
# run_all.sh - run every test tier and end with "N passed, N failed, N skipped".
# Each test prints TAP-style lines "ok - what" / "not ok - what"; a line
# "ok - what # SKIP why" (TAP's skip directive) counts as a skip, never as a
# pass. A test that exits non-zero without printing "not ok" counts as one
# failure, and so does one that exits 0 without printing any line (it ran
# no check). Exit status 1 when anything failed.
#   tiers: unit (host C), generator (freshness, SymPy), engine (MuJoCo
#          cross-check), cli, hal (halrun), lcnc (HAL component tests in
#          LinuxCNC's tests/NAME/ layout, tests/lcnc/runtests),
#          linuxcnc (full stack), check (sanitizers, static analysis),
#          fmu (build/hexaglide.fmu under fmusim and its FMI API; make fmu)
# TESTS_ONLY=tier[,tier] runs a subset.
#
# Three lanes run side by side, each one test at a time: the HAL lane (hal,
# lcnc, linuxcnc: one HAL per host, and their LinuxCNC runs wait on the
# wall clock more than they compute), the offline lane (unit, generator,
# engine, cli, fmu) and the check lane (check: sanitizers, fuzzing, static
# analysis, soak), the last two CPU-bound without HAL and at nice 19, so that
# LinuxCNC's processes keep the cores they ask for. HG_TEST_LANES=serial runs
# them one after the other. Each test's lines are printed as one block when
# it ends; the counts of every lane are summed at the end.
#   run_all.sh --lane offline|check|hal   (internal) one lane, its counts into
#                                         build/test-logs/lane-NAME.counts
cd "$(dirname "$0")/.." || exit 1
LOGS=build/test-logs
mkdir -p "$LOGS"
SKIP_RE='^ok( |$).*#[[:space:]]*[Ss][Kk][Ii][Pp]([^[:alnum:]]|$)'
OFFLINE_TIERS="unit generator engine cli fmu"
CHECK_TIERS="check"
HAL_TIERS="hal lcnc linuxcnc"
LANES="offline check hal"

run_one() { # counts-file name command...
    counts=$1 name=$2; shift 2
    log=$LOGS/$(echo "$name" | tr '/ ' '__').log
    start=$(date +%s)
    "$@" >"$log" 2>&1
    rc=$?
    s=$(grep -cE "$SKIP_RE" "$log")
    p=$(( $(grep -c '^ok\( \|$\)' "$log") - s )); f=$(grep -c '^not ok\( \|$\)' "$log")
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; echo "not ok - $name exited with $rc" >>"$log"; fi
    if [ "$rc" -eq 0 ] && [ "$p" -eq 0 ] && [ "$f" -eq 0 ] && [ "$s" -eq 0 ]; then
        f=1; echo "not ok - $name ran no check (exit 0 without an ok or not ok line)" >>"$log"
    fi
    secs=$(( $(date +%s) - start ))
    block=$(
        if [ "$f" -gt 0 ]; then
            echo "FAIL $name ($p ok, $f not ok, $s skipped, ${secs}s) - log: $log"
            grep '^not ok' "$log" | head -20 | sed 's/^/    /'
            tail -5 "$log" | sed 's/^/    | /'
        elif [ "$p" -eq 0 ]; then
            echo "SKIP $name ($s skipped, ${secs}s)"
        else
            echo "PASS $name ($p checks$( [ "$s" -gt 0 ] && echo ", $s skipped"), ${secs}s)"
        fi
        [ "$s" -gt 0 ] && grep -E "$SKIP_RE" "$log" | head -5 | sed 's/^/    /'
    )
    printf '%s\n' "$block"               # one write: the other lane's lines do not split it
    echo "$p $f $s $name" >>"$counts"
    return 0
}
want() { [ -z "$TESTS_ONLY" ] || echo ",$TESTS_ONLY," | grep -q ",$1,"; }

# run_tiers COUNTS TIER...: every test of the wanted tiers, in order
run_tiers() {
    counts=$1; shift
    : >"$counts"
    for tier in "$@"; do
        want $tier || continue
        if [ $tier = unit ]; then
            # every tests/unit/test_*.c must have been built (make host): a missing binary fails
            for c in tests/unit/test_*.c; do
                [ -e "$c" ] || continue
                t=build/tests/$(basename "$c" .c)
                if [ -x "$t" ]; then run_one "$counts" "unit/$(basename "$t")" "$t"
                else run_one "$counts" "unit/$(basename "$t")" sh -c "echo 'not ok - $t is not built (make host)'; exit 1"; fi
            done
            continue
        fi
        if [ $tier = lcnc ]; then run_one "$counts" lcnc/runtests tests/lcnc/runtests; continue; fi
        for t in tests/$tier/test_*; do
            [ -x "$t" ] || continue
            run_one "$counts" "$tier/$(basename "$t")" "$t"
        done
    done
}

if [ "$1" = --lane ]; then
    case $2 in
    offline) run_tiers "$LOGS/lane-offline.counts" $OFFLINE_TIERS ;;
    check) run_tiers "$LOGS/lane-check.counts" $CHECK_TIERS ;;
    hal) run_tiers "$LOGS/lane-hal.counts" $HAL_TIERS ;;
    *) echo "run_all.sh: --lane offline|check|hal"; exit 2 ;;
    esac
    echo "0 0 0 :done" >>"$LOGS/lane-$2.counts"   # the lane ran to its end
    exit 0
fi

for lane in $LANES; do rm -f "$LOGS/lane-$lane.counts"; done
if [ "$HG_TEST_LANES" = serial ]; then
    for lane in $LANES; do sh "$0" --lane $lane; done
else
    nice -n 19 sh "$0" --lane offline &
    offline=$!
    nice -n 19 sh "$0" --lane check &
    check=$!
    sh "$0" --lane hal
    wait $offline $check
fi
# every lane's counts, "passed failed skipped name" per test; a lane that did
# not reach its end (killed, crashed) is one failure
for lane in $LANES; do
    grep -q ' :done$' "$LOGS/lane-$lane.counts" 2>/dev/null && continue
    echo "not ok - the $lane lane of the tests did not run to its end"
    echo "0 1 0 lane-$lane" >>"$LOGS/lane-$lane.counts"
done
for lane in $LANES; do cat "$LOGS/lane-$lane.counts"; done | awk '
    { p += $1; f += $2; s += $3; if ($2 > 0) failed = failed " " $4 }
    END {
        if (failed != "") print "failed:" failed
        printf "%d passed, %d failed, %d skipped\n", p, f, s
        exit (f > 0 ? 1 : 0)
    }'
