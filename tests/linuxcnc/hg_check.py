"""hg_check.py - helpers of the tests/linuxcnc checks: TAP lines and the
front end's outputs (TAG.json, TAG.csv written by configs/hexaglide_headless.py)."""
import json
import sys

import numpy as np


def check(ok, what):
    """Print one TAP line; return ok."""
    print(("ok - " if ok else "not ok - ") + what)
    return bool(ok)


def report(stem):
    """The front end's JSON report, or exit after a failed check."""
    try:
        with open(stem + ".json") as f:
            return json.load(f)
    except Exception as ex:
        check(False, "front end wrote its report %s.json: %s" % (stem, ex))
        sys.exit(0)


def samples(stem):
    """Sampled pins as a function name -> column, or exit after a failed check."""
    try:
        with open(stem + ".csv") as f:
            names = f.readline().strip().split(",")
        d = np.loadtxt(stem + ".csv", delimiter=",", skiprows=1, ndmin=2)
    except Exception as ex:
        check(False, "sampled data %s.csv: %s" % (stem, ex))
        sys.exit(0)
    return lambda n: d[:, names.index(n)]
