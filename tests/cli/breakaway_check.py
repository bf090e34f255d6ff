#!/usr/bin/python3
"""breakaway_check.py RECORD... [--set NAME=VALUE]... [--truth NAME=VALUE]... [--fine COUNTS_PER_M]
[--split S]

What `hexaglide identify`'s stick-slip fit of f_breakaway[k] does on a
record, per carriage, against the truth (not a test; the numbers of
docs/identification.md, "Why the breakaway's sigma was too small"):
the fit with the other carriages free (inertia 1/W_kk) and held (M_kk)
during a slip, with identify's other estimates and with the truth's (a
board record's in.param-* values, then --truth: spec names, SI), its RMS
in counts, the block bootstrap over the slow stretches, the jackknife
over the distinct motions (a program's repeats), the stretches and their
own fits. --split S: besides, the free fit (truth's parameters) of the
events that start before S seconds (LinuxCNC's homing) and of the rest,
and how many events knock across the backlash (the encoder less the
carriage spans more than half the truth's backlash). --fine: counts of
this many per metre from the record's exact carriage positions (a board
record's out.z, a sampler recording's scale column) instead of the
encoder's: is it the counts' quantization?"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import numpy as np  # noqa: E402
import hexaglide_identify as hi  # noqa: E402
import hexaglide_trainid as trainid  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("records", nargs="+")
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--truth", action="append", default=[])
    ap.add_argument("--fine", type=float, default=0.0)
    ap.add_argument("--split", type=float, default=None)
    ap.add_argument("--ini", default=os.path.join(HERE, "..", "..", "configs", "hexaglide.ini"))
    a = ap.parse_args()
    s = hi.Settings()
    runs = [hi.read_run(p, a.ini) for p in a.records]
    for r in runs if a.fine else ():
        r.counts = np.floor(np.asarray(r.carriage) * a.fine)
        r.count_scale = np.full(6, a.fine)
    params = hi.known_params(runs, a.set)
    reg = hi.Regressor(params)
    ts = trainid.Settings()
    pieces = [hi.usable_stretches(r, hi.Settings()) for r in runs]
    trains = trainid.estimate_slow(runs, params, pieces, ts, lambda *x: None)
    for r in runs:
        if r.carriage is not None and trainid.flexible(trains):
            r.deflection = trainid.deflection(r, params, params["k_axial"], params["backlash"], ts)
    runs = [r for r in runs if trainid.dithered(r, ts).mean() <= 0.5]
    eqs = [hi.equations(r, reg, params, s) for r in runs]
    base = hi.StructuralBase(reg)
    est = hi.estimate(eqs, base, hi.prior_pi(params))
    truth = hi.params_copy(params)
    for name, v in list((getattr(runs[0], "recorded", None) or {}).items()) + \
            [(x.partition("=")[0], float(x.partition("=")[2])) for x in a.truth]:
        try:
            truth[name] = v
        except KeyError:
            pass
    fb_true = truth["f_static"] - truth["f_coulomb"]
    sd = hi.SlowData(runs, reg, params, s, base)
    thetas = {"estimates": np.where(est.ident, est.theta_ls, 0.0),
              "truth": base.base_values(hi.prior_pi(truth))}
    g = fb_true * np.linspace(0.7, 1.3, 61) if fb_true > 0 else np.linspace(-5, 20, 61)
    print("# %s; truth f_breakaway %g N%s" % (", ".join(r.path for r in runs), fb_true,
                                              "; counts of %g per m from the exact positions" % a.fine
                                              if a.fine else ""))
    rng = np.random.default_rng(1)
    for k in range(6):
        evs = sd.events[k]
        if not evs:
            print("carriage %d: no events" % k)
            continue
        blocks = np.array([(e[0] << 32) + e[5] for e in evs], dtype=np.int64)
        mot = hi.same_motions(blocks, sd.states[k], s)
        n = sum(e[2] for e in evs)
        for tag, th in thetas.items():
            fits = []
            for held in (False, True):
                L = sd.losses(k, th, params, g, sd.forces(th, held))[s.event_s]
                fits.append(hi._vertex(g, L.sum(1)))
                if not held:
                    L0 = L
            rms = np.sqrt(L0.sum(1).min() / n) * sd.per[0]["scale"][k]
            boot = np.std(hi._boot_vertices(g, L0, blocks, s.boot, rng))
            um = np.unique(mot)
            jk = np.array([hi._vertex(g, L0[:, mot != m].sum(1)) for m in um])
            jsd = np.sqrt((len(um) - 1) / len(um) * ((jk - jk.mean()) ** 2).sum())
            print("carriage %d, %-9s free %.2f N (%+.2f%%), held %.2f N (%+.2f%%), middle %+.2f%%; RMS %.2f counts; "
                  "bootstrap over %d stretches %.2f N, x sqrt(stretches/motions) %.2f N; jackknife over %d motions "
                  "%.2f N" % (k, tag, fits[0], 100 * (fits[0] / fb_true - 1), fits[1], 100 * (fits[1] / fb_true - 1),
                              100 * (0.5 * (fits[0] + fits[1]) / fb_true - 1), rms, len(set(blocks.tolist())),
                              boot, boot * np.sqrt(len(set(blocks.tolist())) / len(um)), len(um), jsd))
        L = L0
        parts = []
        for b in np.unique(blocks):
            sel = blocks == b
            e0 = evs[int(np.flatnonzero(sel)[0])]
            parts.append("%.1fs:%d:%.1f" % (e0[1] * runs[e0[0]].dt, sel.sum(), hi._vertex(g, L[:, sel].sum(1))))
        print("  stretches (start s:events:own fit N, truth's parameters): " + " ".join(parts))
        if a.split is not None:
            before = np.array([e[1] * runs[e[0]].dt < a.split for e in evs])
            fits = ["%d events, %.2f N" % (sel.sum(), hi._vertex(g, L[:, sel].sum(1))) if sel.any() else "no events"
                    for sel in (before, ~before)]
            line = "  before %g s: %s; after: %s" % (a.split, fits[0], fits[1])
            if truth["backlash"] > 0 and all(getattr(r, "deflection", None) is not None for r in runs):
                span = np.array([np.ptp(runs[e[0]].deflection[e[1]:e[1] + e[2] + 2, k]) for e in evs])
                knock = span > 0.5 * truth["backlash"]
                line += "; knocking (the deflection spans > backlash/2): %d of %d before, %d of %d after" % (
                    (knock & before).sum(), before.sum(), (knock & ~before).sum(), (~before).sum())
            print(line)


if __name__ == "__main__":
    main()
