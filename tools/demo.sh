#!/bin/sh
# demo.sh - make demo: the virtual Hexaglide machining its logo, headless.
# Installs the modules, starts LinuxCNC with tools/headless/hexaglide_headless.ini
# (no X display), resets estop, homes all six joints (home switch + encoder
# index), runs configs/nc_files/hexaglide_logo.ngc (X Y Z A B C), samples the
# servo thread, writes out/demo.{csv,json}, plots out/demo_*.png and prints a
# summary. Exit code: LinuxCNC's verdict (0 = program ran without error).
cd "$(dirname "$0")/.." || exit 1
[ -n "$HG_NO_INSTALL" ] || make -s install || exit 1
mkdir -p out
echo "demo: starting LinuxCNC headless (log: out/demo.log)"
HG_SCENARIO=run HG_TAG=demo HG_OUT=$PWD/out \
HG_PROGRAM=$PWD/configs/nc_files/hexaglide_logo.ngc \
    timeout 600 tools/hg_linuxcnc.sh tools/headless/hexaglide_headless.ini >out/demo.log 2>&1
rc=$?
grep -a '^hexaglide_headless' out/demo.log | sed 's/^/  /'
if [ -s out/demo.csv ]; then
    /usr/bin/python3 tools/plot_run.py out/demo.csv out || rc=${rc:-1}
fi
if [ "$rc" -eq 0 ]; then
    echo "demo: LinuxCNC ran the program: ok"
else
    echo "demo: FAILED (exit $rc); see out/demo.log and out/demo.json" >&2
fi
exit $rc
