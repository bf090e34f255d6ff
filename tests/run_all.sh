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
cd "$(dirname "$0")/.." || exit 1
mkdir -p build/test-logs
passed=0; failed=0; skipped=0; failures=""
SKIP_RE='^ok( |$).*#[[:space:]]*[Ss][Kk][Ii][Pp]([^[:alnum:]]|$)'
run_one() { # name command...
    name=$1; shift
    log=build/test-logs/$(echo "$name" | tr '/ ' '__').log
    start=$(date +%s)
    "$@" >"$log" 2>&1
    rc=$?
    s=$(grep -cE "$SKIP_RE" "$log")
    p=$(( $(grep -c '^ok\( \|$\)' "$log") - s )); f=$(grep -c '^not ok\( \|$\)' "$log")
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; echo "not ok - $name exited with $rc" >>"$log"; fi
    if [ "$rc" -eq 0 ] && [ "$p" -eq 0 ] && [ "$f" -eq 0 ] && [ "$s" -eq 0 ]; then
        f=1; echo "not ok - $name ran no check (exit 0 without an ok or not ok line)" >>"$log"
    fi
    passed=$((passed + p)); failed=$((failed + f)); skipped=$((skipped + s))
    secs=$(( $(date +%s) - start ))
    if [ "$f" -gt 0 ]; then
        echo "FAIL $name ($p ok, $f not ok, $s skipped, ${secs}s) - log: $log"
        grep '^not ok' "$log" | head -20 | sed 's/^/    /'
        tail -5 "$log" | sed 's/^/    | /'
        failures="$failures $name"
    elif [ "$p" -eq 0 ]; then
        echo "SKIP $name ($s skipped, ${secs}s)"
    else
        echo "PASS $name ($p checks$( [ "$s" -gt 0 ] && echo ", $s skipped"), ${secs}s)"
    fi
    [ "$s" -gt 0 ] && grep -E "$SKIP_RE" "$log" | head -5 | sed 's/^/    /'
    return 0
}
want() { [ -z "$TESTS_ONLY" ] || echo ",$TESTS_ONLY," | grep -q ",$1,"; }

if want unit; then
    # every tests/unit/test_*.c must have been built (make host): a missing binary fails
    for c in tests/unit/test_*.c; do
        [ -e "$c" ] || continue
        t=build/tests/$(basename "$c" .c)
        if [ -x "$t" ]; then run_one "unit/$(basename "$t")" "$t"
        else run_one "unit/$(basename "$t")" sh -c "echo 'not ok - $t is not built (make host)'; exit 1"; fi
    done
fi
for tier in generator engine cli hal lcnc linuxcnc check fmu; do
    want $tier || continue
    if [ $tier = lcnc ]; then run_one lcnc/runtests tests/lcnc/runtests; continue; fi
    for t in tests/$tier/test_*; do
        [ -x "$t" ] || continue
        run_one "$tier/$(basename "$t")" "$t"
    done
done
[ -n "$failures" ] && echo "failed:$failures"
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
