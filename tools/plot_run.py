#!/usr/bin/python3
"""plot_run.py - plots and a summary of a sampled Hexaglide run.

Usage: tools/plot_run.py RUN.csv [OUTDIR]
Reads the CSV written by tools/headless/hexaglide_headless.py (one row per servo
period) and writes, in the spirit of Fig. 6 of Ros et al. 2011:
  <stem>_z11_z12.png   commanded vs actual z11 and z12 while the program runs
  <stem>_ferror.png    following error of every joint (LinuxCNC's joint.N.f-error)
  <stem>_step_time.png time of each dynamics step (motenc-hexaglide.0.step-time-ns)
  <stem>_pose.png      head pose of the simulated machine
  <stem>_tool_error.png the encoders' following errors beside the tool-path error
                       (motenc-hexaglide.0.tool-error: what the part gets)
and prints a summary (max following error per joint, step time max and
median) which it also writes to <stem>_summary.json.
"""
import json
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hg_csv  # noqa: E402

JOINTS = ["z11", "z12", "z21", "z22", "z31", "z32"]


NEED = ["t_s"] + ["joint.%d.motor-pos-%s" % (j, w) for j in range(6) for w in ("cmd", "fb")]


def load(path):
    """The run's columns by name; hg_csv.CsvError naming the line of a bad file."""
    return hg_csv.read(path, NEED, "a run sampled by tools/headless/hexaglide_headless.py")[1]


def program_window(d):
    """Boolean mask of the rows where the G-code program runs (all rows if unknown)."""
    run = d.get("halui.program.is-running")
    if run is None or not run.any():
        return np.ones(len(d["t_s"]), bool)
    return run > 0.5


def summarize(d):
    run = program_window(d)
    s = {"samples": int(len(d["t_s"])), "program_samples": int(run.sum()),
         "program_s": float(run.sum() * 0.001), "joints": {}}
    for j, name in enumerate(JOINTS):
        fe = d.get("joint.%d.f-error" % j)
        lag = d["joint.%d.motor-pos-cmd" % j] - d["joint.%d.motor-pos-fb" % j]
        s["joints"][name] = {
            "max_abs_ferror_mm": float(np.abs(fe[run]).max()) if fe is not None else None,
            "max_abs_cmd_minus_fb_mm": float(np.abs(lag[run]).max()),
        }
    st = d.get("motenc-hexaglide.0.step-time-ns")
    if st is not None:
        st = st[st > 0]
        s["step_time_us"] = {"median": float(np.median(st) / 1e3),
                             "p99": float(np.percentile(st, 99) / 1e3),
                             "max": float(st.max() / 1e3), "n": int(len(st))}
    te = d.get("motenc-hexaglide.0.tool-error")
    if te is not None:
        ok = run & (te >= 0)
        s["tool_error_mm"] = {"max": float(te[ok].max()) if ok.any() else None,
                              "rms": float(np.sqrt(np.mean(te[ok] ** 2))) if ok.any() else None,
                              "no_pose_samples": int((run & (te < 0)).sum())}
    it = d.get("hexaglidekins.fk-iterations")
    if it is not None:
        s["fk"] = {"iterations_max": int(it[run].max()),
                   "error_nonzero_samples": int((d["hexaglidekins.fk-error"][run] != 0).sum()),
                   "fault_samples": int((d["hexaglidekins.fk-fault"][run] != 0).sum()),
                   "fail_count_end": int(d["hexaglidekins.fk-fail-count"][-1])}
    return s


def plot_z11_z12(d, path):
    run = program_window(d)
    t = d["t_s"][run]
    fig, ax = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    for a, j in zip(ax, (0, 1)):
        a.plot(t, d["joint.%d.motor-pos-cmd" % j][run], label="commanded (joint.%d.motor-pos-cmd)" % j)
        a.plot(t, d["joint.%d.motor-pos-fb" % j][run], "--", label="actual (joint.%d.motor-pos-fb)" % j)
        a.set_ylabel("%s (mm)" % JOINTS[j])
        a.grid(True, alpha=0.3)
        a.legend(loc="best", fontsize=8)
    ax[-1].set_xlabel("simulated time (s)")
    fig.suptitle("Virtual Hexaglide: commanded and actual carriage positions z11, z12")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_ferror(d, path):
    run = program_window(d)
    t = d["t_s"][run]
    fig, ax = plt.subplots(6, 1, figsize=(10, 10), sharex=True)
    for j, a in enumerate(ax):
        fe = d.get("joint.%d.f-error" % j)
        if fe is None:
            fe = d["joint.%d.motor-pos-cmd" % j] - d["joint.%d.motor-pos-fb" % j]
        a.plot(t, fe[run] * 1e3, lw=0.7)
        a.set_ylabel("%s (um)" % JOINTS[j])
        a.grid(True, alpha=0.3)
    ax[0].set_title("Following error of every joint (joint.N.f-error)")
    ax[-1].set_xlabel("simulated time (s)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_step_time(d, path):
    st = d.get("motenc-hexaglide.0.step-time-ns")
    if st is None:
        return False
    fig, ax = plt.subplots(1, 2, figsize=(11, 4), gridspec_kw={"width_ratios": [3, 1]})
    ax[0].plot(d["t_s"], st / 1e3, ",", alpha=0.6)
    ax[0].set_xlabel("simulated time (s)")
    ax[0].set_ylabel("dynamics step (us)")
    ax[0].set_yscale("log")
    ax[0].axhline(10, color="r", lw=0.8, label="10 us (paper's negligible jitter)")
    ax[0].legend(fontsize=8)
    ax[0].grid(True, alpha=0.3)
    ax[1].hist(st / 1e3, bins=np.logspace(0, np.log10(max(st.max() / 1e3, 2)), 40))
    ax[1].set_xscale("log")
    ax[1].set_xlabel("us")
    ax[1].set_title("histogram", fontsize=9)
    fig.suptitle("motenc.0.dynamics: time of one integration step (wall clock, non-realtime host)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True


def plot_pose(d, path):
    keys = ["motenc-hexaglide.0.head-%s" % a for a in "xyzabc"]
    if not all(k in d for k in keys):
        return False
    run = program_window(d)
    t = d["t_s"][run]
    fig, ax = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    for k, a in zip(keys[:3], "XYZ"):
        ax[0].plot(t, d[k][run], label=a)
        ca = d.get("axis.%s.pos-cmd" % a.lower())
        if ca is not None:
            ax[0].plot(t, ca[run], "k:", lw=0.6)
    for k, a in zip(keys[3:], "ABC"):
        ax[1].plot(t, d[k][run], label=a)
    ax[0].set_ylabel("mm")
    ax[1].set_ylabel("deg")
    for a in ax:
        a.legend(fontsize=8, ncol=3)
        a.grid(True, alpha=0.3)
    ax[1].set_xlabel("simulated time (s)")
    fig.suptitle("Head pose of the simulated machine (dotted: commanded X Y Z)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True


def plot_tool_error(d, path):
    """The following error the encoders show (every joint) over the tool-path error."""
    te = d.get("motenc-hexaglide.0.tool-error")
    if te is None:
        return False
    run = program_window(d)
    t = d["t_s"][run]
    fig, ax = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    for j, name in enumerate(JOINTS):
        fe = d.get("joint.%d.f-error" % j)
        if fe is not None:
            ax[0].plot(t, fe[run] * 1e3, lw=0.6, label=name)
    ax[0].set_ylabel("um")
    ax[0].set_title("Following error the encoders see (joint.N.f-error)", fontsize=10)
    ax[0].legend(fontsize=7, ncol=6)
    v = np.where(te[run] >= 0, te[run], np.nan)
    ax[1].plot(t, v * 1e3, "k", lw=0.7)
    ax[1].set_ylabel("um")
    ax[1].set_title("Tool-path error: the tool tip's distance from where the commanded joints put it "
                    "(motenc-hexaglide.0.tool-error)", fontsize=10)
    for a in ax:
        a.grid(True, alpha=0.3)
    ax[1].set_xlabel("simulated time (s)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True


def main(argv):
    if len(argv) not in (2, 3) or argv[1] in ("-h", "--help"):
        print(__doc__, file=sys.stderr)
        return 2
    csv = argv[1]
    outdir = argv[2] if len(argv) > 2 else os.path.dirname(os.path.abspath(csv))
    if not os.path.isdir(outdir):
        print("plot_run.py: %s: not a directory; give an existing directory for the plots" % outdir,
              file=sys.stderr)
        return 2
    stem = os.path.join(outdir, os.path.splitext(os.path.basename(csv))[0])
    try:
        d = load(csv)
    except hg_csv.CsvError as ex:
        print("plot_run.py: %s" % ex, file=sys.stderr)
        return 1
    try:
        plot_z11_z12(d, stem + "_z11_z12.png")
        plot_ferror(d, stem + "_ferror.png")
        step = plot_step_time(d, stem + "_step_time.png")
        pose = plot_pose(d, stem + "_pose.png")
        tool = plot_tool_error(d, stem + "_tool_error.png")
        s = summarize(d)
        with open(stem + "_summary.json", "w") as f:
            json.dump(s, f, indent=1)
    except OSError as ex:
        print("plot_run.py: cannot write %s: %s" % (ex.filename or stem, ex.strerror or ex), file=sys.stderr)
        return 1
    print("program: %.1f s simulated, %d samples" % (s["program_s"], s["program_samples"]))
    print("max following error per joint (joint.N.f-error; cmd-fb incl. one servo period of lag):")
    for name, v in s["joints"].items():
        fe = v["max_abs_ferror_mm"]
        print("  %s  %8.4f mm   %8.4f mm" % (name, fe if fe is not None else float("nan"),
                                             v["max_abs_cmd_minus_fb_mm"]))
    if "step_time_us" in s:
        st = s["step_time_us"]
        print("dynamics step time: median %.2f us, p99 %.2f us, max %.1f us (%d steps)"
              % (st["median"], st["p99"], st["max"], st["n"]))
    if "fk" in s:
        fk = s["fk"]
        print("forward kinematics: max %d iterations, %d samples with an error, fail count %d"
              % (fk["iterations_max"], fk["error_nonzero_samples"], fk["fail_count_end"]))
    if s.get("tool_error_mm", {}).get("max") is not None:
        te = s["tool_error_mm"]
        print("tool-path error (motenc-hexaglide.0.tool-error): max %.4f mm, rms %.4f mm%s"
              % (te["max"], te["rms"], ", %d samples without a pose" % te["no_pose_samples"]
                 if te["no_pose_samples"] else ""))
    print("plots: %s_{%s}.png" % (stem, ",".join(["z11_z12", "ferror"] + ["step_time"] * step + ["pose"] * pose +
                                                 ["tool_error"] * tool)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
