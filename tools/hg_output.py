"""hg_output.py - the output files of the Python tools (tune, identify, excite,
plot_replay.py), by the rules of build/hexaglide's (src/cli/cli_tree.c):
a path naming a symlink is its target's (the link stays a link); a regular
file, or a new one, is written to a temporary beside it and renamed onto it
when complete (never a half file); a FIFO or device that exists is written
straight into; a directory, or a directory that does not exist, is an error.
"-" is standard output (the Unix idiom, cli_out_is_stdout): never a file named "-"
(./- names one); an output that cannot go to standard output refuses it.
Every error is an OutputError naming the path and the cause.
"""
import os
import tempfile


class OutputError(Exception):
    """An output that cannot be written: the message names the path and why."""


STDOUT = "-"
_NOT_STDOUT = "'-' is standard output, which %s is not written to; give a path (./- names one called '-')"


def refuse_stdout(outputs):
    """OutputError if an output ((option, path) pairs, None paths skipped) is "-", standard
    output, which these outputs are not written to."""
    for o, p in outputs:
        if p == STDOUT:
            raise OutputError("%s -: %s" % (o, _NOT_STDOUT % o))


def target(path):
    """Where writing path goes: symlinks followed (a dangling one's target too).
    OutputError for "-" (refuse_stdout: an output a tool did not take as standard output),
    a directory or a missing directory."""
    if path == STDOUT:
        raise OutputError("cannot write -: %s" % (_NOT_STDOUT % "this output"))
    p = path
    for _ in range(40):
        if not os.path.islink(p):
            break
        p = os.path.join(os.path.dirname(p), os.readlink(p))   # an absolute link replaces it all
    else:
        raise OutputError("cannot write %s: too many levels of symbolic links" % path)
    if os.path.isdir(p):
        raise OutputError("cannot write %s: it is a directory; give a file" % path)
    d = os.path.dirname(p) or "."
    if not os.path.isdir(d):
        raise OutputError("cannot write %s: no directory %s" % (path, d))
    return p


def check_writable(path):
    """OutputError now, before the work, when path cannot be written as atomic_write will:
    target's refusals, then a temporary file that its directory does not take (no permission,
    a read-only file system). A FIFO or device is not probed (opening it could block)."""
    p = target(path)
    if os.path.exists(p) and not os.path.isfile(p):
        return
    d = os.path.dirname(p) or "."
    try:
        fd, tmp = tempfile.mkstemp(dir=d, prefix=".tmp-")
        os.close(fd)
        os.unlink(tmp)
    except OSError as ex:
        raise OutputError("cannot write %s: %s (a new file in %s)" % (path, ex.strerror or ex, d))


def check_writable_dir(path, names):
    """OutputError now, before the work, when the files names cannot be written into the directory
    path (made when missing, as the tools' plot savers make it): in a directory that exists,
    check_writable of each; for a missing one, a new directory that the first existing directory
    above it does not take (no permission, a read-only file system), or a file in the way."""
    if path == STDOUT:
        raise OutputError("cannot write into -: %s" % (_NOT_STDOUT % "this output"))
    if os.path.isdir(path):
        for n in names:
            check_writable(os.path.join(path, n))
        return
    if os.path.lexists(path):
        raise OutputError("cannot write into %s: not a directory; give a directory" % path)
    parent = os.path.dirname(os.path.abspath(path))
    while not os.path.lexists(parent):     # os.makedirs makes the rest below it
        parent = os.path.dirname(parent)
    if not os.path.isdir(parent):
        raise OutputError("cannot make the directory %s: %s is not a directory" % (path, parent))
    try:
        os.rmdir(tempfile.mkdtemp(dir=parent, prefix=".tmp-"))
    except OSError as ex:
        raise OutputError("cannot make the directory %s: %s (a new directory in %s)" % (path, ex.strerror or ex, parent))


def same(a, b):
    """True if outputs a and b would write the same file (symlinks followed; either may be
    missing, or in a directory that is still to be made)."""
    ra, rb = os.path.realpath(a), os.path.realpath(b)
    if ra == rb:
        return True
    try:
        return os.path.samefile(ra, rb)         # (a hard link)
    except OSError:
        return False


def refuse_same(outputs):
    """OutputError if two outputs ((option, path) pairs, None paths skipped) would write one file."""
    outs = [(o, p) for o, p in outputs if p]
    for i, (oa, pa) in enumerate(outs):
        for ob, pb in outs[i + 1:]:
            if same(pa, pb):
                raise OutputError("%s %s and %s %s name the same file; give two files" % (oa, pa, ob, pb))


def refuse_in_dir(output, plots, names):
    """OutputError if the file output ((option, path)) would be written where the directory
    plots ((option, dir), made when missing) is, inside it, or as one of the files names that go
    into it. Either path None: nothing to check."""
    (oo, op), (do, dp) = output, plots
    if not op or not dp:
        return
    what = "%s writes %s into it" % (do, ", ".join(names))
    if same(op, dp):
        raise OutputError("%s %s and %s %s name the same path: %s writes a file there, %s a directory (%s); "
                          "give two paths" % (oo, op, do, dp, oo, do, what))
    if os.path.realpath(dp).startswith(os.path.realpath(op) + os.sep):
        raise OutputError("%s %s is inside %s %s, a file %s writes; give two paths" % (do, dp, oo, op, oo))
    for n in names:
        if same(op, os.path.join(dp, n)):
            raise OutputError("%s %s and %s %s name the same file, %s (%s); give %s another file"
                              % (oo, op, do, dp, os.path.join(dp, n), what, oo))


def refuse_inputs(outputs, inputs):
    """OutputError if an output would overwrite a file the command reads (cli_out_is_input's rule):
    outputs and inputs are (option, path) pairs, "" for a positional input, None paths skipped."""
    for oo, op in outputs:
        if not op:
            continue
        t = os.path.abspath(target(op))
        for io, ip in inputs:
            if ip and os.path.isfile(ip) and os.path.exists(t) and os.path.samefile(t, ip):
                raise OutputError("%s %s names the file the command reads (%s%s): it would be overwritten; give "
                                  "another file" % (oo, op, io + " " if io else "", ip))


def atomic_write(path, write):
    """write(file) into path (binary) by the rules above: a regular file through a
    temporary and a rename, never half written; OutputError when anything fails."""
    p = target(path)
    tmp = None
    try:
        if os.path.exists(p) and not os.path.isfile(p):   # a FIFO, a device: straight into it
            with open(p, "wb") as f:
                write(f)
            return
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(p) or ".", prefix=".tmp-", suffix=os.path.splitext(p)[1])
        with os.fdopen(fd, "wb") as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        if os.path.isfile(p):                    # a file replaced keeps its mode
            mode = os.stat(p).st_mode & 0o7777
        else:
            umask = os.umask(0)
            os.umask(umask)
            mode = 0o666 & ~umask                # a new file: as open() makes one (mkstemp made it 0600)
        os.chmod(tmp, mode)
        os.replace(tmp, p)
        tmp = None
    except OSError as ex:
        raise OutputError("writing %s failed: %s%s" % (path, ex.strerror or ex, " (nothing written)" if tmp else ""))
    finally:
        if tmp and os.path.exists(tmp):
            os.unlink(tmp)
