#!/bin/sh
# run_all.sh - run every test tier and end with "N passed, N failed".
# Each test prints TAP-style lines "ok - what" / "not ok - what"; a test
# that exits non-zero without printing "not ok" counts as one failure.
#   tiers: unit (host C), generator (freshness, SymPy), engine (MuJoCo
#          cross-check), cli, hal (halrun), lcnc (HAL component tests in
#          LinuxCNC's tests/NAME/ layout, tests/lcnc/runtests),
#          linuxcnc (full stack), check (sanitizers, static analysis)
# TESTS_ONLY=tier[,tier] runs a subset.
cd "$(dirname "$0")/.." || exit 1
mkdir -p build/test-logs
passed=0; failed=0; failures=""
run_one() { # name command...
    name=$1; shift
    log=build/test-logs/$(echo "$name" | tr '/ ' '__').log
    start=$(date +%s)
    "$@" >"$log" 2>&1
    rc=$?
    p=$(grep -c '^ok ' "$log"); f=$(grep -c '^not ok ' "$log")
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; echo "not ok - $name exited with $rc" >>"$log"; fi
    if [ "$rc" -eq 0 ] && [ "$p" -eq 0 ] && [ "$f" -eq 0 ]; then p=1; fi
    passed=$((passed + p)); failed=$((failed + f))
    secs=$(( $(date +%s) - start ))
    if [ "$f" -gt 0 ]; then
        echo "FAIL $name ($p ok, $f not ok, ${secs}s) - log: $log"
        grep '^not ok ' "$log" | head -20 | sed 's/^/    /'
        tail -5 "$log" | sed 's/^/    | /'
        failures="$failures $name"
    else
        echo "PASS $name ($p checks, ${secs}s)"
    fi
}
want() { [ -z "$TESTS_ONLY" ] || echo ",$TESTS_ONLY," | grep -q ",$1,"; }

if want unit; then
    for t in build/tests/test_*; do [ -x "$t" ] && run_one "unit/$(basename "$t")" "$t"; done
fi
for tier in generator engine cli hal lcnc linuxcnc check; do
    want $tier || continue
    if [ $tier = lcnc ]; then run_one lcnc/runtests tests/lcnc/runtests; continue; fi
    for t in tests/$tier/test_*; do
        [ -x "$t" ] || continue
        run_one "$tier/$(basename "$t")" "$t"
    done
done
[ -n "$failures" ] && echo "failed:$failures"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
