# test_motenc_common.sh - sourced by tests/hal/test_motenc_*; not a test
# itself (no exec bit). Starts one HAL session with the virtual MOTENC board
# in a 1 ms servo thread in the order docs/driver.md gives, and offers
# small helpers: h (halcmd), g (getp), snapshot (stop the thread, read,
# restart), wait_pin, approx.
# hal_env.sh puts each test in its own IPC namespace (see there).
. "$(dirname "$0")/hal_env.sh"
REALTIME=/usr/lib/linuxcnc/realtime
B=motenc.0
X=motenc-hexaglide.0

h() { halcmd "$@"; }
g() { halcmd getp "$1"; }
s() { halcmd setp "$1" "$2"; }

# start_board [period_ns] [module args...]: threads + module + functions, running
start_board() {
    period=${1:-1000000}; shift 2>/dev/null
    $REALTIME start >/dev/null 2>&1 || { not_ok "realtime start"; exit 1; }
    h loadrt threads name1=servo period1="$period" || { not_ok "loadrt threads"; exit 1; }
    h loadrt motenc_hexaglide_dyns_virtual "$@" || { not_ok "loadrt motenc_hexaglide_dyns_virtual $*"; exit 1; }
    for f in encoder-read digital-in-read adc-read dac-write dynamics digital-out-write misc-update; do
        h addf $B.$f servo || { not_ok "addf $B.$f"; exit 1; }
    done
    h setp $B.out-07 1           # close the E-STOP loop (iocontrol's user-enable-out in a config)
}

# run_for SECONDS: let the thread run (wall clock; sim time is read from pins)
run_for() { h start; sleep "$1"; h stop; }

# wait_pin NAME VALUE TIMEOUT_S: poll until getp NAME prints VALUE (thread running)
wait_pin() {
    n=0; lim=$(awk -v t="$3" 'BEGIN{print int(t*20)}')
    while [ "$n" -lt "$lim" ]; do
        [ "$(g "$1")" = "$2" ] && return 0
        sleep 0.05; n=$((n + 1))
    done
    return 1
}

# approx A B TOL: |A - B| <= TOL (all numbers, awk arithmetic)
approx() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN{d=a-b; if(d<0)d=-d; exit !(d<=t && a==a+0 && b==b+0)}'; }
# lt A B: A < B
lt() { awk -v a="$1" -v b="$2" 'BEGIN{exit !(a+0<b+0)}'; }
# calc EXPR: awk arithmetic
calc() { awk "BEGIN{printf \"%.10g\", $1}"; }

# no_nonfinite PREFIX: no output (OUT or I/O) pin under PREFIX shows nan or
# inf, except the record pins rec.in.* (docs/replay.md): they echo the raw
# inputs the board was given, a NaN DAC value included, so replay can feed
# the same NaN again
no_nonfinite() {
    ! h show pin "$1" | awk 'NR>2 && ($3 == "OUT" || $3 == "I/O") && $5 !~ /[.]rec[.]in[.]/ {print $4}' |
        grep -qiE 'nan|inf'
}

# set_dacs VOLTS: the first six DAC values
set_dacs() { for k in 0 1 2 3 4 5; do s $B.dac-0$k-value "$1"; done; }
