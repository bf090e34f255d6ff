# hal_env.sh - source this in every HAL/LinuxCNC test: uspace HAL as root.
# Sets RTAPI_UID / RTAPI_FIFO_PATH, clears leftovers before and after.
export RTAPI_UID=${RTAPI_UID:-65534}
export RTAPI_FIFO_PATH=${RTAPI_FIFO_PATH:-/tmp/hexaglide-rtapi-fifo}
mkdir -p "$RTAPI_FIFO_PATH" 2>/dev/null
chmod 777 "$RTAPI_FIFO_PATH" 2>/dev/null
hal_cleanup() { halrun -U >/dev/null 2>&1; return 0; }
hal_cleanup
trap hal_cleanup EXIT
# tap helpers
ok()     { echo "ok - $*"; }
not_ok() { echo "not ok - $*"; }
check()  { # check "description" command...
    d=$1; shift
    if "$@"; then ok "$d"; else not_ok "$d"; fi
}
