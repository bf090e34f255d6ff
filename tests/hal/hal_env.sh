# hal_env.sh - source this in every HAL/LinuxCNC test: uspace HAL as root.
# Sets RTAPI_UID and RTAPI_FIFO_PATH (the path of rtapi_app's control
# SOCKET, not a directory), serializes HAL sessions with a lock (there is
# one uspace HAL per machine), and clears leftovers before and after.
export RTAPI_UID=${RTAPI_UID:-65534}
export RTAPI_FIFO_PATH=${RTAPI_FIFO_PATH:-/tmp/hexaglide-rtapi.sock}
if [ -d "$RTAPI_FIFO_PATH" ]; then
    echo "hal_env.sh: RTAPI_FIFO_PATH=$RTAPI_FIFO_PATH is a directory; it must be a socket path" >&2
    exit 1
fi
HAL_LOCK=${HAL_LOCK:-/tmp/hexaglide-hal.lock}
exec 9>"$HAL_LOCK"
flock -w 900 9 || { echo "not ok - could not get the HAL lock $HAL_LOCK in 15 min"; exit 1; }
hal_cleanup() { timeout 20 halrun -U >/dev/null 2>&1; return 0; }
hal_cleanup
trap hal_cleanup EXIT
# TAP helpers
ok()     { echo "ok - $*"; }
not_ok() { echo "not ok - $*"; }
check()  { # check "description" command...
    d=$1; shift
    if "$@"; then ok "$d"; else not_ok "$d"; fi
}
