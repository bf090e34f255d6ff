#!/usr/bin/python3
"""hg_record.py - record a LinuxCNC run of the virtual Hexaglide board, one
row per servo period, every double exact, for `build/hexaglide replay`
(docs/replay.md).

Usage (as a HAL user component, before the threads start; tools/hg_record.tcl
does this when HG_RECORD or [HEXAGLIDE]RECORD names a file):
    loadusr -Wn hg_record tools/hg_record.py OUT [--board N] [--depth N]
                                            [--thread servo-thread] [--prefix P]

What it records: every pin motenc-hexaglide.<board>.rec.* of the virtual
board, i.e. the inputs the board core consumed (hg_board_inputs) and the
outputs it produced (hg_board_outputs) in that period, written by the
board's own function. It loads LinuxCNC's `sampler` with those pins
(at most 20 per FIFO), adds the sampler functions to the end of the servo
thread, reads the FIFOs through the HAL stream API (hal.stream) and writes
floats with repr(), the shortest text that reads back to the same double.
(halsampler prints "%f": six decimals, most bits lost.)

The file (format in src/hg_record.h): a magic line, "# key value" lines,
the header "sample,<column>,...", then one row per period from the first
one. Lost samples (FIFO overrun) are reported on stderr and in the exit
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

PER_FIFO = 20          # sampler's MAX_PINS
MAX_FIFOS = 8          # sampler's MAX_SAMPLERS
MAGIC = "# hexaglide-record 1"
TYPE_CHAR = {hal.HAL_FLOAT: "f", hal.HAL_BIT: "b", hal.HAL_S32: "s", hal.HAL_U32: "u"}


def log(*a):
    print("hg_record:", *a, file=sys.stderr, flush=True)


def halcmd_script(lines):
    """Run HAL commands through one halcmd; raise with its message on failure."""
    r = subprocess.run(["halcmd", "-f"], input="\n".join(lines) + "\n",
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("halcmd failed: %s %s" % (r.stdout.strip(), r.stderr.strip()))


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
    pins = sorted((p for p in hal.get_info_pins() if p["NAME"].startswith(prefix)),
                  key=lambda p: p["NAME"])
    if not pins:
        log("no pin %s*: load motenc_hexaglide_dyns_virtual (a version with record pins) "
            "before this recorder" % prefix)
        return 1
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
                                                 ",".join(cfgs))]
    for f, g in enumerate(groups):
        for i, p in enumerate(g):
            cmds.append("net hg-rec.%s %s sampler.%d.pin.%d" % (p["NAME"][len(prefix):], p["NAME"], f, i))
        cmds.append("addf sampler.%d %s" % (f, a.thread))
    halcmd_script(cmds)
    streams = [hal.stream(comp, hal.sampler_base + f, cfgs[f]) for f in range(len(groups))]
    cols = [p["NAME"][len(prefix):] for p in pins]
    fmts = [fmt_of(p["TYPE"]) for p in pins]

    stop = []
    signal.signal(signal.SIGTERM, lambda s, f: stop.append(s))
    signal.signal(signal.SIGINT, lambda s, f: stop.append(s))
    out.write(MAGIC + "\n")
    out.write("# source %s, LinuxCNC HAL sampler FIFOs read with hal.stream\n" % os.path.basename(__file__))
    out.write("# board %d\n" % a.board)
    out.write("# prefix %s\n" % prefix)
    out.write("# started %s\n" % datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"))
    out.write("sample," + ",".join(cols) + "\n")
    comp.ready()

    n = 0
    pending = [None] * len(streams)   # a row is written once every FIFO gave its part
    idle_since = None
    while True:
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
    out.close()
    if lost:
        log("%d samples lost (sampler FIFO overrun): %s is incomplete; record again with a "
            "larger --depth" % (lost, a.out))
        return 1
    log("%d servo periods, %d columns recorded to %s" % (n, len(cols), a.out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
