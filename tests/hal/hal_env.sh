# hal_env.sh - source this first in every HAL test: uspace HAL as root.
# - Re-runs the test in its own SysV IPC and PID namespaces (`unshare`, root):
#   HAL lives in SysV shared memory and halrun looks for a running rtapi_app
#   with ps, so a LinuxCNC or another test elsewhere on the machine cannot
#   see or stop this session. Without unshare, HAL
#   sessions are serialized with a lock instead (one uspace HAL per host).
# - Sets RTAPI_UID and RTAPI_FIFO_PATH (the path of rtapi_app's control
#   SOCKET, not a directory: a directory there makes rtapi_app hang).
# - Clears leftovers before and after (halrun -U).
if [ -z "$HG_HAL_ISOLATED" ] && command -v unshare >/dev/null 2>&1 &&
   unshare --ipc --pid --fork --mount-proc true 2>/dev/null; then
    HG_HAL_ISOLATED=1 exec unshare --ipc --pid --fork --mount-proc "$0" "$@"
fi
export RTAPI_UID=${RTAPI_UID:-65534}
export RTAPI_FIFO_PATH=${RTAPI_FIFO_PATH:-/tmp/hexaglide-rtapi-$(basename "$0")-$$.sock}
if [ -d "$RTAPI_FIFO_PATH" ]; then
    echo "not ok - RTAPI_FIFO_PATH=$RTAPI_FIFO_PATH is a directory; it must be a socket path"
    exit 1
fi
if [ -z "$HG_HAL_ISOLATED" ]; then
    exec 9>"${HAL_LOCK:-/tmp/hexaglide-hal.lock}"
    flock -w 900 9 || { echo "not ok - could not get the HAL lock in 15 min"; exit 1; }
fi
hal_cleanup() { timeout 20 halrun -U >/dev/null 2>&1; rm -f "$RTAPI_FIFO_PATH"; return 0; }
hal_cleanup
trap hal_cleanup EXIT
# TAP helpers
ok()     { echo "ok - $*"; }
not_ok() { echo "not ok - $*"; }
check()  { # check "description" command...
    d=$1; shift
    if "$@"; then ok "$d"; else not_ok "$d"; fi
}
