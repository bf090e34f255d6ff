"""fmu_lib.py - shared by the tests of tests/fmu (not a test itself): TAP
lines, the paths `make fmu` builds, fmusim runs and its CSV output."""
import csv
import os
import subprocess
import sys
import tempfile

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
BUILD = os.path.join(ROOT, "build")
FMU = os.path.join(BUILD, "hexaglide.fmu")
FMUSIM = os.path.join(BUILD, "fmu", "fmusim")
HEXAGLIDE = os.path.join(BUILD, "hexaglide")
TMP = tempfile.mkdtemp(prefix="hg-fmu-test-")
fails = 0


def check(cond, what):
    """One TAP line; counts a failure."""
    global fails
    print("%s - %s" % ("ok" if cond else "not ok", what))
    sys.stdout.flush()
    fails += 0 if cond else 1
    return cond


def need(*paths):
    """Exit with a failure when something `make fmu` builds is missing."""
    missing = [p for p in paths if not os.path.exists(p)]
    if missing:
        print("not ok - %s not built (make fmu)" % ", ".join(os.path.relpath(p, ROOT) for p in missing))
        sys.exit(1)


def done():
    """Exit status of the test."""
    sys.exit(1 if fails else 0)


def fmusim(fmu, *args, out=None):
    """Run fmusim on fmu (co-simulation) with args; (exit code, its messages, rows of the output CSV or None)."""
    out = out or os.path.join(TMP, "out.csv")
    if os.path.exists(out):
        os.remove(out)
    p = subprocess.run([FMUSIM, "--interface-type", "cs", "--output-file", out] + [str(a) for a in args] + [fmu],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    rows = read_csv(out) if os.path.exists(out) else None
    return p.returncode, p.stdout, rows


def read_csv(path):
    """fmusim's CSV as (header, rows of strings)."""
    with open(path) as f:
        r = list(csv.reader(f))
    return r[0], r[1:]


def write_input(path, names, rows):
    """An fmusim input file: a time column, then names."""
    with open(path, "w") as f:
        f.write(",".join(["time"] + list(names)) + "\n")
        for r in rows:
            f.write(",".join(repr(float(v)) if not isinstance(v, str) else v for v in r) + "\n")
    return path


def column(table, name):
    """A column of fmusim's CSV as floats."""
    header, rows = table
    i = header.index(name)
    return [float(r[i]) for r in rows]
