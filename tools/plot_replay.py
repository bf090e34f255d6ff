#!/usr/bin/python3
"""plot_replay.py - a replayed run beside the recorded one.

Usage: tools/plot_replay.py REPLAY.csv OUT.png [FROM TO]
Reads the CSV of `hexaglide replay --csv` (recorded and replayed columns
side by side, docs/replay.md) and draws, against simulated time: the six
carriage heights (a serial machine's axes) recorded (solid) and replayed
(dashed), and their difference per joint (mm; deg for a rotary axis, whose
columns end in _deg); when the record holds the
joint commands, also the following error recorded and replayed (or
predicted by the closed-loop what-if) of the joint whose predicted peak is
largest, and the largest drive voltage of all, over samples FROM..TO
(replay's f-error window: after homing) when given. A file that is not
such a CSV (missing, empty, cut short, a field not a finite number, a
column missing) is refused naming the line, exit 1; bad arguments exit 2.
The PNG is written as tools/hg_output.py writes (a temporary file and a
rename for a regular file).
"""
import os
import re
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hg_csv  # noqa: E402
import hg_output  # noqa: E402

JOINTS = ["z11", "z12", "z21", "z22", "z31", "z32"]
WHAT = "a CSV of hexaglide replay --csv (docs/replay.md)"


def fail(msg, code=1):
    print("plot_replay.py: %s" % msg, file=sys.stderr)
    return code


def main():
    if len(sys.argv) not in (3, 5) or sys.argv[1] in ("-h", "--help"):
        print(__doc__, file=sys.stderr)
        return 2
    src, png = sys.argv[1], sys.argv[2]
    window = None
    if len(sys.argv) == 5:
        try:
            window = (int(sys.argv[3]), int(sys.argv[4]))
        except ValueError:
            window = None
        if window is None or not 0 <= window[0] <= window[1]:
            return fail("FROM TO '%s %s': give two sample numbers, 0 <= FROM <= TO" % (sys.argv[3], sys.argv[4]), 2)
    try:
        hg_output.refuse_inputs([("OUT.png", png)], [("REPLAY.csv", src)])
    except hg_output.OutputError as ex:
        return fail(str(ex), 2)
    try:
        names, col = hg_csv.read(src, ("sample", "t_s"), WHAT)
        # the channels: the Hexaglide's six joints, a serial machine's axes (replay writes one column
        # each, named in the channel's machine unit: z0_rec_mm, or z0_rec_deg for a rotary axis)
        unit = {int(m.group(1)): m.group(2) for m in (re.match(r"z(\d+)_rec_(mm|deg)$", n) for n in names) if m}
        nj = len(unit)
        if nj == 0 or sorted(unit) != list(range(nj)):
            raise hg_csv.CsvError("%s: no columns z0_rec_mm (or z0_rec_deg), z1_rec_mm, ... in its header: not %s"
                                  % (src, WHAT))
        u = [unit[k] for k in range(nj)]
        hg_csv.check_columns(src, names, ["z%d_%s" % (k, u[k]) for k in range(nj)], WHAT)
        loop = "ferror0_%s" % u[0] in col
        if loop:
            hg_csv.check_columns(src, names, ["%s%d%s" % (c, k, r % u[k] if "%" in r else r) for k in range(nj)
                                              for c, r in (("ferror", "_%s"), ("ferror", "_rec_%s"), ("volts", ""),
                                                           ("volts", "_rec"))],
                                 WHAT)
    except hg_csv.CsvError as ex:
        return fail(ex)
    hexaglide = nj == len(JOINTS) and "a_rec" in col          # the head's pose: the Hexaglide's CSV
    labels = JOINTS if hexaglide else ["axis %d" % k for k in range(nj)]
    t = col["sample"] * 1e-3 if not np.any(col["t_s"]) else col["t_s"]
    w = np.ones(len(t), bool)
    if window:
        w = (col["sample"] >= window[0]) & (col["sample"] <= window[1])
        if loop and not w.any():
            return fail("%s: no sample in the f-error window %d..%d (samples %d..%d): give a window inside the run"
                        % (src, window[0], window[1], col["sample"][0], col["sample"][-1]), 2)
    fig, axes = plt.subplots(4 if loop else 2, 1, figsize=(10, 12 if loop else 7), sharex=True)
    ax, dx = axes[0], axes[1]
    for k, name in enumerate(labels):
        rec, rep = col["z%d_rec_%s" % (k, u[k])], col["z%d_%s" % (k, u[k])]
        line, = ax.plot(t, rec, lw=1.2, label="%s recorded" % name)
        ax.plot(t, rep, lw=1.0, ls="--", color=line.get_color(), label="%s replayed" % name)
        dx.plot(t, rep - rec, lw=1.0, color=line.get_color(), label=name)
    units = " or ".join(sorted(set(u), key=u.index))           # mm, deg, or "mm or deg"
    ax.set_ylabel("carriage height (mm)" if hexaglide else "axis position (%s)" % units)
    ax.set_title("recorded (solid) and replayed (dashed) run")
    ax.legend(ncol=4, fontsize=7)
    dx.set_ylabel("replayed - recorded (%s)" % units)
    dx.legend(ncol=6, fontsize=7)
    if loop:
        k = int(np.argmax([np.max(np.abs(col["ferror%d_%s" % (j, u[j])][w])) for j in range(nj)]))
        fx, vx = axes[2], axes[3]
        fx.plot(t[w], col["ferror%d_rec_%s" % (k, u[k])][w] * 1e3, lw=0.8, label="%s recorded" % labels[k])
        fx.plot(t[w], col["ferror%d_%s" % (k, u[k])][w] * 1e3, lw=0.8, alpha=0.8,
                label="%s replayed / predicted" % labels[k])
        fx.set_ylabel("following error (%s)" % ("um" if u[k] == "mm" else "millidegrees"))
        fx.set_title("following error%s" % (" (samples %d..%d)" % window if window else ""))
        fx.legend(fontsize=7)
        rec = np.max(np.abs([col["volts%d_rec" % j] for j in range(nj)]), axis=0)
        rep = np.max(np.abs([col["volts%d" % j] for j in range(nj)]), axis=0)
        vx.plot(t[w], rec[w], lw=0.8, label="recorded")
        vx.plot(t[w], rep[w], lw=0.8, alpha=0.8, label="replayed / predicted")
        vx.set_ylabel("largest |drive volts| (V)")
        vx.legend(fontsize=7)
    for a in axes:
        a.grid(True, alpha=0.3)
    axes[-1].set_xlabel("simulated time (s)")
    fig.tight_layout()
    try:
        hg_output.atomic_write(png, lambda f: fig.savefig(f, format="png", dpi=100))
    except hg_output.OutputError as ex:
        print("plot_replay.py: %s" % ex, file=sys.stderr)
        return 1
    try:
        print("plot_replay.py: wrote %s" % png, flush=True)
    except OSError:                     # stdout full or closed: the plot is written; hexaglide replay says
        pass                            # that its stdout failed (it is the same stream)
    return 0


if __name__ == "__main__":
    sys.exit(main())
