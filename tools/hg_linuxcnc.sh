#!/bin/sh
# hg_linuxcnc.sh - start LinuxCNC with a Hexaglide config, as root without a
# realtime kernel, in its own IPC and network namespaces (HAL and NML live in
# SysV shared memory, rtapi_app finds its master on an abstract unix socket)
# so that other HAL sessions on the same host (tests,
# halrun -U) cannot see or stop it, and it cannot stop them.
# Usage: tools/hg_linuxcnc.sh [ini]    (default tools/headless/hexaglide_headless.ini)
# Environment HG_* is passed on to the headless front end
# (tools/headless/hexaglide_headless.py). Exit code: LinuxCNC's, i.e. the display's.
# LinuxCNC runs from a run directory (HG_RUN_DIR, default out/run/NAME-PID,
# removed afterwards unless HG_KEEP_RUN=1) whose configs/ holds symbolic
# links to configs/*, tools/headless/* and the files beside the given ini
# (those win), and whose tools/ links to the repository's tools/ (so a path
# like ../tools/hg_record.tcl in the ini means the same as from configs/);
# what a run writes into its config directory (the .var parameter file,
# INI.expanded from #INCLUDE) lands there and configs/ stays as in git.
# HG_SHARED_HAL=1: no namespaces, so halcmd/halscope started from another
# terminal can attach to this session (docs/linuxcnc.md).
if [ -z "$HG_SHARED_HAL" ] && [ -z "$HG_IN_IPC_NS" ] && [ "$(id -u)" = 0 ] && unshare --ipc --net true 2>/dev/null; then
    HG_IN_IPC_NS=1 exec unshare --ipc --net "$0" "$@"
fi
cd "$(dirname "$0")/.." || exit 1
ROOT=$PWD
ini=${1:-tools/headless/hexaglide_headless.ini}
case $ini in /*) ;; *) ini=$PWD/$ini ;; esac
[ -f "$ini" ] || { echo "hg_linuxcnc.sh: no such config $ini" >&2; exit 2; }
export HG_OUT=${HG_OUT:-$ROOT/out}
base=${HG_RUN_DIR:-$ROOT/out/run/$(basename "$ini" .ini)-$$}
run=$base/configs
rm -rf "$base" && mkdir -p "$run" && ln -sfn "$ROOT/tools" "$base/tools" ||
    { echo "hg_linuxcnc.sh: cannot create run directory $base" >&2; exit 2; }
for d in "$ROOT/configs" "$ROOT/tools/headless" "$(dirname "$ini")"; do
    for f in "$d"/*; do
        case $f in *.var|*.expanded|*.var.bak|*"*") continue ;; esac
        ln -sfn "$f" "$run/$(basename "$f")"
    done
done
ini=$run/$(basename "$ini")
export RTAPI_UID=${RTAPI_UID:-65534}
# rtapi_app's master socket (a socket file, not a directory); shared
# sessions use a fixed one that other terminals can name
if [ -n "$HG_IN_IPC_NS" ]; then
    # HG_RTAPI_FIFO_PATH: a caller in the same namespace (tests/linuxcnc/test_halscope) names it
    export RTAPI_FIFO_PATH=${HG_RTAPI_FIFO_PATH:-/tmp/hexaglide-lcnc-$$.sock}
else
    export RTAPI_FIFO_PATH=${RTAPI_FIFO_PATH:-/tmp/hexaglide-lcnc.sock}
fi
cd "$(dirname "$ini")" || exit 1
# a fresh namespace has no leftovers; without one, clear a previous session's
# (only when no other realtime session is running: it would be stopped too)
if [ -z "$HG_IN_IPC_NS" ] && ! pgrep -x rtapi_app >/dev/null; then
    timeout 30 halrun -U >/dev/null 2>&1
fi
# a lock left by a LinuxCNC that was killed hard would make linuxcnc try
# to stop that (gone) session and wait for it
if [ -f /tmp/linuxcnc.lock ] && ! pgrep -f '^/bin/bash /usr/bin/linuxcnc' >/dev/null; then
    rm -f /tmp/linuxcnc.lock
fi
# -r: LinuxCNC's messages stay on stdout/stderr even without a tty.
# On TERM/INT (e.g. from timeout) let LinuxCNC shut down in order.
linuxcnc -r "$ini" </dev/null &
pid=$!
trap 'kill -TERM $pid 2>/dev/null' TERM INT
wait $pid
rc=$?
if kill -0 $pid 2>/dev/null; then wait $pid; rc=$?; fi
rm -f "$RTAPI_FIFO_PATH"
[ -n "$HG_KEEP_RUN" ] || [ -n "$HG_RUN_DIR" ] || rm -rf "$base"
exit $rc
