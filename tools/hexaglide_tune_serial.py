#!/usr/bin/python3
"""hexaglide_tune_serial.py - `hexaglide tune` for the serial-axis plant
(docs/serial.md): LinuxCNC's pid around the virtual board's serial axes
(src/hg_loop.c, the plant src/hg_plant_serial.c), in the config's own units.

The loop's units are the INI's, exactly as its HAL file scales the board:
motenc_motion.hal sets enc-NN-scale to [JOINT_N]INPUT_SCALE (counts per
inch in the stock MOTENC config) and dac-NN-gain to OUTPUT_SCALE (volts per
PID output unit), and hg_loop applies the same two numbers, read from the
same INI, so the commands, feedback and following errors are in inches
here. The machine is the INI's [SERIAL] section (the HAL file's setp lines
read it too).

Started by tools/hexaglide_tune.py when the plant is serial (`--plant
serial`, or an INI with a [SERIAL] section and no [HEXAGLIDE]); see
docs/tuning.md and docs/serial.md. stdout: [JOINT_N] sections, then the
predicted peak following error per joint. Exit 0 ok, 1 no stable gains, 2
bad input.

The Hexaglide's own parts of tune are not run here, and the output says so:
the stability margins at HOME (tools/hg_margins.py linearizes the
Hexaglide's coupled six-joint model), the tool-path error (the Hexaglide's
pose error from its kinematics; with trivkins it is the joints' errors
themselves) and the notch (against the Hexaglide's structural mode). A
serial axis's stability is checked here on a step response instead."""
import configparser
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hexaglide as hg  # noqa: E402
import hg_config  # noqa: E402
import hg_csv  # noqa: E402
import hg_cli  # noqa: E402
import hg_output  # noqa: E402
import hg_identify_base as ib  # noqa: E402
import hg_program  # noqa: E402
import hg_tune_options  # noqa: E402

PERIOD_S = hg_program.PERIOD_S
MIN_SAMPLES = 200
SETTLE = 500                      # periods at rest before the trajectory
SEARCH_KEYS = ["P", "FF1", "FF2"]
# [JOINT_N] keys LinuxCNC's stock MOTENC HAL file (motenc_motion.hal, tests/linuxcnc/vitalsystems) sets, and where
HAL_KEYS = {"P": "pid.%d.Pgain", "I": "pid.%d.Igain", "D": "pid.%d.Dgain", "FF0": "pid.%d.FF0", "FF1": "pid.%d.FF1",
            "FF2": "pid.%d.FF2", "BIAS": "pid.%d.bias", "DEADBAND": "pid.%d.deadband", "MAX_OUTPUT": "pid.%d.maxoutput",
            "INPUT_SCALE": "motenc.0.enc-%02d-scale", "OUTPUT_SCALE": "motenc.0.dac-%02d-gain",
            "OUTPUT_OFFSET": "motenc.0.dac-%02d-offset"}
OUT_KEYS = ["P", "I", "D", "FF0", "FF1", "FF2", "DEADBAND"]
# the options' ranges, as the Hexaglide's tune has them (hg_cli.out_of_range)
RANGES = {k: hg_tune_options.RANGES[k] for k in ("--max-overshoot", "--maxiter", "--popsize", "--seed", "--jobs")}
SKIPPED = ("# not run for the serial plant: the margins at HOME (tools/hg_margins.py linearizes the "
           "Hexaglide's coupled joints), the tool-path error (the Hexaglide's pose from its kinematics; with "
           "trivkins each axis's error is its joint's f-error, above) and the notch (the Hexaglide's structural "
           "mode); each axis's stability is checked on a step response instead")


class BadInput(Exception):
    """A user error: exit 2 with the message."""


def log(*a):
    print("hexaglide tune:", *a, file=sys.stderr, flush=True)


def _ini(path):
    cp = configparser.ConfigParser(strict=False, interpolation=None, comment_prefixes=("#", ";"))
    cp.optionxform = str.upper
    with open(path) as f:
        cp.read_string("".join(l for l in f if not l.startswith("#INCLUDE")))
    return cp


def read_ini_file(path, what):
    """The parsed INI file at path (what: "INI", "gains"), BadInput naming what is wrong."""
    if not os.path.isfile(path):
        raise BadInput("no such %s file: %s" % (what, path))
    try:
        return _ini(path)
    except configparser.Error as ex:
        raise BadInput("%s does not parse as an INI file: %s" % (path, ex))


def is_serial_ini(path):
    """True for an INI whose machine is the serial plant: a [SERIAL] section."""
    try:
        return _ini(path).has_section("SERIAL")
    except (OSError, configparser.Error):
        return False


class Machine:
    """What the INI says: joints, their pid keys and scales, the plant's parameters, the units."""

    def __init__(self, ini, model=None):
        cp = read_ini_file(ini, "INI")
        if not cp.has_section("SERIAL"):
            raise BadInput("%s has no [SERIAL] section: the serial plant's machine (docs/serial.md); add it, "
                           "or tune the Hexaglide without --plant serial" % ini)
        if model is None:
            coords = cp.get("TRAJ", "COORDINATES", fallback="").replace(" ", "")
            joints = cp.getint("KINS", "JOINTS", fallback=len(coords))
            if not coords or len(coords) != joints:
                raise BadInput("%s: [TRAJ]COORDINATES %r and [KINS]JOINTS %d do not name one axis per joint: "
                               "give --model (the axes, e.g. XYZ)" % (ini, coords, joints))
            model = coords.upper()
        self.model = model
        try:                           # [SERIAL] and [JOINT_N] as sim and LinuxCNC read them (the C reader)
            cfg = hg_config.read(ini, loop=True, cmd="tune", plant="serial", model=model)
        except ValueError as ex:       # (hg_config.ConfigError, an unknown model)
            raise BadInput(str(ex))
        try:
            hg_config.check_period(cfg, "tune", PERIOD_S, hg_program.PERIOD_WHY)
        except hg_config.ConfigError as ex:
            raise BadInput(str(ex))
        self.params, self.joints, self.n = cfg.params, cfg.joints, len(cfg.joints)
        for j, g in enumerate(self.joints):
            for k in HAL_KEYS:         # halcmd stops at a setp of a missing key; the tune would run pid.c's default
                if k not in g:
                    raise BadInput("%s: [JOINT_%d]%s is missing: LinuxCNC's MOTENC HAL file sets %s from it (LinuxCNC "
                                   "stops there: \"Ini variable '[JOINT_%d]%s' not found\"); add it"
                                   % (ini, j, k, HAL_KEYS[k] % j, j, k))
            for k in ("INPUT_SCALE", "OUTPUT_SCALE"):
                if not g.get(k):
                    raise BadInput("%s [JOINT_%d] needs a nonzero %s (the HAL file's enc/dac scale)" % (ini, j, k))
        self.unit = {"inch": "in", "in": "in", "mm": "mm", "metric": "mm"}.get(
            cp.get("TRAJ", "LINEAR_UNITS", fallback="mm").strip().lower(), "mm")
        self.rotary = [c in "ABC" for c in model]
        self.ini = ini
        board = hg.Board(plant="serial", kind=None, params=self.params)   # (a scale not the encoder's: said, run)
        for k, why in board.enc_scale_notes([g["INPUT_SCALE"] for g in self.joints]):
            log("warning: [JOINT_%d]INPUT_SCALE = %s" % (k, why))

    def unit_of(self, j):
        return "deg" if self.rotary[j] else self.unit

    def gains(self, overrides=None):
        """The loop's per-joint keys: the INI's pid keys and scales, overridden per joint."""
        out = []
        for j, g in enumerate(self.joints):
            d = {k: v for k, v in g.items() if k in hg.GAIN_KEYS or k in ("INPUT_SCALE", "OUTPUT_SCALE",
                                                                           "OUTPUT_OFFSET")}
            d.update((overrides or [{}] * self.n)[j])
            out.append(d)
        return out

    def ff1_model(self, j):
        """FF1 that commands the velocity-mode amplifier's speed: 10 V / (OUTPUT_SCALE V_RATED) in the
        INI's units (V_RATED from [SERIAL], mm/s or deg/s on HAL); None for torque mode."""
        pp = self.params
        if pp["amp_mode_%d" % j] < 0.5:
            return None
        v_si = pp["v_rated_%d" % j]
        v_user = v_si * (180 / np.pi if self.rotary[j] else (1000 / 25.4 if self.unit == "in" else 1000.0))
        return 10.0 / (self.joints[j]["OUTPUT_SCALE"] * v_user)


def load_trajectory(path, n):
    """Joint commands (rows, n) from a CSV of joint.N.motor-pos-cmd columns (LinuxCNC's sampled run,
    the headless runners' CSV; its columns checked as hg_tune_options.csv_columns checks them), comma
    or space separated; rows of n numbers without a header."""
    if not os.path.isfile(path):
        raise BadInput("no such trajectory file: %s" % path)
    try:
        with open(path, "rb") as f:
            is_record = f.readline().rstrip(b"\r\n") in hg.RECORD_MAGICS
    except OSError as ex:
        raise BadInput("%s: cannot read it: %s" % (path, ex.strerror or ex))
    if is_record:
        return load_record(path, n)
    header, hdr_no, rows, lines_of = None, 0, [], []
    try:
        lines = hg_csv.text_lines(path)
    except hg_csv.CsvError as ex:
        raise BadInput(str(ex))
    for no, line in enumerate(lines, 1):
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        fields = s.replace(",", " ").split()
        if header is None and not rows and not re.match(r"[-+0-9.]", fields[0]):
            header, hdr_no = fields, no
            continue
        try:
            vals = [hg_csv.number(x) for x in fields]
        except ValueError:
            raise BadInput("%s line %d does not parse as numbers: %r" % (path, no, s[:80]))
        if not np.all(np.isfinite(vals)):
            raise BadInput("%s line %d holds a NaN or infinite value" % (path, no))
        rows.append(vals)
        lines_of.append(no)
    if not rows:
        raise BadInput("%s: no samples" % path)
    if header is not None:
        try:
            a = hg_tune_options.csv_columns(path, header, hdr_no, rows, lines_of)
        except ValueError as ex:
            raise BadInput(str(ex))
        cols = []
        for j in range(n):
            name = "joint.%d.motor-pos-cmd" % j
            if name not in header:
                raise BadInput("%s: column %s missing (the serial plant's model has joints 0..%d)" % (path, name, n - 1))
            cols.append(header.index(name))
        if "halui.program.is-running" in header:      # the program, with its lead-in and tail kept
            span = hg_program.program_rows(a[:, header.index("halui.program.is-running")] > 0.5, a[:, cols])
            if span:
                a = a[max(0, span[0] - hg_program.LEAD_IN):min(len(a), span[1] + hg_program.LEAD_IN)]
        cmd = a[:, cols]
    else:
        for no, v in zip(lines_of, rows):
            if len(v) != n:
                raise BadInput("%s line %d: %d numbers; the model's %d joints need %d" % (path, no, len(v), n, n))
        cmd = np.array(rows)
    if len(cmd) < MIN_SAMPLES:
        raise BadInput("%s: %d samples; at least %d (%.1f s at 1 kHz)" % (path, len(cmd), MIN_SAMPLES,
                                                                        MIN_SAMPLES * PERIOD_S))
    return cmd


def load_record(path, n):
    """Joint commands (rows, n) from a board record of the serial plant (docs/replay.md), read as
    replay reads it: its joint.N.motor-pos-cmd columns, at tune's servo period. A record of another
    plant (the Hexaglide's joints are not this machine's axes) is refused."""
    import hexaglide_identify_serial as ids
    if not ids.is_serial_record(path):
        raise BadInput("%s is a board record of another plant than the serial one (its '# plant' line or "
                       "in.plant): the serial plant's tune takes a serial machine's record, or a CSV of its "
                       "joint.N.motor-pos-cmd" % path)
    want = ["joint.%d.motor-pos-cmd" % j for j in range(n)] + ["in.period-ns"]
    try:
        data, _, hdr_no, _ = ib.record_columns(path, want, "tune needs motion's joint commands (a record of "
                                               "tools/hg_record.py under LinuxCNC has them)")
    except ib.RecordError as ex:
        raise BadInput(str(ex))
    off = np.flatnonzero(data[:, n] != round(PERIOD_S * 1e9))
    if len(off):
        raise BadInput("%s line %d: in.period-ns %d: tune runs one line per %g s servo period" % (
            path, hdr_no + 1 + off[0], data[off[0], n], PERIOD_S))
    if len(data) < MIN_SAMPLES:
        raise BadInput("%s: %d samples; at least %d (%.1f s at 1 kHz)" % (path, len(data), MIN_SAMPLES,
                                                                        MIN_SAMPLES * PERIOD_S))
    return np.ascontiguousarray(data[:, :n])


def generated_move(m):
    """Each joint out and back over a quarter of its travel (at most 2 units) at its MAX_VELOCITY and
    MAX_ACCELERATION, toward - (the stock config's machine 0 is its + end)."""
    segs = [np.zeros((1, m.n))]
    for j in range(m.n):
        g = m.joints[j]
        dist = min(2.0, 0.25 * abs(g.get("MAX_LIMIT", 0.0) - g.get("MIN_LIMIT", -8.0)))
        prof = hg_program.s_curve(dist, g.get("MAX_VELOCITY", 1.0), g.get("MAX_ACCELERATION", 4.0))
        for path in (-prof, prof - dist):
            seg = np.repeat(segs[-1][-1:], len(prof), 0)
            seg[:, j] = path
            segs.append(seg)
    return np.vstack(segs)


def with_settle(cmd):
    """The commands relative to the first (the plant starts at rest at its power-up position 0), after
    SETTLE periods at rest there."""
    c = cmd - cmd[0]
    return np.vstack([np.zeros((SETTLE, c.shape[1])), c])


def run(m, gains, cmd):
    return hg.Loop(gains, params=m.params).run(cmd)


def step_command(m, j):
    """Joint j's step response command: 600 periods, a step of 200 counts (a count is 0.5 % of it)
    at period 100, the other joints at rest."""
    cmd = np.zeros((600, m.n))
    cmd[100:, j] = 200.0 / abs(m.joints[j]["INPUT_SCALE"])
    return cmd


def feedback_only(gains):
    """The gains without their feed-forward terms (which act outside the loop: a step's derivative
    would only kick it)."""
    return [dict(g, FF0=0.0, FF1=0.0, FF2=0.0, FF3=0.0) for g in gains]


def step_overshoot(r, cmd, j):
    """Overshoot (fraction) of joint j's step response r (a RunResult of step_command's cmd, with
    its f-error kept); inf when the run tripped or faulted."""
    if not r.ok:
        return np.inf
    step = cmd[-1, j]
    fb = (np.vstack([np.zeros((1, cmd.shape[1])), cmd[:-1]]) - r.ferror_mm)[:, j]
    return max(0.0, fb[100:].max() / step - 1.0)


def evaluate(m, gains, cmd):
    """(peak |f-error| per joint, peak |output| per joint, ok) over the trajectory."""
    r = run(m, gains, cmd)
    return r.peak_ferror_mm, r.peak_output_v, r.ok


def search(m, cmd, a, threads):
    """Per joint, P, FF1, FF2 by differential evolution on the peak f-error, refusing candidates whose
    step overshoots more than --max-overshoot or whose output saturates (MAX_OUTPUT); each
    generation's candidates (a trajectory run and a step run each) in one hg.batch over threads
    (the same answer for any number)."""
    from scipy.optimize import differential_evolution
    bp = m.params.board_params()
    best = []
    for j in range(m.n):
        ff1 = m.ff1_model(j)
        ff1_hi = 2.0 * ff1 if ff1 else 1.0
        p0 = m.joints[j].get("P", 1.0)
        bounds = [(np.log10(max(1.0, p0 / 10)), np.log10(max(10.0, p0 * 50))), (0.0, ff1_hi), (0.0, 0.01)]
        step_cmd = step_command(m, j)
        maxout = m.joints[j].get("MAX_OUTPUT", 0.0)

        def gains_of(x, j=j):
            o = [{} for _ in range(m.n)]
            o[j] = {"P": 10 ** x[0], "FF1": x[1], "FF2": x[2], "I": 0.0, "D": 0.0}
            return m.gains(o)

        def cost(x, traj, step, j=j, step_cmd=step_cmd, maxout=maxout):
            """x's cost from its trajectory run and its step run."""
            if not traj.ok or not np.isfinite(traj.peak_ferror_mm[j]):
                return 1e9
            ov = step_overshoot(step, step_cmd, j)
            c = traj.peak_ferror_mm[j]
            if ov > a.max_overshoot:
                c *= 1 + 100 * (ov - a.max_overshoot)
            if maxout > 0 and traj.peak_output_v[j] >= 0.999 * maxout:
                c *= 10
            return c

        def costs(_func, xs, j=j, step_cmd=step_cmd):
            """Every candidate of xs through one hg.batch (differential_evolution's map)."""
            xs = list(xs)
            jobs = []
            for x in xs:
                g = gains_of(x)
                jobs += [hg.Job(hg.loop_config(g, plant=m.params), bp, cmd),
                         hg.Job(hg.loop_config(feedback_only(g), plant=m.params), bp, step_cmd, keep=True)]
            res = hg.batch(jobs, threads)
            return [cost(x, res[2 * i], res[2 * i + 1]) for i, x in enumerate(xs)]

        res = differential_evolution(lambda x: costs(None, [x])[0], bounds, maxiter=a.maxiter,
                                     popsize=a.popsize, seed=(a.seed + j) % 2 ** 32, tol=1e-3, polish=False,
                                     x0=[np.log10(max(1.0, p0)), ff1 or 0.0, 0.0], updating="deferred",
                                     workers=costs)
        g = gains_of(res.x)[j]
        log("joint %d: P %.4g FF1 %.6g FF2 %.3g: peak |f-error| %.6g %s (%d candidates, two runs each)"
            % (j, g["P"], g["FF1"], g["FF2"], res.fun, m.unit_of(j), res.nfev))
        best.append({k: g[k] for k in ("P", "I", "D", "FF1", "FF2")})
    return best


def ini_text(m, gains, pred, stock, source):
    lines = ["# hexaglide tune (serial plant, model %s) for %s, trajectory %s" % (m.model, m.ini, source),
             "# units: the INI's (%s; INPUT_SCALE counts per %s, OUTPUT_SCALE volts per output unit), as its HAL "
             "file scales the board" % (m.unit, m.unit)]
    for j in range(m.n):
        lines.append("[JOINT_%d]" % j)
        for k in OUT_KEYS:
            if k in gains[j]:
                lines.append("%-8s = %s" % (k, hg_config.GAIN_FORMAT % gains[j][k]))
    for j in range(m.n):
        fe = m.joints[j].get("FERROR")
        lines.append("# joint %d: peak |f-error| %.6g %s (the INI's gains: %.6g %s%s)"
                     % (j, pred[j], m.unit_of(j), stock[j], m.unit_of(j),
                        "; FERROR %g" % fe if fe is not None else ""))
    lines.append(SKIPPED)
    return "\n".join(lines) + "\n"


def read_gain_file(path, n):
    """[JOINT_N] gain keys of a file (tune's output or an INI): hg.read_gains, LinuxCNC's reading."""
    try:
        return hg.read_gains(path, n)[0]
    except OSError as ex:
        raise BadInput("--gains %s: %s" % (path, ex.strerror or ex))
    except ValueError as ex:
        raise BadInput("--gains %s" % ex)


def beyond_ferror(m, peaks):
    """The joints whose peak |f-error| exceeds their [JOINT_N]FERROR (where the INI gives one)."""
    return [j for j in range(m.n) if m.joints[j].get("FERROR") and peaks[j] > m.joints[j]["FERROR"]]


def main(argv=None):
    ap = hg_cli.Parser(prog="hexaglide tune --plant serial", description=__doc__.split("\n\n")[0])
    ap.add_argument("--plant", default="serial")
    ap.add_argument("--model", help="the axes (default: the INI's [TRAJ]COORDINATES)")
    ap.add_argument("--ini", required=True, help="the config: [JOINT_N] gains and scales, [SERIAL] the machine")
    ap.add_argument("--trajectory", help="joint.N.motor-pos-cmd samples (CSV); default a generated move")
    ap.add_argument("--evaluate", action="store_true", help="predict the INI's (or --gains') gains only")
    ap.add_argument("--gains", metavar="FILE", help="gains to evaluate ([JOINT_N] sections)")
    ap.add_argument("--max-overshoot", type=hg_csv.number, default=0.15,
                    help="the step overshoot allowed, a fraction in [0, 1]; default 0.15")
    ap.add_argument("--maxiter", type=hg_csv.integer, default=12,
                    help="generations of differential evolution per joint, %d..%d; default 12" % RANGES["--maxiter"][:2])
    ap.add_argument("--popsize", type=hg_csv.integer, default=6,
                    help="population per search variable, %d..%d; default 6" % RANGES["--popsize"][:2])
    ap.add_argument("--seed", type=hg_csv.integer, default=1,
                    help="the search's random seed (joint N's is seed + N, modulo 2^32), %d..%d; default 1" % RANGES["--seed"][:2])
    hg_tune_options.add_jobs_option(ap)
    ap.add_argument("--output", help="also write the suggestion to this file")
    a, rest = ap.parse_known_args(argv)
    try:
        if rest:
            raise BadInput("%s: not an option of the serial plant's tune (hexaglide tune --plant serial "
                           "takes --ini --model --trajectory --evaluate --gains --max-overshoot --maxiter "
                           "--popsize --seed --jobs --output)" % " ".join(rest))
        if a.plant != "serial":
            raise BadInput("--plant %s: this is the serial plant's tuner" % a.plant)
        why = hg_cli.out_of_range(a, RANGES)
        if why:
            raise BadInput(why)
        m = Machine(a.ini, a.model)
        cmd = load_trajectory(a.trajectory, m.n) if a.trajectory else generated_move(m)
        source = a.trajectory or "generated (each joint out and back)"
        why = a.trajectory and hg_program.beyond_limits(source, cmd, m.joints, m.unit_of)
        if why:                            # (the generated move keeps its own rule: toward -)
            raise BadInput(why)
        cmd = with_settle(cmd)
        stock_g = m.gains()
        try:                               # the loop's rules (pid.c's) now, not as a traceback later
            hg.loop_config(stock_g, plant=m.params)
        except hg.LoopConfigError as ex:
            raise BadInput(ex.in_ini(a.ini))
        if a.gains:
            stock_g = m.gains(read_gain_file(a.gains, m.n))
            try:
                hg.loop_config(stock_g, plant=m.params)
            except hg.LoopConfigError as ex:
                raise BadInput("--gains %s: %s" % (a.gains, ex))
        if a.output:
            hg_output.check_writable(a.output)         # a missing or unwritable directory now, not after the search
            hg_output.refuse_inputs([("--output", a.output)], [("--ini", a.ini), ("--trajectory", a.trajectory),
                                                               ("--gains", a.gains)])
    except (BadInput, hg_output.OutputError) as ex:
        log(ex)
        return 2
    stock, _, ok = evaluate(m, stock_g, cmd)
    for j in beyond_ferror(m, stock) if ok else []:   # the loop runs on past FERROR; LinuxCNC does not
        log("joint %d: peak |f-error| %.6g %s beyond [JOINT_%d]FERROR %g: LinuxCNC stops on a following error "
            "here: the trajectory asks more than the machine follows with these gains"
            % (j, stock[j], m.unit_of(j), j, m.joints[j]["FERROR"]))
        if a.evaluate:
            return 1
    if not ok:
        log("the given gains are unstable or fault the board on this trajectory (peak |f-error| %s)" % stock)
        if a.evaluate:
            return 1
    for j in range(m.n):
        log("joint %d, the given gains: peak |f-error| %.6g %s" % (j, stock[j], m.unit_of(j)))
    if a.evaluate:
        sys.stdout.write(ini_text(m, [{k: g[k] for k in OUT_KEYS if k in g} for g in stock_g], stock, stock,
                                  source))
        return 0
    best = search(m, cmd, a, a.jobs or hg.cores())
    gains = m.gains(hg_config.as_printed(best, OUT_KEYS))   # the prediction is the printed gains'
    pred, _, ok = evaluate(m, gains, cmd)
    if not ok:
        log("no stable gains found")
        return 1
    over = beyond_ferror(m, pred)
    if over:
        j = over[0]
        log("joint %d: the best gains found leave a peak |f-error| of %.6g %s, beyond [JOINT_%d]FERROR %g: "
            "LinuxCNC stops on a following error; the machine cannot follow this trajectory: nothing suggested"
            % (j, pred[j], m.unit_of(j), j, m.joints[j]["FERROR"]))
        return 1
    text = ini_text(m, [{k: g[k] for k in OUT_KEYS if k in g} for g in gains], pred, stock, source)
    sys.stdout.write(text)
    if a.output:
        hg_output.atomic_write(a.output, lambda f: f.write(text.encode()))
    return 0


if __name__ == "__main__":
    hg_cli.run(main, log, (hg_output.OutputError,))
