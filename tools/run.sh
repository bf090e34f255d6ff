#!/bin/sh
# run.sh - make run: the virtual Hexaglide in AXIS with its vismach 3D view
# (configs/hexaglide.ini). Installs the modules first.
#   With an X display ($DISPLAY): interactive; quit AXIS to stop.
#   Without one, or with HG_SCREENSHOT=file.png: runs AXIS under Xvfb with
#   HG_AUTOSTART=1 (AXIS homes and starts the logo program by itself,
#   configs/hexaglide_axisrc.py), waits until AXIS and the 3D view are up
#   and the machine moves, saves two screenshots 3 s apart (default
#   out/run_screenshot.png and out/run_screenshot_2.png) and shuts down.
cd "$(dirname "$0")/.." || exit 1
[ -n "$HG_NO_INSTALL" ] || make -s install || exit 1
mkdir -p out
if [ -n "$DISPLAY" ] && [ -z "$HG_SCREENSHOT" ]; then
    # a TCP display (ssh -X: localhost:10.0) is out of reach from a private
    # network namespace: run in the shared one then
    case $DISPLAY in :*) ;; *) export HG_SHARED_HAL=1 ;; esac
    exec tools/hg_linuxcnc.sh configs/hexaglide.ini
fi

shot=${HG_SCREENSHOT:-out/run_screenshot.png}
shot2=${shot%.png}_2.png
export HG_AUTOSTART=${HG_AUTOSTART-1}
wait_s=${HG_WAIT_S:-90}
# a free X display number
n=91
while [ -e /tmp/.X11-unix/X$n ] || [ -e /tmp/.X$n-lock ]; do n=$((n + 1)); done
Xvfb :$n -screen 0 1600x900x24 -nolisten tcp >out/run_xvfb.log 2>&1 &
xvfb=$!
export DISPLAY=:$n
i=0
until xwininfo -root >/dev/null 2>&1; do
    i=$((i + 1)); [ $i -gt 50 ] && { echo "run: Xvfb did not start" >&2; kill $xvfb; exit 1; }
    sleep 0.2
done
echo "run: AXIS on Xvfb $DISPLAY (log: out/run.log)"
tools/hg_linuxcnc.sh configs/hexaglide.ini >out/run.log 2>&1 &
lcnc=$!
# wait for both windows: AXIS's main window and the vismach 3D view
t=0; up=0
while [ $t -lt "$wait_s" ] && kill -0 $lcnc 2>/dev/null; do
    tree=$(xwininfo -root -tree 2>/dev/null)
    if echo "$tree" | grep -q 'Hexaglide 3D' && echo "$tree" | grep -q 'AXIS'; then up=1; break; fi
    sleep 1; t=$((t + 1))
done
rc=1
if [ $up = 1 ]; then
    sleep "${HG_SETTLE_S:-15}"   # draw, home (about 6 s), start the program
    import -window root "$shot" && sleep 3 && import -window root "$shot2" && rc=0
    echo "run: screenshots $shot $shot2"
else
    echo "run: AXIS and the 3D view did not both come up within ${wait_s}s; see out/run.log" >&2
fi
kill -TERM $lcnc 2>/dev/null
i=0
while kill -0 $lcnc 2>/dev/null && [ $i -lt 30 ]; do sleep 1; i=$((i + 1)); done
kill -9 $lcnc 2>/dev/null
kill $xvfb 2>/dev/null
exit $rc
