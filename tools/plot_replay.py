#!/usr/bin/python3
"""plot_replay.py - a replayed run beside the recorded one.

Usage: tools/plot_replay.py REPLAY.csv OUT.png
Reads the CSV of `hexaglide replay --csv` (recorded and replayed columns
side by side, docs/replay.md) and draws, against simulated time: the six
carriage heights recorded (solid) and replayed (dashed), and their
difference per joint (mm).
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

JOINTS = ["z11", "z12", "z21", "z22", "z31", "z32"]


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    src, png = sys.argv[1], sys.argv[2]
    with open(src) as f:
        names = f.readline().strip().split(",")
    data = np.loadtxt(src, delimiter=",", skiprows=1, ndmin=2)
    if data.shape[0] == 0:
        print("plot_replay.py: %s has no rows" % src, file=sys.stderr)
        return 1
    col = {n: data[:, i] for i, n in enumerate(names)}
    t = col["sample"] * 1e-3 if not np.any(col["t_s"]) else col["t_s"]
    fig, (ax, dx) = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
    for k, name in enumerate(JOINTS):
        line, = ax.plot(t, col["z%d_rec_mm" % k], lw=1.2, label="%s recorded" % name)
        ax.plot(t, col["z%d_mm" % k], lw=1.0, ls="--", color=line.get_color(), label="%s replayed" % name)
        dx.plot(t, col["z%d_mm" % k] - col["z%d_rec_mm" % k], lw=1.0, color=line.get_color(), label=name)
    ax.set_ylabel("carriage height (mm)")
    ax.set_title("recorded (solid) and replayed (dashed) run")
    ax.legend(ncol=4, fontsize=7)
    ax.grid(True, alpha=0.3)
    dx.set_ylabel("replayed - recorded (mm)")
    dx.set_xlabel("simulated time (s)")
    dx.grid(True, alpha=0.3)
    dx.legend(ncol=6, fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    print("plot_replay.py: wrote %s" % png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
