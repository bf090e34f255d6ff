"""hg_csv.py - the numeric CSV files the plotting tools read (plot_replay.py:
`hexaglide replay --csv`; plot_run.py: the headless front end's run): one
header line of column names, then rows of as many finite numbers. Every
defect is a CsvError naming the file, the line (and the column) and what is
wrong: a file that cannot be read (missing, a directory, unreadable), an
empty one, a header only, a row with too many or too few fields (a file cut
short), a field that is not a number, NaN or inf, a column the tool needs.
"""
import math
import re

import numpy as np

# a number as the C tools read one (strtod: ASCII digits, no '_'); Python's float() also takes
# "1_000" (1000) and other scripts' digits ("١٢": 12), which build/hexaglide and LinuxCNC refuse
_NUMBER = re.compile(r"\s*[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|nan|inf|infinity)\s*\Z", re.ASCII | re.I)


class CsvError(Exception):
    """A CSV that cannot be used: the message names the file, the line and the cause."""


def integer(text):
    """int(text) for a whole number as the C tools read one (ASCII digits, no '_': Python's int()
    takes "1_0"); ValueError else. argparse's type for integer options."""
    if not isinstance(text, str) or not re.match(r"\s*[+-]?\d+\s*\Z", text, re.ASCII):
        raise ValueError("not a whole number: %r" % (text,))
    return int(text)


def number(text):
    """float(text) for a decimal number as the C tools read it (NaN and inf too: the caller
    says they are not finite); ValueError for anything else, "1_000" and non-ASCII digits too."""
    if not isinstance(text, str) or not _NUMBER.match(text):
        raise ValueError("not a number: %r" % (text,))
    return float(text)


def text_lines(path):
    """The lines of the text file path (a .gz one unpacked); CsvError naming the file and the cause
    for one that cannot be read, a .gz cut short, bytes that are not text, or a last line without
    its newline (a copy or a run that stopped while writing: "-2." of "-2.87"; the recorders and
    halsampler end every line)."""
    import gzip
    import zlib
    gz = path.endswith(".gz")
    try:
        with (gzip.open if gz else open)(path, "rt") as f:
            text = f.read()
        if text and not text.endswith(("\n", "\r")):
            lines = text.splitlines()
            raise CsvError("%s: line %d, the last, has no newline: the file may be cut short (%r); if it is "
                           "whole, end it with a newline" % (path, len(lines), lines[-1][-40:]))
        return text.splitlines()
    except EOFError:
        raise CsvError("%s: the compressed file ends before its end-of-stream marker (cut short?): "
                       "copy or compress it again" % path)
    except (OSError, zlib.error) as ex:
        raise CsvError("%s: cannot read it%s: %s" % (path, " as gzip" if gz else "", getattr(ex, "strerror", None) or ex))
    except UnicodeDecodeError as ex:
        raise CsvError("%s: cannot read it as text (%s): give joint commands as text, one line per servo period"
                       % (path, ex))


def read(path, need=(), what="the CSV this tool reads"):
    """(names, columns): the header's names and a dict name -> float64 array
    of the rows; need: columns that must be there (else an error saying the
    file is not `what`)."""
    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as ex:
        raise CsvError("%s: cannot read it: %s" % (path, ex.strerror or ex))
    if b"\0" in raw:
        raise CsvError("%s: line %d: binary data, not a CSV" % (path, raw[:raw.index(b"\0")].count(b"\n") + 1))
    lines = raw.decode("utf-8", errors="replace").split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    if not lines:
        raise CsvError("%s: the file is empty: no header line" % path)
    names = [x.strip() for x in lines[0].rstrip("\r").split(",")]
    if len(set(names)) != len(names):
        dup = next(n for n in names if names.count(n) > 1)
        raise CsvError("%s: line 1: column '%s' appears twice" % (path, dup))
    check_columns(path, names, need, what)
    rows = []
    for no, line in enumerate(lines[1:], 2):
        fields = line.rstrip("\r").split(",")
        if len(fields) != len(names):
            raise CsvError("%s: line %d: %d fields, the header names %d (a file cut short?)"
                           % (path, no, len(fields), len(names)))
        vals = []
        for i, x in enumerate(fields):
            try:
                v = number(x)
            except ValueError:
                v = None
            if v is None or not math.isfinite(v):
                raise CsvError("%s: line %d, field %d (%s): '%s' is not a finite number"
                               % (path, no, i + 1, names[i], x.strip()))
            vals.append(v)
        rows.append(vals)
    if not rows:
        raise CsvError("%s: a header and no rows: nothing to plot" % path)
    data = np.array(rows)
    return names, {n: data[:, i] for i, n in enumerate(names)}



def check_columns(path, names, need, what="the CSV this tool reads"):
    """CsvError naming the first of need that names lacks (the file is not `what`)."""
    for n in need:
        if n not in names:
            raise CsvError("%s: line 1: no column '%s': not %s" % (path, n, what))
