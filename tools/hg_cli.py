"""hg_cli.py - the Python tools' command lines (tune, identify, excite) by
build/hexaglide's rules (src/cli/cli_parse.c, src/cli/main.c): an option
that takes a value is given once (a second is refused naming both values)
and never empty, while an option with action="append" (--set, --param)
repeats; a result or --help that cannot be written to standard output (a
full disk, a closed descriptor) is an error naming the cause, exit 1.
"""
import argparse
import errno
import os
import sys


class _Once(argparse.Action):
    """store, refusing a second occurrence of the option and an empty value."""

    def __call__(self, parser, namespace, values, option_string=None):
        name = max(self.option_strings, key=len) if self.option_strings else self.metavar or self.dest
        if isinstance(values, str) and not values.strip():
            parser.error("%s: an empty value; give %s" % (name, self.metavar or "one"))
        if self.option_strings and self.dest in parser.given:
            parser.error("%s given twice (%s and %s); give it once" % (name, parser.given[self.dest], values))
        parser.given[self.dest] = values
        setattr(namespace, self.dest, values)


class Parser(argparse.ArgumentParser):
    """An ArgumentParser whose plain options (action "store") are given once, never empty, and
    spelled out (no abbreviations)."""

    def __init__(self, *args, **kw):
        kw.setdefault("allow_abbrev", False)    # --eval is not --evaluate (build/hexaglide refuses it too)
        super().__init__(*args, **kw)
        self.register("action", None, _Once)
        self.register("action", "store", _Once)
        self.given = {}

    def parse_known_args(self, args=None, namespace=None):
        self.given = {}                    # each parse counts its own options
        return super().parse_known_args(args, namespace)


def out_of_range(a, ranges, names=None):
    """The message naming the first option of names (default every one of ranges) whose value
    on a (argparse's namespace) lies outside its range, else None. ranges: {"--opt": (lowest,
    highest, lowest allowed?, what it is)}; whole numbers when lowest is an int."""
    for opt in names or ranges:
        lo, hi, lo_in, what = ranges[opt]
        v = getattr(a, opt[2:].replace("-", "_"))
        if not ((lo <= v if lo_in else lo < v) and v <= hi):
            rng = "%d..%d" % (lo, hi) if isinstance(lo, int) else "%s%g, %g]" % ("[" if lo_in else "(", lo, hi)
            shown = ("%g" % v if float("%g" % v) == v else repr(v)) if isinstance(v, float) else v  # 250.0001: not 250
            return "%s %s: must be in %s (%s)" % (opt, shown, rng, what)
    return None


def run(main, log, caught=()):
    """sys.exit with main()'s code; an exception of caught is logged, exit 1; standard output
    closed, or a write to it failing (also --help's), is logged naming the cause, exit 1."""
    if sys.stdout is None:             # (Python's for a closed descriptor 1)
        log("writing stdout failed: %s" % os.strerror(errno.EBADF))
        sys.exit(1)
    try:
        try:
            rc = main()
        except SystemExit as ex:           # argparse's --help and errors
            rc = ex.code
        sys.stdout.flush()
    except caught as ex:
        log(ex)
        rc = 1
    except OSError as ex:
        if ex.errno not in (errno.ENOSPC, errno.EPIPE, errno.EBADF, errno.EIO) or ex.filename is not None:
            raise
        log("writing stdout failed: %s" % os.strerror(ex.errno))
        try:                               # nothing more to flush at exit
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        except OSError:
            pass
        rc = 1
    sys.exit(rc)
