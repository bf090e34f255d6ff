# lib.sh - shared by tests/linuxcnc/test_*: run the Hexaglide LinuxCNC
# config headless (tools/hg_linuxcnc.sh) with one scenario of
# tools/headless/hexaglide_headless.py, bounded in time. Outputs go to out/tests/.
cd "$(dirname "$0")/../.." || exit 1
ROOT=$PWD
OUT=$ROOT/out/tests
mkdir -p "$OUT"
export HG_OUT=$OUT
# hg_scenario TAG SCENARIO PROGRAM TIMEOUT_S [VAR=value...]
# Runs LinuxCNC; sets LCNC_RC; the front end writes $OUT/TAG.json (+ .csv).
# HG_INI (shell variable): another ini than the headless one; the files
# beside it take the place of configs/'s (tools/hg_linuxcnc.sh).
hg_scenario() {
    tag=$1 scen=$2 prog=$3 tmo=$4; shift 4
    rm -f "$OUT/$tag.json" "$OUT/$tag.csv"
    env HG_TAG="$tag" HG_SCENARIO="$scen" HG_PROGRAM="$ROOT/$prog" "$@" \
        timeout -k 20 "$tmo" tools/hg_linuxcnc.sh "${HG_INI:-tools/headless/hexaglide_headless.ini}" \
        >"$OUT/$tag.log" 2>&1
    LCNC_RC=$?
    echo "# LinuxCNC exit code $LCNC_RC (log: out/tests/$tag.log)"
    grep -a '^hexaglide_headless' "$OUT/$tag.log" | sed 's/^/# /'
}
# hg_no_crash TAG: one TAP line, no crash signs in out/tests/TAG.log
hg_no_crash() {
    if grep -a -i -E 'segmentation|core dumped|traceback' "$OUT/$1.log" >/dev/null; then
        echo "not ok - crash signs in out/tests/$1.log"
    else
        echo "ok - no crash signs in out/tests/$1.log"
    fi
}
