#!/usr/bin/python3
"""backlash_sweep.py SEED N - random flexible drive trains with backlash through the board
(docs/dynamics.md, "Stability"): stiffness, damping, rotor inertia, lead, carriage mass and
backlash drawn over two to three decades each, a random scheme and constant volts (random, or
0 V) for 100 periods at the substeps the board chooses. Prints how many ran, how many the
board refused (no count up to 64 integrates them) and every run that faulted, with its code
and period. Not a test: the sets are hostile on purpose, and a run may strike a limit."""
import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
import hexaglide as hg  # noqa: E402

rng = random.Random(int(sys.argv[1]) if len(sys.argv) > 1 else 1)
n_sets = int(sys.argv[2]) if len(sys.argv) > 2 else 100
faults, refused, ran = [], 0, 0
for _ in range(n_sets):
    kw = dict(k_axial=10 ** rng.uniform(6, 8.5), c_axial=10 ** rng.uniform(1, 3.5), j_rotor=10 ** rng.uniform(-6.5, -3),
              lead=10 ** rng.uniform(-2.5, 0), m_carriage=10 ** rng.uniform(0, 1.5), backlash=10 ** rng.uniform(-6.5, -3))
    scheme = rng.choice(["improved-euler", "heun", "rk4"])
    try:
        b = hg.Board(params=hg.Params(**kw), integrator=hg.integrator_id(scheme))
    except (ValueError, hg.HexaglideError):
        refused += 1
        continue
    volts = [rng.uniform(-10, 10) for _ in range(6)] if rng.random() < 0.7 else [0.0] * 6
    o = b.step(volts)
    if o.fault or o.param_error:
        refused += 1
        continue
    ran += 1
    for period in range(1, 100):
        o = b.step(volts)
        if o.fault:
            faults.append((kw, scheme, o.substeps_run, o.fault_code, period))
            break
print("ran %d, refused %d, faulted %d" % (ran, refused, len(faults)))
for kw, scheme, n, code, period in faults:
    print("  %s, %s, %d substeps: code %d (%s) at period %d" % (
        ", ".join("%s=%.4g" % kv for kv in kw.items()), scheme, n, code, hg.strerror(code), period))
