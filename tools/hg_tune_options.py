"""hg_tune_options.py - the options both tuners take (tools/hexaglide_tune.py for
the Hexaglide, tools/hexaglide_tune_serial.py for the serial plant): their
ranges and the --jobs option, below both (docs/tuning.md "Options")."""
import hg_csv

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
