#!/usr/bin/python3
"""plot_replay.py - a replayed run beside the recorded one.

Usage: tools/plot_replay.py REPLAY.csv OUT.png [FROM TO]
Reads the CSV of `hexaglide replay --csv` (recorded and replayed columns
side by side, docs/replay.md) and draws, against simulated time: the six
carriage heights recorded (solid) and replayed (dashed), and their
difference per joint (mm); when the record holds the joint commands, also
the following error recorded and replayed (or predicted by the closed-loop
what-if) of the joint whose predicted peak is largest, and the largest
drive voltage of the six, over samples FROM..TO (replay's f-error window:
after homing) when given. The PNG is written as tools/hg_output.py writes (a temporary
file and a rename for a regular file).
"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hg_output  # noqa: E402

JOINTS = ["z11", "z12", "z21", "z22", "z31", "z32"]


def main():
    if len(sys.argv) not in (3, 5):
        print(__doc__, file=sys.stderr)
        return 2
    src, png = sys.argv[1], sys.argv[2]
    window = (int(sys.argv[3]), int(sys.argv[4])) if len(sys.argv) == 5 else None
    with open(src) as f:
        names = f.readline().strip().split(",")
    data = np.loadtxt(src, delimiter=",", skiprows=1, ndmin=2)
    if data.shape[0] == 0:
        print("plot_replay.py: %s has no rows" % src, file=sys.stderr)
        return 1
    col = {n: data[:, i] for i, n in enumerate(names)}
    t = col["sample"] * 1e-3 if not np.any(col["t_s"]) else col["t_s"]
    loop = "ferror0_mm" in col
    fig, axes = plt.subplots(4 if loop else 2, 1, figsize=(10, 12 if loop else 7), sharex=True)
    ax, dx = axes[0], axes[1]
    for k, name in enumerate(JOINTS):
        line, = ax.plot(t, col["z%d_rec_mm" % k], lw=1.2, label="%s recorded" % name)
        ax.plot(t, col["z%d_mm" % k], lw=1.0, ls="--", color=line.get_color(), label="%s replayed" % name)
        dx.plot(t, col["z%d_mm" % k] - col["z%d_rec_mm" % k], lw=1.0, color=line.get_color(), label=name)
    ax.set_ylabel("carriage height (mm)")
    ax.set_title("recorded (solid) and replayed (dashed) run")
    ax.legend(ncol=4, fontsize=7)
    dx.set_ylabel("replayed - recorded (mm)")
    dx.legend(ncol=6, fontsize=7)
    if loop:
        w = np.ones(len(t), bool)
        if window:
            w = (col["sample"] >= window[0]) & (col["sample"] <= window[1])
        k = int(np.argmax([np.max(np.abs(col["ferror%d_mm" % j][w])) for j in range(6)]))
        fx, vx = axes[2], axes[3]
        fx.plot(t[w], col["ferror%d_rec_mm" % k][w] * 1e3, lw=0.8, label="%s recorded" % JOINTS[k])
        fx.plot(t[w], col["ferror%d_mm" % k][w] * 1e3, lw=0.8, alpha=0.8,
                label="%s replayed / predicted" % JOINTS[k])
        fx.set_ylabel("following error (um)")
        fx.set_title("following error%s" % (" (samples %d..%d)" % window if window else ""))
        fx.legend(fontsize=7)
        rec = np.max(np.abs([col["volts%d_rec" % j] for j in range(6)]), axis=0)
        rep = np.max(np.abs([col["volts%d" % j] for j in range(6)]), axis=0)
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
    print("plot_replay.py: wrote %s" % png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
