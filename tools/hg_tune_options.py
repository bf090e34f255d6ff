"""hg_tune_options.py - what both tuners share (tools/hexaglide_tune.py for the
Hexaglide, tools/hexaglide_tune_serial.py for the serial plant): the options'
ranges and the --jobs option (docs/tuning.md "Options"), and the columns of a
recorded CSV trajectory (csv_columns)."""
import numpy as np

import hg_csv
import hg_program

# the options' ranges (docs/tuning.md "Options"): (lowest, highest, lowest allowed?, what it is)
# (hg_cli.out_of_range); the serial plant's tune takes those of its options
RANGES = {
    "--runs": (1, 16, True, "closed-loop runs per candidate"),
    "--maxiter": (1, 1000, True, "generations"),
    "--popsize": (1, 100, True, "members per search variable"),
    "--seed": (0, 2 ** 32 - 1, True, "the search's random seed"),
    "--jobs": (0, 1024, True, "threads, 0 for every core"),
    "--bandwidth": (0.0, 250.0, False, "Hz, above 0: the model start's closed-loop bandwidth, at most a quarter "
                    "of the 1 kHz servo rate"),
    "--damping": (0.0, 5.0, False, "above 0: the model start's damping ratio"),
    "--max-overshoot": (0.0, 1.0, True, "the step overshoot allowed, a fraction"),
}


def add_jobs_option(ap):
    """--jobs N, as both tuners take it (RANGES["--jobs"])."""
    ap.add_argument("--jobs", type=hg_csv.integer, default=0,
                    help="threads the closed-loop runs share (hg_batch; default 0: every core; at most %d); "
                    "the answer is the same for any number" % RANGES["--jobs"][1])


def csv_columns(path, header, hdr_no, rows, lines):
    """(rows, columns) array of a recorded CSV's rows (lists of numbers; lines[i]: the file line
    of rows[i]) under its header (the names, on line hdr_no); ValueError naming the line (and
    column) where a tuner would have to guess or would run a trajectory LinuxCNC never commanded:
    a column named twice (which of the two holds the joint commands?), a row of another width, a
    `sample` column (tools/hg_record.py's, halsampler -t's) that does not advance by 1 a line
    (samples missing, repeated or out of order), a `t_s` column (the headless runners') that does
    not advance by one servo period a line (hg_program.uneven_times)."""
    for i, name in enumerate(header):
        if name in header[:i]:
            raise ValueError("%s line %d: column %d is named %s, as column %d is: which one holds the recording "
                             "would be a guess; rename or remove one" % (path, hdr_no, i + 1, name,
                                                                         header.index(name) + 1))
    for no, v in zip(lines, rows):
        if len(v) != len(header):
            raise ValueError("%s line %d has %d fields, the header %d" % (path, no, len(v), len(header)))
    data = np.array(rows, dtype=float).reshape(-1, len(header))
    if len(data) > 1 and "sample" in header:
        c = header.index("sample")
        n = data[:, c]
        bad = np.flatnonzero(np.diff(n) != 1)
        if len(bad):
            k = bad[0]
            raise ValueError("%s line %d: sample %.17g after sample %.17g (column %d, sample): %s; tune takes every "
                             "servo period in turn: record again"
                             % (path, lines[k + 1], n[k + 1], n[k], c + 1,
                                "samples missing (a gap in the recording)" if n[k + 1] > n[k] + 1
                                else "not the next sample (repeated or out of order)"))
    if len(data) > 1 and "t_s" in header:
        why = hg_program.uneven_times(path, data[:, header.index("t_s")], lines)
        if why:
            raise ValueError(why)
    return data
