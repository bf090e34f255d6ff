#!/usr/bin/python3
"""verify_gains.py - run LinuxCNC with gains suggested by `hexaglide tune`
and compare the measured peak following error per joint with the prediction.

    tools/verify_gains.py GAINS_FILE [--program NGC] [--tolerance 0.10]

GAINS_FILE is tune's stdout (or --output): [JOINT_N] sections with
P I D FF0 FF1 FF2 FF3 BIAS ... and the "# joint N: peak |f-error| ..." lines;
or any INI (configs/hexaglide.ini: its [JOINT_N] gains).
The gains are set with halcmd over configs/hexaglide.ini's (HG_SETP of
tools/headless/hexaglide_headless.py), the program runs headless
(tools/hg_linuxcnc.sh), every servo period is sampled, and the measured peak
|f-error| per joint is compared with tune's prediction made offline from
this run's own joint commands (motion's output only, never the measured
errors). LinuxCNC's planner does not give the same commands twice here
(the interpreter feeds its queue in wall-clock time on a non-realtime host:
two logo runs lasted 43.5 and 45.0 s), so the prediction of the gains file,
made on an earlier recording, is printed beside as an estimate.
On this shared host, run it under the install lock (docs/tuning.md).
Exit: 0 when every joint is within the tolerance of the prediction (or
inside the spread of its offline runs), 1 not, 2 bad input or LinuxCNC failed.
"""
import argparse
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
sys.path.insert(0, HERE)
import hexaglide as hg  # noqa: E402
import hg_csv  # noqa: E402
import hexaglide_tune as tune  # noqa: E402
import hg_margins as hgm  # noqa: E402



def run_linuxcnc(gains, program, out, tag):
    """Headless LinuxCNC run with the gains; the sampled CSV's path."""
    setp = ";".join("pid.%d.%s %.17g" % (j, hg.GAIN_PINS[k], v) for j, g in enumerate(gains) for k, v in g.items())
    env = dict(os.environ, HG_SETP=setp, HG_SCENARIO="run", HG_TAG=tag, HG_OUT=out, HG_PROGRAM=program)
    csv = os.path.join(out, tag + ".csv")
    if os.path.exists(csv):
        os.unlink(csv)
    with open(os.path.join(out, tag + ".log"), "w") as log:
        rc = subprocess.call(["timeout", "-k", "20", "300", os.path.join(ROOT, "tools", "hg_linuxcnc.sh"),
                              os.path.join(ROOT, "tools", "headless", "hexaglide_headless.ini")],
                             env=env, stdout=log, stderr=subprocess.STDOUT, cwd=ROOT)
    if rc != 0 or not os.path.exists(csv):
        raise RuntimeError("LinuxCNC run failed (exit %d); see %s" % (rc, os.path.join(out, tag + ".log")))
    return csv


def measured(csv):
    """Peak |f-error| (mm) and peak |pid output| (V) per joint while the program ran,
    and the peak tool-path error (mm; the board's tool-error, None when not sampled)."""
    need = (["joint.%d.motor-pos-cmd" % j for j in range(6)] + ["halui.program.is-running"] +
            ["joint.%d.f-error" % j for j in range(6)] + ["pid.%d.output" % j for j in range(6)])
    try:                               # (a missing column, a NaN, a cut row: named, not a traceback)
        names, col = hg_csv.read(csv, need, "a run sampled by the headless front end (tools/headless)")
    except hg_csv.CsvError as ex:
        raise RuntimeError(str(ex))
    cmd = np.column_stack([col["joint.%d.motor-pos-cmd" % j] for j in range(6)])
    span = tune.program_rows(col["halui.program.is-running"] > 0.5, cmd)
    if span is None:
        raise RuntimeError("%s: the program never ran" % csv)
    run = np.zeros(len(cmd), bool)
    run[span[0]:span[1]] = True
    fe = np.array([np.abs(col["joint.%d.f-error" % j][run]).max() for j in range(6)])
    v = np.array([np.abs(col["pid.%d.output" % j][run]).max() for j in range(6)])
    tool = None
    if "motenc-hexaglide.0.tool-error" in names:
        te = col["motenc-hexaglide.0.tool-error"][run]
        tool = te.max() if (te >= 0).all() else -1.0      # -1: some period without a pose
    return fe, v, tool


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("gains", help="tune's output: [JOINT_N] sections + predicted peaks")
    ap.add_argument("--program", default=os.path.join(ROOT, "configs", "nc_files", "hexaglide_logo.ngc"))
    ap.add_argument("--tolerance", type=float, default=0.10, help="allowed |measured/predicted - 1|")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "verify"))
    ap.add_argument("--tag", default="verify")
    ap.add_argument("--csv", help="use this sampled run instead of starting LinuxCNC")
    ap.add_argument("--ini", default=os.path.join(ROOT, "configs", "hexaglide.ini"),
                    help="the INI LinuxCNC runs (its pid settings under the file's gains)")
    a = ap.parse_args()
    try:
        gains, pred = hg.read_gains(a.gains)
        notch = hgm.read_notch(a.gains)
    except (OSError, ValueError) as ex:
        print("verify_gains: %s" % ex, file=sys.stderr)
        return 2
    if notch:                          # the run sets gains over configs/hexaglide.hal, which has no biquad
        print("verify_gains: %s: its gains go with the biquad notch f0 %g Hz, Q %g (its hal lines), which this "
              "run cannot load (it sets pid gains over %s's HAL, which has no biquad): LinuxCNC and the "
              "prediction would both run the loop without the notch; verify it in a config whose HAL file "
              "loads those lines" % ((a.gains,) + notch + (os.path.basename(a.ini),)), file=sys.stderr)
        return 2
    os.makedirs(a.out, exist_ok=True)
    try:
        csv = a.csv or run_linuxcnc(gains, os.path.abspath(a.program), a.out, a.tag)
        fe, volts, tool = measured(csv)
    except RuntimeError as ex:
        print("verify_gains: %s" % ex, file=sys.stderr)
        return 2
    # as in the LinuxCNC run: the INI's pid settings, the file's gains set over them
    try:                               # the INI as LinuxCNC and sim read it (the C reader)
        ini = [tune.pid_keys(g) for g in tune.read_ini(a.ini, cmd="verify_gains")[0]]
    except tune.BadInput as ex:
        print("verify_gains: %s" % ex, file=sys.stderr)
        return 2
    gains = [dict(i, **g) for i, g in zip(ini, gains)]
    cmd = tune.load_trajectory(csv)
    prob = {"cmd": cmd, "ferror_limit": 2.0}
    again, why = tune.predict(gains, prob, tune.PREDICT_SETTLES)
    if again is None:
        print("verify_gains: offline on this run's commands: %s" % why, file=sys.stderr)
        return 1
    print("# %s with %s" % (os.path.basename(a.program), a.gains))
    print("# predicted = tune's prediction from this run's joint commands (median of 15 offline runs);")
    print("# file = the prediction in the gains file (from the trajectory tune was given)")
    print("%-6s %12s %12s %8s %22s %12s %8s %8s" % ("joint", "measured_mm", "predicted_mm", "ratio",
                                                  "runs: min..max", "file_mm", "meas_V", "pred_V"))
    ok = True
    ratios = []
    for j in range(6):
        p = again["ferror"][j]
        r = fe[j] / p if p > 0 else np.inf
        ratios.append(r)
        # within the tolerance of the median, or inside the spread of the offline runs
        # (the encoder's 1 um counts make single runs differ by up to a count)
        good = abs(r - 1) <= a.tolerance or again["ferror_lo"][j] <= fe[j] <= again["ferror_hi"][j]
        ok &= good
        print("%-6d %12.5f %12.5f %8.3f %10.5f..%-10.5f %12s %8.3f %8.3f%s"
              % (j, fe[j], p, r, again["ferror_lo"][j], again["ferror_hi"][j],
                 "%.5f" % pred[j] if j in pred else "-", volts[j], again["volts"][j],
                 "" if good else "   <-- off by more than %.0f%%" % (100 * a.tolerance)))
    worst = max(ratios, key=lambda r: abs(r - 1))
    print("# peak over joints: measured %.5f mm at %.3f V; predicted %.5f mm at %.3f V%s"
          % (fe.max(), volts.max(), again["ferror"].max(), again["volts"].max(),
             "; gains file: %.5f mm" % max(pred.values()) if pred else ""))
    if tool is not None:
        print("# peak tool-path error: measured %.5f mm, predicted %.5f mm (ratio %.3f)"
              % (tool, again["tool"], tool / again["tool"] if again["tool"] > 0 else np.inf))
    print("VERIFY %s max_ferror_mm=%.5f max_volts=%.3f worst_ratio=%.3f"
          % ("ok" if ok else "off", fe.max(), volts.max(), worst))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
