#!/usr/bin/python3
"""train_record.py OUT NAME=VALUE... - a halsampler-style recording of the
virtual board in LinuxCNC's closed loop (the board, src/hg_board.c, under
six LinuxCNC pids, src/hg_pid.c, configs/hexaglide.ini's gains), of a
machine with the given parameters (hidden from identify), for the drive
train's identification (tests/cli/test_identify_train).

The program: `hexaglide excite --trains`' vertical strokes (excite.strokes:
constant speed, reversals at the ends: the backlash's), excite's design
for the rigid parameters (fourier), or LinuxCNC's homing latch (latch: every
joint 6 mm down at HOME_LATCH_VEL 2 mm/s and back, again and again, from
rest at HOME); from the first
second on the trains' dither added to the pids' outputs as excite's HAL
snippet adds it (excite.dither: chirps over --band Hz of --dither-v volts). Columns: joint.N.motor-pos-cmd (mm),
motenc.0.enc-NN-count, motenc.0.dac-NN-value (V),
motenc-hexaglide.0.joint-N.pos (the carriage, mm to 10 nm: a linear scale),
the encoder and the scale read before the period's DAC write."""
import argparse
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import ctypes as C  # noqa: E402
import hexaglide as hg  # noqa: E402
import hexaglide_excite as ex  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("sets", nargs="*")
    ap.add_argument("--seconds", type=float, default=12.0)
    ap.add_argument("--program", choices=["trains", "fourier", "latch"], default="trains",
                    help="trains: excite --trains' strokes; fourier: excite's design for the rigid parameters "
                    "(one start, 15 iterations, as tests/cli/test_identify_cli); latch: every joint down 6 mm "
                    "at 2 mm/s and back up at 10 mm/s, after 1 s at rest, repeated")
    ap.add_argument("--substeps", type=int, default=16)
    ap.add_argument("--integrator", type=int, default=2, help="0 improved Euler, 1 Heun, 2 RK4")
    ap.add_argument("--dither-v", type=float, default=ex.DITHER_V)
    ap.add_argument("--band", type=float, nargs=2, default=ex.DITHER_BAND_HZ)
    a = ap.parse_args()
    p = hg.Params(**{k: float(v) for k, v in (s.split("=") for s in a.sets)})
    gains = hg.read_ini()[0]
    dt = 0.001
    n = int(a.seconds / dt)
    t = np.arange(n) * dt
    if a.program == "latch":      # joint commands: 1 s at rest, 3 s down at 2 mm/s, 0.5 s, 0.6 s up
        cycle = np.r_[np.zeros(1000), -0.002 * np.arange(1, 3001), np.full(500, -6.0), -6.0 + 0.01 * np.arange(1, 601)]
        pose = None
        cmd = np.repeat(np.resize(cycle, n)[:, None], 6, axis=1)
    elif a.program == "trains":     # the trains' program (hexaglide excite --trains): vertical strokes
        pose = np.zeros((n, 6))
        pose[:, 2] = ex.strokes(n, dt)
    else:
        e = argparse.Namespace(ini=hg.DEFAULT_INI, margin=0.8, max_volts=4.0, harmonics=5, period=8.0, grid=160,
                               segment=0.2, starts=1, maxiter=15)
        prob = ex.Problem(e, hg.Params())
        th, _ = ex.design(e, prob, np.random.default_rng(1))
        pose = prob.fourier.eval(th, t)[0]
    if pose is not None:
        cmd = np.array([hg.ik(x) for x in pose])
    if a.program == "fourier":        # from HOME at rest to the program's start (tune's lead-in)
        import hexaglide_tune as tune
        cmd = tune.lead_in(cmd, 1000)[0][:n]

    dither = ex.dither(n, dt, a.band, a.dither_v) if a.dither_v > 0 else np.zeros((n, 6))
    dither[t < 1.0] = 0.0
    b = hg.Board(params=p, substeps=a.substeps, integrator=a.integrator)
    g = [hg.pid_gains(x) for x in gains]
    st = [hg.PidState() for _ in range(6)]
    scale = [x["INPUT_SCALE"] for x in gains]
    rows = []
    out = b.outputs
    for i in range(n):
        read = np.r_[list(out.count)[:6], np.array(list(out.pos)[:6]) * 1e3]   # before this period's DAC write
        fb = [read[k] / scale[k] for k in range(6)]
        v = [hg._pid_calc(C.byref(g[k]), C.byref(st[k]), float(cmd[i, k]), fb[k], 1, 0, 1000000) + dither[i, k]
             for k in range(6)]
        out = b.step(v)
        if out.fault:
            sys.exit("train_record: the board faulted at period %d (code %d)" % (i, out.fault_code))
        rows.append(np.r_[cmd[i], read[:6], v, read[6:]])
    names = (["joint.%d.motor-pos-cmd" % j for j in range(6)] + ["motenc.0.enc-%02d-count" % j for j in range(6)] +
             ["motenc.0.dac-%02d-value" % j for j in range(6)] +
             ["motenc-hexaglide.0.joint-%d.pos" % j for j in range(6)])
    with open(a.out, "w") as f:
        f.write(" ".join(["sample"] + names) + "\n")
        for i, r in enumerate(rows):
            f.write("%d %s %s %s %s\n" % (i, " ".join("%.6f" % x for x in r[:6]), " ".join("%d" % x for x in r[6:12]),
                                           " ".join("%.6f" % x for x in r[12:18]),
                                           " ".join("%.5f" % x for x in r[18:24])))


if __name__ == "__main__":
    main()
