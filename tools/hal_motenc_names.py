#!/usr/bin/python3
"""hal_motenc_names.py - the pin, parameter and function names of LinuxCNC's
hal_motenc driver (Vital Systems MOTENC-100), read from its source.

Writes tests/hal/hal_motenc_names.txt, the list that
tests/hal/test_motenc_interface compares the virtual board against. The
tests never run this script: they use the shipped list, so they do not need
a LinuxCNC source tree. Regenerate the list after moving to another
LinuxCNC version:

    git --git-dir=LINUXCNC.git show COMMIT:src/hal/drivers/hal_motenc.c >hal_motenc.c
    git --git-dir=LINUXCNC.git show COMMIT:src/hal/drivers/motenc.h >motenc.h
    tools/hal_motenc_names.py --commit COMMIT hal_motenc.c motenc.h \\
        --out tests/hal/hal_motenc_names.txt

Each hal_pin_*_newf / hal_param_*_newf call with a name "motenc.%d.NAME"
gives "pin|param TYPE DIR motenc.B.NAME" (B = --board), once per channel when
NAME holds %02d: the channel count is the bound of the for loop before the
call, evaluated with motenc.h's #defines and this->numFpga = --fpgas (2 on a
MOTENC-100 with both FPGAs, what the virtual board emulates). Each
rtapi_snprintf(name, ..., "motenc.%d.FUNCT") gives "funct motenc.B.FUNCT"
(the name of the hal_export_funct that follows). Lines are sorted bytewise
(LC_ALL=C), after a header naming the source files and the commit."""
import argparse
import os
import re
import sys
import tempfile

DIRS = {"HAL_OUT": "OUT", "HAL_IN": "IN", "HAL_IO": "I/O", "HAL_RW": "RW", "HAL_RO": "RO"}


def defines(header_text):
    """#define NAME EXPR lines of a C header as a dict (comments dropped)."""
    d = {}
    for m in re.finditer(r"^#define\s+(\w+)[ \t]+([^\n]*)$", header_text, re.M):
        d[m.group(1)] = re.sub(r"//.*|/\*.*?\*/", "", m.group(2)).strip()
    return d


def evaluate(expr, defs, depth=0):
    """Integer value of a C constant expression made of #defines, integers,
    + - * / and parentheses; ValueError for anything else."""
    if depth > 20:
        raise ValueError("#define nesting too deep in %r" % expr)
    out = re.sub(r"[A-Za-z_]\w*",
                 lambda m: "(%d)" % evaluate(defs[m.group(0)], defs, depth + 1)
                 if m.group(0) in defs else m.group(0), expr)
    if not re.fullmatch(r"[0-9+\-*/() \t]+", out):
        raise ValueError("cannot evaluate %r (gives %r)" % (expr, out))
    return int(eval(out.replace("/", "//"), {"__builtins__": {}}))  # digits and operators only


def names(source, defs, fpgas, board):
    """Sorted list of the lines "pin|param TYPE DIR motenc.B.NAME" and "funct motenc.B.NAME"."""
    src = source.replace("this->numFpga", "NUMFPGA__")
    defs = dict(defs, NUMFPGA__=str(fpgas))
    token = re.compile(
        r"for\s*\(\s*channel\s*=\s*0\s*;\s*channel\s*<\s*(?P<bound>[^;]+);"
        r"|hal_(?P<kind>pin|param)_(?P<type>\w+?)_newf\(\s*(?P<dir>HAL_\w+)\s*,[^\"]*\"motenc\.%d\.(?P<name>[^\"]+)\""
        r"|rtapi_snprintf\(\s*name\s*,[^\"]*\"motenc\.%d\.(?P<funct>[^\"]+)\"", re.S)
    out, bound = [], None
    prefix = "motenc.%d." % board
    for m in token.finditer(src):
        if m.group("bound"):
            bound = evaluate(m.group("bound"), defs)
        elif m.group("funct"):
            out.append("funct " + prefix + m.group("funct"))
        else:
            n = m.group("name")
            if m.group("dir") not in DIRS:
                raise ValueError("unknown direction %s of %s" % (m.group("dir"), n))
            if "%" in n:
                if n.count("%02d") != 1 or bound is None:
                    raise ValueError("%s: expected one %%02d inside a channel loop" % n)
                chans = [n.replace("%02d", "%02d" % c) for c in range(bound)]
            else:
                chans = [n]
            out += ["%s %s %s %s%s" % (m.group("kind"), m.group("type"), DIRS[m.group("dir")], prefix, c)
                    for c in chans]
    if len(set(out)) != len(out):
        raise ValueError("a name occurs twice")
    return sorted(out, key=lambda s: s.encode())


def main():
    """Parse the arguments, write the list (through a temporary file and a rename)."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("hal_motenc_c", help="LinuxCNC's src/hal/drivers/hal_motenc.c")
    ap.add_argument("motenc_h", help="LinuxCNC's src/hal/drivers/motenc.h (channel counts)")
    ap.add_argument("--commit", required=True, help="LinuxCNC commit the two files come from (named in the header)")
    ap.add_argument("--fpgas", type=int, default=2, help="FPGAs on the board (default 2, a full MOTENC-100)")
    ap.add_argument("--board", type=int, default=0, help="board number in the names (default 0)")
    ap.add_argument("--out", help="output file (default: standard output)")
    a = ap.parse_args()
    try:
        with open(a.hal_motenc_c) as f:
            source = f.read()
        with open(a.motenc_h) as f:
            defs = defines(f.read())
        lines = names(source, defs, a.fpgas, a.board)
    except (OSError, ValueError, KeyError) as ex:
        sys.exit("hal_motenc_names: %s" % ex)
    if not any(l.startswith("funct ") for l in lines) or not any(l.startswith("pin ") for l in lines):
        sys.exit("hal_motenc_names: %s has no motenc pins or functions: is it hal_motenc.c?" % a.hal_motenc_c)
    count = {k: sum(l.startswith(k + " ") for l in lines) for k in ("pin", "param", "funct")}
    text = ("# hal_motenc_names.txt - every pin, parameter and function LinuxCNC's hal_motenc\n"
            "# exports for board %d of a MOTENC-100 with %d FPGAs: %d pins, %d parameters, %d functions.\n"
            "# Source: LinuxCNC src/hal/drivers/hal_motenc.c and motenc.h at commit %s.\n"
            "# Written by tools/hal_motenc_names.py (see there to regenerate); do not edit.\n"
            "# Lines: pin|param TYPE DIR NAME, or funct NAME; sorted bytewise.\n"
            % (a.board, a.fpgas, count["pin"], count["param"], count["funct"], a.commit)) + "".join(l + "\n" for l in lines)
    if not a.out:
        sys.stdout.write(text)
        return
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(a.out)), prefix=".hal_motenc_names.")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.chmod(tmp, 0o644)
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
