#!/usr/bin/python3
"""hg_record.py - record a LinuxCNC run of the virtual Hexaglide board, one
row per servo period, every double exact, for `build/hexaglide replay`
(docs/replay.md).

Usage (as a HAL user component, before the threads start; tools/hg_record.tcl
does this when HG_RECORD or [HEXAGLIDE]RECORD names a file):
    loadusr -Wn hg_record tools/hg_record.py OUT [--board N] [--depth N]
                [--thread servo-thread] [--prefix P] [--extra PIN]...
    (HG_RECORD_EXTRA="PIN PIN ..." adds --extra pins too)

What it records: every pin motenc-hexaglide.<board>.rec.* of the virtual
board, i.e. the inputs the board core consumed (hg_board_inputs) and the
outputs it produced (hg_board_outputs) in that period, written by the
board's own function; motion's joint commands joint.N.motor-pos-cmd
(columns of that name) and any --extra pins. For the closed-loop what-if
of `replay` it checks that the loops are wired as configs/hexaglide.hal
wires them (header line "# closed-loop ...") and polls the pid settings
and DAC scales in force (pid.N.Pgain ..., motenc.<board>.dac-CC-gain,
-offset), written after the last row as "# name value" lines. It loads LinuxCNC's `sampler` with those pins
(at most 21 per FIFO), adds the sampler functions to the end of the servo
thread, reads the FIFOs through the HAL stream API (hal.stream) and writes
floats with repr(), the shortest text that reads back to the same double.
(halsampler prints "%f": six decimals, most bits lost.)

The file (format in src/hg_record.h): a magic line, "# key value" lines,
the header "sample,<column>,...", one row per period from the first
one, then the footer's "# key value" lines. Lost samples (FIFO overrun) are reported on stderr and in the exit
code; the file is then incomplete and `replay` refuses the gap.
"""
import argparse
import datetime
import os
import signal
import subprocess
import sys
import time

import hal

PER_FIFO = 21          # HAL_STREAM_MAX_PINS of LinuxCNC 2.9's hal.h (hal_lib's stream limit)
MAX_FIFOS = 8          # sampler's MAX_SAMPLERS
JOINTS_MAX = 8         # the board's channels: joints 0..7 at most
# pid.c's setting pins (LinuxCNC 2.9): what src/hg_pid.h's hg_pid_gains holds
PID_SETTINGS = ["Pgain", "Igain", "Dgain", "bias", "FF0", "FF1", "FF2", "FF3", "deadband",
                "maxerror", "maxerrorI", "maxerrorD", "maxcmdD", "maxcmdDD", "maxcmdDDD",
                "maxoutput", "error-previous-target"]
POLL_S = 0.2           # how often the settings are read
MAGIC = "# hexaglide-record %d"   # the format of the board's rec pins (src/hg_board_rec.h)
TYPE_CHAR = {hal.HAL_FLOAT: "f", hal.HAL_BIT: "b", hal.HAL_S32: "s", hal.HAL_U32: "u"}


def log(*a):
    print("hg_record:", *a, file=sys.stderr, flush=True)


def halcmd_script(lines):
    """Run HAL commands through one halcmd; raise with its message on failure."""
    r = subprocess.run(["halcmd", "-f"], input="\n".join(lines) + "\n",
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("halcmd failed: %s %s" % (r.stdout.strip(), r.stderr.strip()))


def pin_signals():
    """{pin name: signal name or None} of every HAL pin (halcmd show pin)."""
    r = subprocess.run(["halcmd", "-s", "show", "pin"], capture_output=True, text=True)
    sig = {}
    for line in r.stdout.splitlines():
        f = line.split()
        if len(f) >= 5:
            sig[f[4]] = f[6] if len(f) >= 7 and f[5] in ("==>", "<==", "<=>") else None
    return sig


def loop_wiring(sig, board, joints):
    """'' if joint N, pid.N and the board's channel N are wired as
    configs/hexaglide.hal (and LinuxCNC's stock motenc_motion.hal) wire
    them, for joints 0..joints-1, else what differs."""
    for j in range(joints):
        groups = [("joint.%d.motor-pos-cmd" % j, "pid.%d.command" % j),
                  ("motenc.%d.enc-%02d-position" % (board, j), "pid.%d.feedback" % j),
                  ("pid.%d.output" % j, "motenc.%d.dac-%02d-value" % (board, j)),
                  ("joint.%d.amp-enable-out" % j, "pid.%d.enable" % j, "motenc.%d.out-%02d" % (board, 8 + j)),
                  ("motenc.%d.enc-%02d-index-enable" % (board, j), "pid.%d.index-enable" % j)]
        for g in groups:
            for p in g:
                if p not in sig:
                    return "no pin %s" % p
            if sig[g[0]] is None or any(sig[p] != sig[g[0]] for p in g[1:]):
                return "%s not on one signal" % " ".join(g)
    return ""


def settings_names(board, joints):
    """The settings the closed loop needs, in footer order."""
    names = ["pid.%d.%s" % (j, k) for j in range(joints) for k in PID_SETTINGS]
    for j in range(joints):
        names += ["motenc.%d.dac-%02d-gain" % (board, j), "motenc.%d.dac-%02d-offset" % (board, j)]
    return names


def read_settings(names):
    """{name: value} of the settings that exist (bits and integers as ints)."""
    vals = {}
    for n in names:
        try:
            vals[n] = hal.get_value(n)
        except Exception:         # noqa: BLE001 - a pin or parameter that is not there
            pass
    return vals


def fmt_of(t):
    """Formatter of one column: exact text of a HAL value."""
    if t == hal.HAL_FLOAT:
        return repr
    if t == hal.HAL_BIT:
        return lambda v: "1" if v else "0"
    return lambda v: str(int(v))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", default=os.environ.get("HG_RECORD", ""),
                    help="record file to write (default: $HG_RECORD)")
    ap.add_argument("--board", type=int, default=0)
    ap.add_argument("--depth", type=int, default=20000,
                    help="FIFO depth in servo periods (default 20000: 20 s at 1 kHz)")
    ap.add_argument("--thread", default="servo-thread")
    ap.add_argument("--prefix", default=None,
                    help="pins to record (default motenc-hexaglide.<board>.rec.)")
    ap.add_argument("--extra", action="append", default=os.environ.get("HG_RECORD_EXTRA", "").split(),
                    help="another pin to record, column named as the pin (repeatable)")
    a = ap.parse_args()
    if not a.out:
        log("no output file: give OUT or set HG_RECORD")
        return 2
    prefix = a.prefix or "motenc-hexaglide.%d.rec." % a.board

    try:
        out = open(a.out, "w")
    except OSError as ex:
        log("cannot write the record file: %s; give a writable path in HG_RECORD or "
            "[HEXAGLIDE]RECORD" % ex)
        return 1
    comp = hal.component("hg_record")
    allpins = hal.get_info_pins()
    pins = sorted((p for p in allpins if p["NAME"].startswith(prefix)),
                  key=lambda p: p["NAME"])
    if not pins:
        log("no pin %s*: load the board with its record pins, 'loadrt "
            "motenc_hexaglide_dyns_virtual record=1', before this recorder" % prefix)
        return 1
    byname = {p["NAME"]: p for p in allpins}
    joints = 0                        # motion's joints: one command column each
    while joints < JOINTS_MAX and "joint.%d.motor-pos-cmd" % joints in byname:
        joints += 1
    fmt = 2 if prefix + "in.params-fp" in byname else 1
    sig = pin_signals()
    wiring = loop_wiring(sig, a.board, joints) if joints else "no joint.0.motor-pos-cmd"
    loop = ["joint.%d.motor-pos-cmd" % j for j in range(joints)]
    unknown = [n for n in a.extra if n not in byname]
    if unknown:
        log("no such pin to record (--extra):", " ".join(unknown))
        return 1
    pins += [byname[n] for n in dict.fromkeys(loop + a.extra) if n in byname]
    bad = [p["NAME"] for p in pins if p["TYPE"] not in TYPE_CHAR]
    if bad:
        log("pins of a type sampler cannot record:", " ".join(bad))
        return 1
    groups = [pins[i:i + PER_FIFO] for i in range(0, len(pins), PER_FIFO)]
    if len(groups) > MAX_FIFOS:
        log("%d pins need %d sampler FIFOs, sampler has %d" % (len(pins), len(groups), MAX_FIFOS))
        return 1
    cfgs = ["".join(TYPE_CHAR[p["TYPE"]] for p in g) for g in groups]
    cmds = ["loadrt sampler depth=%s cfg=%s" % (",".join([str(a.depth)] * len(groups)),
                                                 ",".join(cfgs)),
            "setp motenc-hexaglide.%d.record 1" % a.board]   # the board writes its rec pins
    for f, g in enumerate(groups):
        for i, p in enumerate(g):
            name = p["NAME"]
            net = sig.get(name) or "hg-rec." + (name[len(prefix):] if name.startswith(prefix) else name)
            cmds.append("net %s %s sampler.%d.pin.%d" % (net, name, f, i))
        cmds.append("addf sampler.%d %s" % (f, a.thread))
    halcmd_script(cmds)
    streams = [hal.stream(comp, hal.sampler_base + f, cfgs[f]) for f in range(len(groups))]
    cols = [p["NAME"][len(prefix):] if p["NAME"].startswith(prefix) else p["NAME"] for p in pins]
    fmts = [fmt_of(p["TYPE"]) for p in pins]

    stop = []
    signal.signal(signal.SIGTERM, lambda s, f: stop.append(s))
    signal.signal(signal.SIGINT, lambda s, f: stop.append(s))
    out.write(MAGIC % fmt + "\n")
    out.write("# source %s, LinuxCNC HAL sampler FIFOs read with hal.stream\n" % os.path.basename(__file__))
    out.write("# board %d\n" % a.board)
    out.write("# prefix %s\n" % prefix)
    out.write("# started %s\n" % datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"))
    out.write("# closed-loop %s\n" % ("no: " + wiring if wiring else "hexaglide.hal"))
    out.write("sample," + ",".join(cols) + "\n")
    comp.ready()

    n = 0
    pending = [None] * len(streams)   # a row is written once every FIFO gave its part
    idle_since = None
    names = settings_names(a.board, joints)
    settings = read_settings(names)   # as the HAL files left them, before the threads start
    changed_at = 0                    # rows written when a change was last seen
    polled = time.time()
    while True:
        if not stop and time.time() - polled > POLL_S:
            polled = time.time()
            now = read_settings(names)
            if len(now) == len(settings) and now != settings:
                # the change is in force by the sample the threads are at now:
                # rows written + those still in the first FIFO
                settings = now
                changed_at = n + (pending[0] is not None) + int(hal.get_value("sampler.0.curr-depth"))
        progressed = False
        for f, s in enumerate(streams):
            if pending[f] is None and s.readable:
                pending[f] = s.read()
                progressed = True
        if all(p is not None for p in pending):
            vals = [v for p in pending for v in p]
            out.write("%d,%s\n" % (n, ",".join(fm(v) for fm, v in zip(fmts, vals))))
            n += 1
            pending = [None] * len(streams)
            continue
        if stop:
            # threads may still run a little: drain until nothing comes for 0.2 s
            if progressed:
                idle_since = None
            elif idle_since is None:
                idle_since = time.time()
            elif time.time() - idle_since > 0.2:
                break
        time.sleep(0.001)
    lost = sum(s.num_overruns for s in streams)
    # the footer: the settings in force (as last polled) and from when they held
    for k in names:
        if k in settings:
            v = settings[k]
            out.write("# %s %s\n" % (k, repr(float(v)) if isinstance(v, float) else str(int(v))))
    if changed_at:
        out.write("# settings-from-sample %d\n" % changed_at)
    out.close()
    if lost:
        log("%d samples lost (sampler FIFO overrun): %s is incomplete; record again with a "
            "larger --depth" % (lost, a.out))
        return 1
    log("%d servo periods, %d columns recorded to %s" % (n, len(cols), a.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
