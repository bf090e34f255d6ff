#!/usr/bin/python3
"""hexaglide_tune.py - PID + feed-forward gains for the Hexaglide's six
joints, tuned against the model: the closed loop of LinuxCNC's pid and the
virtual board runs in C (build/libhexaglide.so, src/hg_loop.c), the search is
scipy's differential evolution on all cores, the plots are matplotlib's.
Normally started as `build/hexaglide tune ...` (src/cli/cmd_tune.c); see
docs/tuning.md.

stdout: ready-to-paste [JOINT_0]..[JOINT_5] sections, then the predicted
peak following error per joint (comment lines). stderr: progress.
Exit codes: 0 ok, 1 no stable gains / unstable gains given, 2 bad input.
"""
import ctypes as C
import os
import re
import sys
import time

try:
    import numpy as np
    import scipy  # noqa: F401  (differential_evolution, imported where used)
    import matplotlib  # noqa: F401  (the plots)
except ImportError as _ex:  # a message, not a traceback: which interpreter is needed and why
    sys.exit("hexaglide tune: %s (this is %s): the tuner needs numpy, scipy and matplotlib; run it as "
             "build/hexaglide tune, which picks a python3 that has them ($HEXAGLIDE_PYTHON, else $PATH), "
             "or install python3-numpy python3-scipy python3-matplotlib (Debian 12)" % (_ex, sys.executable))

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hexaglide as hg  # noqa: E402
import hg_csv  # noqa: E402
import hg_config  # noqa: E402
import hg_margins as hgm  # noqa: E402
from hg_program import LEAD_IN, PERIOD_S, PERIOD_WHY, beyond_limits, program_rows, s_curve  # noqa: E402
import hg_identify_base as ib  # noqa: E402  (the C record reader)
import hg_cli  # noqa: E402
from hg_tune_options import RANGES, add_jobs_option, csv_columns  # noqa: E402
import hg_output  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
MIN_SAMPLES = 200          # a trajectory shorter than this is refused (0.2 s)
SETTLE = 1500              # periods at the first command before the trajectory
RAMP = 500                 # periods of the smooth move from HOME to the first command
PREDICT_SETTLES = [SETTLE + 53 * i for i in range(15)]   # the prediction's 15 runs
KEYS = ["P", "I", "D", "FF0", "FF1", "FF2", "FF3", "BIAS"]


class BadInput(Exception):
    """A user error: exit 2 with the message."""


def log(*a):
    print("hexaglide tune:", *a, file=sys.stderr, flush=True)


# ------------------------------------------------------------------ INI
def read_config(path, params=(), cmd="tune"):
    """The config as build/hexaglide reads it (tools/hg_config.py, `hexaglide config --loop`: the
    C CLI's INI reader, the servo loops as soak reads them): an hg_config.Config whose params are
    the defaults, [HEXAGLIDE], then params ("name=value", SI: --param); BadInput naming the key,
    file and line of what the user must fix."""
    try:
        return hg_config.read(path, params, loop=True, cmd=cmd, set_option="--param")
    except hg_config.ConfigError as ex:
        raise BadInput(str(ex))


def read_ini(path, cmd="tune"):
    """([JOINT_0..5] as {KEY: float}, {axis: {KEY: float}}) of read_config (the C CLI's reader)."""
    cfg = read_config(path, cmd=cmd)
    return cfg.joints, cfg.axes


def pid_keys(g):
    """What hg.Loop takes of an INI joint dict: the pid gains and limits, the scales."""
    return {k: v for k, v in g.items() if k in hg.GAIN_KEYS or k in ("INPUT_SCALE", "OUTPUT_SCALE", "OUTPUT_OFFSET")}


# ------------------------------------------------------------------ trajectories
def load_trajectory(path):
    """Joint commands (n, 6) in mm from a recorded run.

    Accepted: a record of tools/hg_record.py (load_record), the CSV of
    tools/headless/hexaglide_headless.py (columns
    joint.N.motor-pos-cmd; cropped to the program when halui.program.is-running
    is there), or plain rows of 6 numbers (or 7: a sample number / time first,
    as `halsampler -t` prints), separated by spaces or commas; lines starting
    with # are comments. .gz files are read too. A CSV's columns are checked
    as hg_tune_options.csv_columns checks them (a name given twice, a row of
    another width, `sample` and `t_s` not one servo period a line)."""
    if os.path.isdir(path):
        raise BadInput("--trajectory %s is a directory: give the recorded file (docs/tuning.md)" % path)
    if not os.path.isfile(path):
        raise BadInput("no such trajectory file: %s" % path)
    try:
        with open(path, "rb") as f:
            if f.readline().rstrip(b"\r\n") in hg.RECORD_MAGICS:
                return check_trajectory(path, load_record(path))
    except OSError as ex:
        raise BadInput("%s: cannot read it: %s" % (path, ex.strerror or ex))
    try:
        lines = hg_csv.text_lines(path)
    except hg_csv.CsvError as ex:
        raise BadInput(str(ex))
    header, hdr_no = None, 0
    rows = []
    for no, line in enumerate(lines, 1):
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        if s == "overrun":
            raise BadInput("%s line %d: 'overrun': halsampler lost samples here; record again with a "
                           "deeper FIFO (loadrt sampler depth=...)" % (path, no))
        fields = [x for x in s.replace(",", " ").split()]
        if header is None and not rows and any("motor-pos-cmd" in x for x in fields):
            header, hdr_no = fields, no        # "t_s, joint.0.motor-pos-cmd, ..." too
            continue
        try:
            vals = [hg_csv.number(x) for x in fields]
        except ValueError:
            if header is None and not rows and "," in s and not any(c.isdigit() for c in fields[0][:1]):
                raise BadInput("%s line %d is a header without joint.N.motor-pos-cmd columns: record "
                               "motion's joint commands (docs/tuning.md)" % (path, no))
            raise BadInput("%s line %d does not parse as numbers: %r" % (path, no, s[:80]))
        if not np.all(np.isfinite(vals)):
            raise BadInput("%s line %d holds a NaN or infinite value" % (path, no))
        rows.append((no, vals))
    if header is not None:
        try:
            data = csv_columns(path, header, hdr_no, [v for _, v in rows], [no for no, _ in rows])
        except ValueError as ex:
            raise BadInput(str(ex))
        cols = []
        for j in range(hg.JOINTS):
            name = "joint.%d.motor-pos-cmd" % j
            if name not in header:
                raise BadInput("%s: column %s missing (need joints 0..5)" % (path, name))
            cols.append(header.index(name))
        extra = [c for c in header if re.fullmatch(r"joint\.(\d+)\.motor-pos-cmd", c)
                 and int(c.split(".")[1]) >= hg.JOINTS]
        if extra:
            raise BadInput("%s: %d joints, the Hexaglide has 6" % (path, hg.JOINTS + len(extra)))
        cmd = data[:, cols]
        if "halui.program.is-running" in header and len(data):
            span = program_rows(data[:, header.index("halui.program.is-running")] > 0.5, cmd)
            if span:
                cmd = cmd[max(0, span[0] - LEAD_IN):span[1]]
    else:
        widths = {len(v) for _, v in rows}
        if len(widths) > 1:
            no, v = next((no, v) for no, v in rows if len(v) != len(rows[0][1]))
            raise BadInput("%s line %d: %d values, line %d has %d" % (path, no, len(v), rows[0][0], len(rows[0][1])))
        width = widths.pop() if widths else 6
        if width not in (6, 7):
            raise BadInput("%s: %d values per line; need 6 joint commands (mm), optionally after a "
                           "sample number: the Hexaglide has 6 joints" % (path, width))
        cmd = np.array([v[-6:] for _, v in rows]).reshape(-1, 6)
        if width == 7 and len(rows) > 1:
            n = np.array([v[0] for _, v in rows])
            step = n[1] - n[0]
            if abs(step - 1) > 1e-6 and abs(step - PERIOD_S) > 1e-3 * PERIOD_S and step > 0:
                raise BadInput("%s line %d: the first column advances by %g a line, neither a sample number (1) "
                               "nor the time of a %g s servo period: tune takes one line per period; resample "
                               "the trajectory to %g s" % (path, rows[1][0], step, PERIOD_S, PERIOD_S))
            bad = np.where(np.abs(np.diff(n) - step) > 0.25 * abs(step))[0] if step > 0 else [0]
            if len(bad):
                raise BadInput("%s line %d: the first column (sample number or time) does not advance "
                               "evenly: samples lost?" % (path, rows[bad[0] + 1][0]))
    return check_trajectory(path, cmd)


def check_trajectory(path, cmd):
    """cmd (n, 6) if it is long enough and in mm, else BadInput."""
    if len(cmd) < MIN_SAMPLES:
        raise BadInput("%s: %d samples; need at least %d (%.1f s of servo periods)"
                       % (path, len(cmd), MIN_SAMPLES, MIN_SAMPLES * PERIOD_S))
    if np.abs(cmd).max() > 1000:
        raise BadInput("%s: a joint command beyond 1000 mm: not joint commands in mm?" % path)
    return np.ascontiguousarray(cmd)


def check_reach(source, cmd, joints):
    """BadInput for a joint command outside its [JOINT_N]MIN_LIMIT..MAX_LIMIT: the machine cannot go there."""
    why = beyond_limits(source, cmd, joints, lambda j: "mm")
    if why:
        raise BadInput(why)


def beyond_drive(cmd, start, joints):
    """Where the trajectory asks more than a drive gives, or None: per joint the model's volts for
    it (FF1 v + FF2 a + BIAS, friction aside: a lower bound) above MAX_OUTPUT (0: the DAC's 10 V),
    said for the first such sample. Not a refusal: a LinuxCNC run may saturate a drive for a few
    periods and still stay within FERROR, which the closed-loop runs decide."""
    v = np.diff(cmd, axis=0) / PERIOD_S
    acc = np.diff(cmd, 2, axis=0) / PERIOD_S ** 2
    need = start["FF1"] * v[1:] + start["FF2"] * acc + start["BIAS"]
    vmax = np.array([hg_config.output_limit(g) for g in joints])
    over = np.argwhere(np.abs(need) > vmax)
    if not len(over):
        return None
    i, j = over[0]
    return ("joint %d at sample %d (%.4g mm/s, %.4g mm/s^2) needs %.4g V of its drive by the model (FF1 v + FF2 a "
            "+ BIAS, friction aside), beyond [JOINT_%d]MAX_OUTPUT %g V, at %d samples in all: the drive saturates "
            "there and the loop lags the trajectory" % (j, i + 2, v[i + 1, j], acc[i, j], need[i, j], j, vmax[j],
                                                       len(np.unique(over[:, 0]))))

def load_record(path):
    """Joint commands (n, 6) in mm from a record of tools/hg_record.py
    (docs/replay.md), read as `replay` reads it (every column typed as its pin,
    every sample in turn: src/hg_record.c), at tune's servo period: the columns
    joint.N.motor-pos-cmd, from the second period after the last index latch
    (homing done, where `replay` starts its f-error window) to the last period
    with every amplifier enabled (pid.N.enable is out-08+N of in.dout-values)."""
    want = ["joint.%d.motor-pos-cmd" % j for j in range(hg.JOINTS)] + ["out.index-latched", "in.dout-values",
                                                                      "in.period-ns"]
    try:
        data, _, hdr_no, _ = ib.record_columns(path, want, "tune needs motion's joint commands and the servo period "
                                               "(an older tools/hg_record.py's record has no joint commands); "
                                               "record again (docs/replay.md)")
    except ib.RecordError as ex:
        raise BadInput(str(ex))
    off = np.where(data[:, 8] != round(PERIOD_S * 1e9))[0]
    if len(off):
        raise BadInput("%s line %d: in.period-ns %d: tune runs one line per %g s servo period; record with "
                       "[EMCMOT]SERVO_PERIOD = %d (ns)" % (path, hdr_no + 1 + off[0], data[off[0], 8], PERIOD_S,
                                                           round(PERIOD_S * 1e9)))
    latched = np.where(data[:, 6].astype(np.int64) & 0x3f)[0]
    on = np.where((data[:, 7].astype(np.int64) >> 8 & 0x3f) == 0x3f)[0]
    i0 = latched[-1] + 2 if len(latched) else (on[0] if len(on) else 0)
    i1 = on[-1] + 1 if len(on) else len(data)
    return np.ascontiguousarray(data[i0:i1, :6])


def generated_move(axes, params=None, ini=None):
    """Joint commands of a default test move: each world axis out and back
    on an S-curve at its MAX_VELOCITY / MAX_ACCELERATION (ini given: both
    required, BadInput naming the key; else 20 mm/s, 200 mm/s^2 where absent),
    then all together; the joints by the inverse kinematics of params."""
    amp = {"X": 40.0, "Y": 40.0, "Z": 40.0, "A": 8.0, "B": 8.0, "C": 10.0}
    poses = [np.zeros(6)]
    for i, a in enumerate("XYZABC"):
        lim = axes.get(a, {})
        for key in ("MAX_VELOCITY", "MAX_ACCELERATION"):
            if ini is not None and key not in lim:
                raise BadInput("%s: [AXIS_%s]%s is missing: the generated move runs each axis at its limits "
                               "(or give --trajectory)" % (ini, a, key))
        v, acc = lim.get("MAX_VELOCITY", 20.0), lim.get("MAX_ACCELERATION", 200.0)
        for sign in (1, -1):
            prof = s_curve(amp[a], v, acc) * sign
            seg = np.repeat(poses[-1][None, :], len(prof), 0)
            seg[:, i] += prof
            poses.extend(seg)
    poses = np.array(poses)
    try:
        return np.ascontiguousarray([hg.ik(p, params) for p in poses])
    except hg.HexaglideError as ex:
        raise BadInput("the generated move leaves this machine's working volume (%s): give --trajectory" % ex)


# ------------------------------------------------------------------ model-based start
def model_start(cmd, params=None):
    """Per joint: FF1 (viscous), FF2 (inertia), BIAS (gravity) and the mass for P/I/D, from
    the dynamics at poses along the trajectory: the linear part of the machine, so Coulomb
    and static friction are off and each winding starts at its commanded current (a torque-
    mode amplifier's steady state), leaving volts -> force = fpv."""
    mech = hg.Params()
    if params is not None:
        C.memmove(mech.buf, params.buf, C.sizeof(mech.buf))
    mech["f_coulomb"] = mech["f_static"] = 0.0
    mech["k_axial"] = 0.0     # the trains' low-frequency limit: rotor and carriage one body (the rigid mass)
    mech["backlash"] = 0.0    # (lost motion belongs to the flexible train: the rigid one refuses it)
    m = hg.Model("reduced-cartesian", mech)
    fpv = m.params["ka"] * m.params["kt"] * 2 * np.pi / m.params["lead"]
    idx = np.linspace(0, len(cmd) - 1, 12).astype(int)
    guess = [0, 0, 0, 0, 0, 0]
    diag, rows, holds = [], [], []
    for i in idx:
        try:
            pose = hg.fk(cmd[i], guess, params)
        except hg.HexaglideError:
            continue
        guess = pose

        def accel(volts):
            d = hg.Data()
            C.memmove(C.byref(d), C.byref(m.d), C.sizeof(d))
            p_si = list(np.array(pose[:3]) / 1000.0) + list(np.radians(pose[3:]))
            for k in range(6):
                d.z_m[k], d.zd_mps[k], d.pose[k], d.posed[k] = cmd[i][k] / 1000.0, 0.0, p_si[k], 0.0
                d.current_a[k] = m.params["ka"] * volts[k]
            d.trig_valid = 0
            rc = hg._step(m.m, C.byref(d), hg._d6(*volts), 1e-5)
            if rc:
                raise hg.HexaglideError("model step", rc)
            return np.array(d.zdd_mps2[:])
        a0 = accel([0.0] * 6)
        B = np.array([accel([1.0 if i2 == k else 0.0 for i2 in range(6)]) - a0 for k in range(6)]).T
        M = np.linalg.inv(B)                       # V per m/s^2
        diag.append(np.diag(M))
        rows.append(M.sum(1))
        holds.append(-M @ a0)
    if not diag:
        raise BadInput("no pose along the trajectory solves the forward kinematics")
    diag, rows, holds = np.mean(diag, 0), np.mean(rows, 0), np.mean(holds, 0)
    ff2 = 0.5 * (diag + rows) / 1000.0              # V per mm/s^2
    ff1 = np.full(6, m.params["c_visc"] / fpv / 1000.0)
    return {"FF1": ff1, "FF2": ff2, "BIAS": holds, "mass_kg": ff2 * 1000.0 * fpv,
            "c_visc": m.params["c_visc"], "fpv": fpv}


pid_from_bandwidth = hgm.pid_from_bandwidth


# ------------------------------------------------------------------ evaluation (runs in workers)
X0 = (0.0, 0.0, 0.0, 1.0, 1.0)   # the search's start: the model start's gains


def gains_from_x(x, prob):
    """Search vector -> six INI gain dicts: x = log10 of multipliers of the model's P, I, D,
    and multipliers of FF1, FF2."""
    b = prob["base"]
    out = []
    for j in range(6):
        g = dict(prob["fixed"][j])
        g.update(P=b["P"][j] * 10 ** x[0], I=b["I"][j] * 10 ** x[1], D=b["D"][j] * 10 ** x[2],
                 FF1=b["FF1"][j] * x[3], FF2=b["FF2"][j] * x[4], FF0=0.0, FF3=0.0, BIAS=b["BIAS"][j])
        out.append(g)
    return out


def per_joint(notch):
    """tune's one notch (f0, Q) as hg.loop_config and hg_margins take a notch, one entry per
    joint; None for None."""
    return [notch] * hg.JOINTS if notch else None


def notch_of(x, prob):
    """The notch of search vector x: per_joint of prob["notch"] (f0, Q) when x has the notch
    switch (x[5], with prob["notch"]) on, else None."""
    return per_joint(prob["notch"]) if len(x) > 5 and x[5] > 0.5 else None


APPROACH_MM = 0.03         # the runs after the first come to the start from +-this per joint


def lead_in(cmd, settle, approach=None):
    """(commands, index where cmd starts): from HOME at rest a smooth move to
    cmd's first row (RAMP periods), settle periods there, then cmd. With
    approach (mm per joint) the move goes to first row + approach, then in
    RAMP/2 periods to the first row: the carriages come to rest from that
    side, so static friction holds them at another point of its band."""
    c0 = cmd[:1]
    s = (0.5 - 0.5 * np.cos(np.pi * np.arange(RAMP) / RAMP))[:, None]
    if approach is None:
        return np.vstack([s * c0, np.repeat(c0, settle, 0), cmd]), RAMP + settle
    a = np.asarray(approach, float)[None, :]
    h = s[::2]
    parts = [s * (c0 + a), c0 + a - h * a, np.repeat(c0, settle, 0), cmd]
    return np.vstack(parts), RAMP + len(h) + settle


def approach_of(i):
    """Run i's approach (mm per joint): none for run 0, else +-APPROACH_MM by the bits of i."""
    return None if i == 0 else APPROACH_MM * np.array([1.0 if (i >> j) & 1 else -1.0 for j in range(6)])


def loop_cfg(gains, prob, notch=None):
    """hg_loop_config of the gains (and notch) with the problem's trip limit."""
    return hg.loop_config(gains, ferror_limit_mm=prob["ferror_limit"], notch=notch)


def board_params(prob):
    """The board parameters of the machine tuned on: prob["board_params"], by default the
    board's defaults (a caller's prob of only cmd and ferror_limit: tools/verify_gains.py)."""
    if "board_params" not in prob:
        prob["board_params"] = hg.Params().board_params()
    return prob["board_params"]


def search_params(prob):
    """The board parameters the search runs on: prob["search_params"] (search_scheme's
    choice) if set, else the machine's (board_params)."""
    return prob.get("search_params") or board_params(prob)


def search_scheme(params, own_bp, choice):
    """(the board parameters the search runs on, None for the machine's own_bp; a sentence for
    the log). The machine's board runs own_bp's scheme on at least its substeps, as many as its
    stability check asks (hg.substeps_run). choice "board": the search runs that too. "auto":
    it runs RK4 instead when RK4 evaluates fewer accelerations a period (stages x substeps), so
    also on fewer steps: the same machine by a scheme of higher order on fewer, longer steps,
    where the flexible trains' axial mode sets the substeps (at the defaults RK4 2 a period,
    Heun 5). The search's best are then costed on the machine's own scheme (verify)."""
    own = own_bp.integrator
    n_own = hg.substeps_run(params, own, own_bp.substeps)
    rk4 = hg.integrator_id("rk4")
    n_rk4 = hg.substeps_run(params, rk4, own_bp.substeps) if choice == "auto" and rk4 != own else 0
    evals = lambda i, n: hg.integrator_stages(i) * n
    name = hg.integrator_name(own)
    steps = lambda n: "%d step%s a servo period" % (n, "" if n == 1 else "s")
    if n_rk4 and n_own and evals(rk4, n_rk4) < evals(own, n_own):
        return params.board_params(own_bp.substeps, rk4), (
            "the search runs rk4 on %s (%d accelerations) instead of the board's %s on %d (%d): the same "
            "machine, cheaper; its best are costed on %s (--search-integrator board: %s throughout)"
            % (steps(n_rk4), evals(rk4, n_rk4), name, n_own, evals(own, n_own), name, name))
    if not n_own:                        # the board refuses these parameters: its message comes with the runs
        return None, "the search runs the board's %s" % name
    return None, "the search runs the board's %s on %s%s" % (
        name, steps(n_own), " (rk4 would evaluate no fewer accelerations: %d on %s)"
        % (evals(rk4, n_rk4), steps(n_rk4)) if n_rk4 else "")


def trajectory_jobs(cfg, prob, settles, keep=False, tool_error=True, windows=False, bp=None):
    """The batch jobs of trajectory_runs: the trajectory after each settle and approach
    (tool_error False: without the tool-path error, as the search needs only f-errors;
    windows: prob["windows"]'s chain of critical windows instead of the whole trajectory;
    bp: the board parameters, None for the machine's)."""
    jobs = []
    for i, settle in enumerate(settles):
        key = ("windows", settle, i) if windows else (settle, i)
        if key not in prob.setdefault("seqs", {}):
            prob["seqs"][key] = lead_in(prob["windows"][0] if windows else prob["cmd"], settle, approach_of(i))
        seq, s = prob["seqs"][key]
        jobs.append(hg.Job(cfg, bp or board_params(prob), seq, start=s, keep=keep, tool_error=tool_error))
    return jobs


def trajectory_runs(gains, prob, settles, keep=False, notch=None):
    """Closed-loop runs over the trajectory after different settle times and
    approaches to the start (the encoder and DAC quantization and where
    static friction holds each carriage make single runs differ by about a
    count), through hg.batch on prob["threads"] threads."""
    jobs = trajectory_jobs(loop_cfg(gains, prob, notch), prob, settles, keep)
    res = hg.batch(jobs, prob.get("threads", 1))
    if keep:
        for j, r in zip(jobs, res):
            if r.ferror_mm is not None:
                r.ferror_mm, r.output_v = r.ferror_mm[j.start:], r.output_v[j.start:]
    return res


def step_job(cfg, prob, joint=0, step_mm=0.05, n=600, tool_error=True, bp=None):
    """The batch job of step_response: SETTLE periods at HOME, then a command step (bp: the
    board parameters, None for the machine's)."""
    key = ("step", joint, step_mm, n)
    if key not in prob.setdefault("seqs", {}):
        cmd = np.zeros((SETTLE + n, 6))
        cmd[SETTLE:, joint] = step_mm
        prob["seqs"][key] = cmd
    return hg.Job(cfg, bp or board_params(prob), prob["seqs"][key], keep=True, tool_error=tool_error)


def step_feedback(job, r, joint=0):
    """The feedback (mm) after the step of step_job's run r; None when the loop tripped."""
    if not r.ok:
        return None
    fe = r.ferror_mm[SETTLE:, joint]
    cmd = job.cmd[SETTLE:, joint]
    return cmd - np.r_[fe[1:], fe[-1]]


def step_response(gains, prob, joint=0, step_mm=0.05, n=600, notch=None):
    """Feedback (mm) of joint `joint` after a command step (others hold), after settling.
    None when the loop tripped."""
    job = step_job(loop_cfg(gains, prob, notch), prob, joint, step_mm, n)
    return step_feedback(job, hg.batch([job], 1)[0], joint)


def step_metrics(fb, step_mm=0.05):
    """(overshoot fraction, settled?) of a step response."""
    if fb is None or not np.all(np.isfinite(fb)):
        return np.inf, False
    over = max(0.0, (fb.max() - step_mm) / step_mm)
    tail = fb[-150:]
    settled = np.abs(tail - step_mm).max() < 0.2 * step_mm
    return over, settled


def margins_of(gains, prob, notch=None):
    """The loop's margins on the measured plant (hg_margins.margins)."""
    return hgm.margins(gains, prob["frf_hz"], prob["frf"], notch, prob["mode_hz"])


def margins_many(gains, prob, notches):
    """margins_of each of a list of gain sets with notches[i], in one go (hg_margins.margins_many)."""
    return hgm.margins_many(gains, prob["frf_hz"], prob["frf"], notches, prob["mode_hz"], prob.get("threads", 1))


def margin_penalty(m):
    """What the search adds for margins short of what tune asks: 0.05 mm per criterion
    missed plus the shortfall (hg_margins.verdict's criteria)."""
    c = 0.0
    if m["mode_modulus"] is not None and m["mode_modulus"] < hgm.MIN_MODULUS:
        c += 0.05 + 0.1 * (hgm.MIN_MODULUS - m["mode_modulus"])
    if m["gm_db"] < hgm.MIN_GM_DB:
        c += 0.05 + 0.01 * (hgm.MIN_GM_DB - m["gm_db"])
    if m["pm_deg"] < hgm.MIN_PM_DEG:
        c += 0.05 + 0.001 * (hgm.MIN_PM_DEG - m["pm_deg"])
    return c


W_RMS = 0.2                # run_cost: mm of cost per mm of the worst RMS f-error
W_VOLTS = 1.0              # run_cost: mm of cost per volt above the limit
VOLTS_SHOWN = 5e-4         # half the last digit of the volts tune prints (%.3f)


def run_cost(runs, prob):
    """The trajectory runs' share of a candidate's cost: worst peak |f-error| over joints and
    runs plus W_RMS times the worst RMS (mm), plus W_VOLTS mm per volt above the limit; None
    when a run tripped; 0 for no run (a lower bound: every term is a maximum over the runs,
    >= 0, so a subset of them bounds it from below)."""
    if not all(r.ok for r in runs):
        return None
    if not runs:
        return 0.0
    peak = max(r.peak_ferror_mm.max() for r in runs)
    rms = max(r.rms_ferror_mm.max() for r in runs)
    volts = max(r.peak_output_v.max() for r in runs)
    return peak + W_RMS * rms + W_VOLTS * max(0.0, volts - prob["vmax"])


# ------------------------------------------------------------------ critical windows
# A long trajectory's search runs only the rows where the model start's f-errors and outputs peak
# (each joint's largest |f-error| and |output|), each with the trajectory's rows before it, joined
# by smooth moves; the best candidates are then costed on the whole trajectory (search's verify).
WINDOW_HALF = 60           # scored periods either side of a peak
WINDOW_LEAD = 200          # the trajectory's periods run before a window's scored rows, not scored
BRIDGE = 150               # periods, at least, of the smooth move from one window to the next one's lead
WINDOW_SETTLE = 300        # periods at the first row before the chain (the search's whole runs: SETTLE)
WINDOW_SHARE = 0.5         # windows only when their chain is at most this share of the trajectory
VERIFY = 4                 # the search's best of each kind (without, with the notch) costed on the whole trajectory


def hermite(p1, v1, p2, v2, n):
    """The n - 1 rows of the cubic from row p1 (velocity v1 per row) to row p2 (velocity v2)
    n rows later, both ends excluded: position and velocity continuous at both."""
    u = (np.arange(1, n) / n)[:, None]
    return ((2 * u ** 3 - 3 * u ** 2 + 1) * p1 + (u ** 3 - 2 * u ** 2 + u) * (v1 * n)
            + (3 * u ** 2 - 2 * u ** 3) * p2 + (u ** 3 - u ** 2) * (v2 * n))


def critical_spans(runs, n):
    """The scored row spans [a, b) of a trajectory of n rows around each joint's largest
    |f-error| and |output| in each of runs (kept traces from the trajectory's first row),
    merged where the trajectory between them is no longer than a bridge."""
    peaks = []
    for y in [r.ferror_mm for r in runs] + [r.output_v for r in runs]:
        mag = np.abs(y[:n])
        peaks += [int(np.argmax(mag[:, j])) for j in range(mag.shape[1]) if mag[:, j].max() > 0]   # at rest: none
    spans = sorted((max(0, i - WINDOW_HALF), min(n, i + WINDOW_HALF + 1)) for i in peaks)
    merged = []
    for a, b in spans:
        if merged and a - WINDOW_LEAD <= merged[-1][1] + BRIDGE:
            merged[-1] = (merged[-1][0], max(merged[-1][1], b))
        else:
            merged.append((a, b))
    return merged


def bridge(cmd, end, s, vmax, amax, lo, hi):
    """The rows that join cmd's row end - 1 (the first row at rest when end is 0) to row s: the
    shortest cubic of BRIDGE x 1.5^k rows whose steps and second differences, the junctions'
    included, are within vmax and amax per joint (window_chain: the trajectory's own largest, no
    faster and no harder than LinuxCNC moved the joints there) and whose rows stay within lo..hi
    per joint (the trajectory's own range, which a cubic between two windows can bulge past);
    None where that is no shorter than cmd[end:s] itself."""
    vel = lambda i: cmd[i + 1] - cmd[i] if i + 1 < len(cmd) else cmd[i] - cmd[i - 1]
    if end == 0:                    # from the first row at rest: the chain starts with that row
        p1, v1, head, before = cmd[0], 0 * cmd[0], cmd[:1], cmd[:1]
    else:
        p1, v1, head, before = cmd[end - 1], vel(end - 2), cmd[:0], cmd[max(0, end - 2):end]
    n = BRIDGE
    while n < s - end:
        br = np.vstack([head, hermite(p1, v1, cmd[s], vel(s), n)])
        seq = np.vstack([before, br, cmd[s:s + 2]])
        if np.all(np.abs(np.diff(seq, axis=0)) <= vmax) and np.all(np.abs(np.diff(seq, 2, axis=0)) <= amax) \
                and np.all(br >= lo - 1e-9) and np.all(br <= hi + 1e-9):
            return br
        n = int(np.ceil(1.5 * n))
    return None


def bridge_limits(cmd):
    """(vmax, amax, lo, hi) per joint a bridge keeps to: the trajectory's largest step and second
    difference (+1e-9 mm), its smallest and largest row."""
    return (np.abs(np.diff(cmd, axis=0)).max(0) + 1e-9, np.abs(np.diff(cmd, 2, axis=0)).max(0) + 1e-9,
            cmd.min(0), cmd.max(0))


def window_chain(cmd, spans):
    """(commands, scored): from cmd's first row, each span's rows with WINDOW_LEAD rows before,
    the gaps between them a bridge (or the trajectory itself where no bridge is shorter); scored
    marks the spans' rows."""
    vmax, amax, lo, hi = bridge_limits(cmd)
    parts, scored, end = [], [], 0      # end: the row of cmd after the last one taken
    for a, b in spans:
        s = max(0, a - WINDOW_LEAD)
        br = bridge(cmd, end, s, vmax, amax, lo, hi) if s > end else None
        if br is None:
            s = end
        else:
            parts.append(br)
            scored.append(np.zeros(len(br), bool))
        parts.append(cmd[s:b])
        scored.append(np.arange(s, b) >= a)
        end = b
    return np.vstack(parts), np.concatenate(scored)


def critical_windows(prob):
    """prob["windows"] = (chain, scored) of window_chain around the peaks of the runs of the
    model's gains (X0), without the notch and with prob["notch"] if there is one, with the first
    search run's settle and approach, when the chain is at most WINDOW_SHARE of the trajectory
    (else no prob["windows"]); a line for the log either way."""
    cmd = prob["cmd"]
    prob.pop("windows", None)
    prob["seqs"] = {k: v for k, v in prob.get("seqs", {}).items() if k[0] != "windows"}
    g0 = gains_from_x(X0, prob)
    notches = [None] + ([per_joint(prob["notch"])] if prob.get("notch") else [])
    runs = [trajectory_runs(g0, prob, prob["search_settles"][:1], keep=True, notch=nf)[0] for nf in notches]
    if not all(r.ok for r in runs):
        return "the search runs the whole trajectory (a run of the model start trips, so it shows no peaks)"
    spans = critical_spans(runs, len(cmd))
    chain, scored = window_chain(cmd, spans)
    if len(chain) > WINDOW_SHARE * len(cmd):
        return "the search runs the whole trajectory (its critical windows would be %d of its %d rows)" % (
            len(chain), len(cmd))
    prob["windows"] = chain, scored
    jobs = [trajectory_jobs(loop_cfg(g0, prob, nf), prob, window_settles(prob)[:1], windows=True,
                            bp=search_params(prob))[0] for nf in notches]
    if not all(r.ok for r in hg.batch(jobs, prob.get("threads", 1))):   # the chain must not trip them either
        prob.pop("windows")
        return "the search runs the whole trajectory (the model start trips on its critical windows' chain)"
    return ("the search runs %d critical windows (%d scored rows around each joint's peak |f-error| and "
            "|output| with the model's gains%s, %d rows a run against %d; --whole-search runs the whole "
            "trajectory), then costs its best %d%s on the whole trajectory" % (
                len(spans), scored.sum(), ", without and with the notch" if len(notches) > 1 else "", len(chain),
                len(cmd), VERIFY, " of each, without and with the notch," if len(notches) > 1 else ""))


def window_settles(prob):
    """The window chain's settles: the search runs' settles with WINDOW_SETTLE in place of SETTLE."""
    return [s - SETTLE + WINDOW_SETTLE for s in prob["search_settles"]]


class Scored:
    """A run's summary over the scored rows of the window chain, as RunResult's (run_cost reads it)."""

    def __init__(self, r, start, scored):
        self.ok, self.periods = r.ok, r.periods
        if r.ok:
            fe, out = r.ferror_mm[start:][scored], r.output_v[start:][scored]
            self.peak_ferror_mm, self.peak_output_v = np.abs(fe).max(0), np.abs(out).max(0)
            self.rms_ferror_mm = np.sqrt(np.mean(fe ** 2, 0))


def costs(xs, prob, beat=None, whole=False, stop=True):
    """What the search minimizes, for every candidate x of xs in batches (prob["threads"]
    threads, no Python per period): run_cost over the trajectory runs, plus penalties for
    step overshoot and the margins on the plant; 1 - 1e-9 per period run when a run trips
    (each candidate with its notch, notch_of).
    beat[i] (optional): the cost candidate i must not exceed to be kept (the population member
    it competes with). Then the candidates go in stages, every candidate's margins first (no
    run), then its step run, then its trajectory runs one at a time: one whose cost is already
    above beat[i] after a stage (the margins, then the step's settling and overshoot, then the
    runs' errors too) runs no further and gets that lower bound instead of its cost: it loses either way, so
    the search's choices, and its answer, are the full costs'. A trajectory run itself stops at
    the first scored period where the bound its rows so far give passes beat[i] (run_stop).
    stop False: beat is only compared (every candidate runs all). With prob["windows"] (and not
    whole) the runs are of the window chain, their costs of its scored rows. The search's runs
    are on search_params, whole's on the machine's board (board_params)."""
    windows = "windows" in prob and not whole
    settles = window_settles(prob) if windows else prob["search_settles"]
    bp = board_params(prob) if whole else search_params(prob)
    cands = []
    for x in xs:
        gains, notch = gains_from_x(x, prob), notch_of(x, prob)
        cfg = loop_cfg(gains, prob, notch)
        cands.append((gains, notch, step_job(cfg, prob, tool_error=False, bp=bp),
                      trajectory_jobs(cfg, prob, settles, keep=windows, tool_error=False, windows=windows, bp=bp)))
    jobs = [[sj] + tj for _g, _n, sj, tj in cands]
    if not stop:
        beat = None
    stages = [slice(None)] if beat is None else [slice(k, k + 1) for k in range(1 + len(settles))]
    done = [[] for _ in cands]                 # each candidate's results: step, then its runs
    out, live, ran = [None] * len(cands), list(range(len(cands))), 0
    stopped = prob.setdefault("stopped_at", [0] * (2 + len(settles)))   # on the margins, after the step, in or after run 1, ...
    margin = [margin_penalty(m) for m in margins_many([c[0] for c in cands], prob, [c[1] for c in cands])]
    if beat is not None:                       # the margins first: they need no run
        live = stop_early(live, cands, done, prob, margin, beat, out, stopped, 0)
    for n, part in enumerate(stages):
        todo = [(i, j) for i in live for j in jobs[i][part]]
        if beat is not None and n > 0:         # a trajectory run: stopped once its candidate cannot win
            todo = [(i, j.with_stop(run_stop(cands[i], done[i], prob, margin[i], beat[i], j, windows)))
                    for i, j in todo]
        res = hg.batch([j for _i, j in todo], prob.get("threads", 1)) if todo else []
        for (i, j), r in zip(todo, res):
            if r.stop_bound is not None:       # this run stopped: the candidate loses (run_stop)
                out[i] = stopped_cost(cands[i], done[i], prob, margin[i], r.stop_bound)
                stopped[n + 1] += 1
                prob["stopped_in_run"] = prob.get("stopped_in_run", 0) + 1
                continue
            done[i].append(Scored(r, j.start, prob["windows"][1]) if windows and j is not cands[i][2] else r)
        live = [i for i in live if out[i] is None]
        ran += sum(r.periods for r in res)
        if n + 1 == len(stages):
            break
        live = stop_early(live, cands, done, prob, margin, beat, out, stopped, n + 1)
    for i in live:
        sj = cands[i][2]
        out[i] = penalized(done[i][0], sj, done[i][1:], prob, margin[i])
    prob["periods_run"] = prob.get("periods_run", 0) + ran
    return out


def stop_early(live, cands, done, prob, margin, beat, out, stopped, stage):
    """The candidates of live that run on: one whose lower bound (lower_bound) is above beat[i]
    gets it as out[i] and counts in stopped[stage]."""
    keep = []
    for i in live:
        lb = lower_bound(cands[i], done[i], prob, margin[i])
        if lb > beat[i]:
            out[i] = lb
            stopped[stage] += 1
        else:
            keep.append(i)
    return keep


def known_terms(cand, done, prob, margin):
    """(the cost's terms that no further trajectory run changes: the margin penalty and the step
    run's, the trajectory's floor (the cost of a trip in a later run), the runs so far or None
    when one tripped) of candidate cand after its step run and the trajectory runs of done[1:]."""
    _g, _notch, sj, tj = cand
    floor = 1.0 - 1e-9 * sum(j.cmd.shape[0] for j in tj)
    runs = done[1:]
    return penalized(done[0], sj, [], prob, margin), floor, runs if all(r.ok for r in runs) else None


def run_stop(cand, done, prob, margin, beat, job, windows):
    """The hg.Stop of candidate cand's next trajectory run (job), after its step run and the runs
    of done[1:]: it stops once the candidate's cost, whatever its later runs give, is above beat
    (penalized's known terms plus run_cost's terms over the runs so far and this one's rows so
    far, each a maximum that only grows; below the trip floor); None where no stop is sound (a
    run tripped, or beat is at the floor)."""
    known, floor, runs = known_terms(cand, done, prob, margin)
    if runs is None or not beat < floor:
        return None
    scored = None
    if windows:                                # the chain's scored rows, after the job's lead-in
        key = ("windows", "scored", job.start)   # (with the chain's sequences: critical_windows drops both)
        if key not in prob["seqs"]:
            prob["seqs"][key] = np.r_[np.zeros(job.start, bool), prob["windows"][1]]
        scored = prob["seqs"][key]
    mx = lambda f: max([float(f(r).max()) for r in runs], default=0.0)
    # (the limit a hair above beat - known: the bound's RMS sums in order, numpy's pairwise; 1e-12 covers it)
    return hg.Stop(beat - known + 1e-12 * max(1.0, abs(beat)), scored, W_RMS, W_VOLTS, prob["vmax"],
                   mx(lambda r: r.peak_ferror_mm), mx(lambda r: r.rms_ferror_mm), mx(lambda r: r.peak_output_v),
                   volts_dac=not windows)


def stopped_cost(cand, done, prob, margin, bound):
    """The lower bound a candidate gets whose next trajectory run after done (its step run and
    runs so far) stopped at `bound` (run_stop's): above the beat it had to stay under."""
    known, floor, _runs = known_terms(cand, done, prob, margin)
    return min(floor, known + bound)


def lower_bound(cand, done, prob, margin):
    """A lower bound of candidate cand's cost from its margin penalty and its results so far
    (done: none yet, or the step run, then some of its trajectory runs): penalized's with the
    runs so far, at most the cost of a trip in a later run (1 - 1e-9 x every period); before
    the step run at most 0.5 too (an unsettled step costs 0.5 plus the runs' errors, without
    the margins)."""
    _g, _notch, sj, tj = cand
    floor = 1.0 - 1e-9 * sum(j.cmd.shape[0] for j in tj)
    if not done:
        return min(floor, 0.5, margin)
    return min(floor, penalized(done[0], sj, done[1:], prob, margin))


def penalized(step, sj, runs, prob, margin):
    """costs' cost of one candidate from its step run (of job sj) and trajectory runs, with its
    margin penalty `margin`; with fewer runs than the search's or margin 0, a lower bound of its
    cost (every term of run_cost is a maximum over the runs)."""
    c = run_cost(runs, prob)
    if c is None:
        return 1.0 + np.sum([r.periods for r in runs]) * -1e-9
    over, settled = step_metrics(step_feedback(sj, step))
    if not settled:
        return 0.5 + c
    c += 1.0 * max(0.0, over - prob["max_overshoot"])  # 0.01 mm per % over: hard in effect
    return c + margin


# ------------------------------------------------------------------ output
atomic_write = hg_output.atomic_write   # (identify and excite write through it too)


def ini_text(gains, pred, source, notch=None, without=None):
    """The suggestion as INI sections + predicted peaks and margins (comment lines); with a
    notch (f0, Q) its hal lines (commented) and the margins without it (without: predict's)."""
    out = []
    for j, g in enumerate(gains):
        out.append("[JOINT_%d]" % j)
        for k in KEYS:
            out.append("%s = %s" % (k, hg_config.GAIN_FORMAT % g.get(k, 0.0)))
        out.append("")
    out.append("# predicted with these gains%s on %s (%d closed-loop runs through the board model):"
               % (" and the notch below" if notch else "", source, pred["runs"]))
    for j in range(6):
        out.append("# joint %d: peak |f-error| %.5f mm (%.5f..%.5f), peak output %.3f V"
                   % (j, pred["ferror"][j], pred["ferror_lo"][j], pred["ferror_hi"][j], pred["volts"][j]))
    out.append("# peak tool-path error %.5f mm (the tool against the commanded joints; median of the runs)"
               % pred["tool"])
    if "margins" in pred:
        out.append("# margins on the plant at HOME (docs/tuning.md \"Margins\"): %s" % hgm.describe(pred["margins"]))
    if notch:
        out.append("# LinuxCNC's biquad notch f0 %.6g Hz, Q %.6g between pid.N.output and the DAC: in"
                   % notch)
        out.append("# configs/hexaglide.hal replace each joint's \"net zNN-output <= pid.N.output => "
                   "motenc.0.dac-NN-value\" by its two nets")
        out.append("# below, and put the addf lines after addf pid.5.do-pid-calcs, before addf motenc.0.dac-write:")
        out += ["#   " + line for line in hgm.notch_hal(*notch).splitlines()]
        if without:
            out.append("# without the notch, these gains: %s" % (
                hgm.describe(without["margins"]) if "margins" in without else "unstable"))
    return "\n".join(out) + "\n"


def predict(gains, prob, settles, notch=None):
    runs = trajectory_runs(gains, prob, settles, notch=notch)
    if not all(r.ok for r in runs):
        i, bad = next((i, r) for i, r in enumerate(runs) if not r.ok)
        at = (bad.tripped_at if bad.tripped_at >= 0 else bad.periods) - prob["seqs"][(settles[i], i)][1]
        return None, "the loop is unstable: |f-error| exceeds %.3g mm (FERROR) %s%s%s" % (
            prob["ferror_limit"], "%.3f s into the trajectory" % (at * PERIOD_S) if at >= 0 else
            "before the trajectory (on the move from HOME to its first row or settling there)",
            "" if bad.rc == 0 else " (board: %s)" % hg.strerror(bad.rc),
            "; the trajectory asks more than the drives give: %s (give a slower trajectory: a LinuxCNC run "
            "within the INI's MAX_VELOCITY and MAX_ACCELERATION)" % prob["beyond_drive"]
            if prob.get("beyond_drive") else "")
    fe = np.array([r.peak_ferror_mm for r in runs])
    v = np.array([r.peak_output_v for r in runs])
    return {"ferror": np.median(fe, 0), "ferror_lo": fe.min(0), "ferror_hi": fe.max(0),
            "volts": v.max(0), "volts_median": np.median(v.max(1)), "runs": len(runs),
            "tool": float(np.median([r.peak_tool_error_mm for r in runs])),
            **({"margins": margins_of(gains, prob, notch)} if "frf" in prob else {})}, None


def png_saver(outdir, paths):
    """save(fig, name): write matplotlib figure fig as outdir/name (PNG, via
    atomic_write), close it and append its path to paths. outdir is made if missing."""
    import matplotlib.pyplot as plt
    try:
        os.makedirs(outdir, exist_ok=True)
    except OSError as ex:
        raise hg_output.OutputError("cannot write plots into %s: %s" % (outdir, ex.strerror or ex))

    def save(fig, name):
        p = os.path.join(outdir, name)
        atomic_write(p, lambda f: fig.savefig(f, format="png", dpi=100))
        plt.close(fig)
        paths.append(p)
    return save


PLOT_NAMES = ("tune_step.png", "tune_ferror.png", "tune_bode.png")     # what plots() writes into --plots


def plots(outdir, cur, sug, prob, source, notch=None):
    """PLOT_NAMES in outdir (each written to a temp, then renamed): the current gains cur and the
    suggestion sug with its notch (f0, Q) or None, as the prediction runs them."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    paths = []

    save = png_saver(outdir, paths)
    curves = (("current", cur, None), ("suggested" + (" + notch" if notch else ""), sug, per_joint(notch)))

    fig, ax = plt.subplots(figsize=(8, 4.5))
    for lab, g, nf in curves:
        fb = step_response(g, prob, notch=nf)
        if fb is not None:
            ax.plot(np.arange(len(fb)) * PERIOD_S * 1000, fb * 1000, "-", label=lab)
    ax.axhline(50, color="k", lw=0.5)
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("joint 0 feedback (um)")
    ax.set_title("Step response: 0.05 mm command step on joint 0 (model)")
    ax.set_xlim(0, 300)
    ax.legend()
    ax.grid(alpha=0.3)
    save(fig, PLOT_NAMES[0])

    fig, axs = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    for lab, g, nf in curves:
        r = trajectory_runs(g, prob, [SETTLE], keep=True, notch=nf)[0]
        if r.ferror_mm is None or not len(r.ferror_mm):
            continue
        t = np.arange(len(r.ferror_mm)) * PERIOD_S
        j = int(np.argmax(np.abs(r.ferror_mm).max(0)))
        axs[0].plot(t, r.ferror_mm[:, j] * 1000, lw=0.6,
                    label="%s (joint %d, peak %.2f um)" % (lab, j, np.abs(r.ferror_mm).max() * 1000))
        axs[1].plot(t, np.abs(r.output_v).max(1), lw=0.6, label=lab)
    axs[0].set_ylabel("f-error (um)")
    axs[0].set_title("Following error over %s (model)" % os.path.basename(source))
    axs[0].legend(fontsize=8)
    axs[1].set_ylabel("max |output| (V)")
    axs[1].set_xlabel("time (s)")
    for a in axs:
        a.grid(alpha=0.3)
    save(fig, PLOT_NAMES[1])

    freqs = prob["frf_hz"]
    fig, axs = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    for (lab, g, nf), col in zip(curves, ("C0", "C1")):
        lam = hgm.loci(g, freqs, prob["frf"], nf)
        m = margins_of(g, prob, nf)
        c = int(np.argmin(np.abs(1 + lam).min(0)))          # the locus nearest -1
        axs[0].semilogx(freqs, 20 * np.log10(np.maximum(abs(lam[:, c]), 1e-6)), "-", color=col,
                        label="%s: L's locus nearest -1 (GM %.1f dB, PM %.0f deg)" % (lab, m["gm_db"], m["pm_deg"]))
        axs[1].semilogx(freqs, np.degrees(np.unwrap(np.angle(lam[:, c]))), "-", color=col, label=lab)
    if prob["mode_hz"]:
        for a in axs:
            a.axvline(prob["mode_hz"], color="k", lw=0.5, ls=":")
    axs[0].axhline(0, color="k", lw=0.5)
    axs[1].axhline(-180, color="k", lw=0.5)
    axs[0].set_ylabel("gain (dB)")
    axs[0].set_title("Open loop on the plant measured at HOME (docs/tuning.md \"Margins\")")
    axs[1].set_ylabel("phase (deg)")
    axs[1].set_xlabel("frequency (Hz)")
    for a in axs:
        a.grid(alpha=0.3, which="both")
        a.legend(fontsize=7)
    save(fig, PLOT_NAMES[2])
    return paths


def setup(a, prob, joints, cmd):
    """The search's base: the model start's gains (prob["base"], ["fixed"])."""
    try:
        start = model_start(cmd, prob["params"])
    except hg.HexaglideError as ex:
        raise BadInput("the model at the trajectory's poses: %s" % ex)
    P, I, D = pid_from_bandwidth(start, a.bandwidth, a.damping)
    prob["base"] = {"P": P, "I": I, "D": D, "FF1": start["FF1"], "FF2": start["FF2"], "BIAS": start["BIAS"]}
    prob["fixed"] = [{k: g[k] for k in ("DEADBAND", "MAX_OUTPUT", "MAX_ERROR_I", "INPUT_SCALE", "OUTPUT_SCALE",
                                        "OUTPUT_OFFSET") if k in g} for g in joints]
    log("model start (%.0f Hz, damping %.2f): P %.3g I %.3g D %.3g FF1 %.4g FF2 %.4g BIAS %.4g (joint 0); "
        "effective mass %.1f-%.1f kg" % (a.bandwidth, a.damping, P[0], I[0], D[0], start["FF1"][0],
                                         start["FF2"][0], start["BIAS"][0], start["mass_kg"].min(),
                                         start["mass_kg"].max()))
    return start


def search(a, prob):
    """Differential evolution over the gains (x: gains_from_x) and, with prob["notch"], a sixth
    variable, 0 or 1, that puts the notch in the loop (notch_of); every generation's candidates
    in one hg.batch over a.jobs threads; verify's answer."""
    x0 = np.array(X0 + ((0.0,) if prob.get("notch") else ()))
    if not a.whole_search:
        log(critical_windows(prob))
    log("model start: cost %.5f" % costs([x0], prob)[0])
    # scipy's differential_evolution is this solver's solve(); holding the solver lets each
    # generation's trials see the energies of the members they compete with (costs' beat)
    from scipy.optimize._differentialevolution import DifferentialEvolutionSolver
    bounds = [(-1.0, 1.0), (-1.5, 1.0), (-1.0, 1.0), (0.8, 1.2), (0.6, 1.4)] + [(0.0, 1.0)] * (len(x0) - 5)
    switch = [False] * 5 + [True] * (len(x0) - 5)      # the notch switch takes whole values
    gen = [0]
    seen = []                                   # (cost, x, kept?) of every candidate, for verify and the log
    solver = [None]
    t0, p0, s0 = time.time(), prob.get("periods_run", 0), list(prob.get("stopped_at", []))
    r0 = prob.get("stopped_in_run", 0)

    def cost(x):
        return costs([x], prob)[0]

    def beat(n):
        """The energies trial 0..n-1 compete with: with updating="deferred" and no constraints,
        trial i is member i's and replaces it only if its cost is <= member i's. None for the
        first population (no energies yet: every candidate is a member) or if that does not hold."""
        s = solver[0]
        e = getattr(s, "population_energies", None)
        if e is None or n > len(e) or not np.all(np.isfinite(e)) or not np.all(getattr(s, "feasible", False)):
            return None
        return list(e[:n])

    def batch_map(_func, xs):
        xs, b = list(xs), beat(len(xs))
        cs = costs(xs, prob, b, stop=not a.no_stop_early)
        seen.extend((c, tuple(x), b is None or c <= b[i]) for i, (x, c) in enumerate(zip(xs, cs)))
        return cs

    def progress(xk, convergence):
        gen[0] += 1
        log("generation %d: best cost %.5f (%.0f s)" % (gen[0], min(seen)[0] if seen else np.nan, time.time() - t0))

    with DifferentialEvolutionSolver(cost, bounds, x0=x0, maxiter=a.maxiter, popsize=a.popsize,
                                     seed=a.seed, polish=False, tol=1e-3, updating="deferred",
                                     workers=batch_map, callback=progress, init="sobol",
                                     integrality=switch) as sv:
        solver[0] = sv
        res = sv.solve()
    took = time.time() - t0
    at = prob.get("stopped_at", [])
    stopped = [c - (s0[k] if k < len(s0) else 0) for k, c in enumerate(at)]
    where = ", ".join("%d %s" % (c, "on their margins" if k == 0 else "after their step run" if k == 1
                                 else "in or after trajectory run %d" % (k - 1)) for k, c in enumerate(stopped))
    inrun = prob.get("stopped_in_run", 0) - r0
    log("sweep: %d candidates%s in %.1f s, %d thread%s (hg.batch; %.1f per second), %d servo periods run, "
        "%d candidates stopped early%s%s"
        % (res.nfev, " (%d with the notch)" % sum(notch_of(x, prob) is not None for _c, x, _k in seen)
           if any(switch) else "", took, prob["threads"], "s" if prob["threads"] > 1 else "",
           res.nfev / max(took, 1e-9), prob.get("periods_run", 0) - p0, sum(stopped),
           " (%s)" % where if where else "", "; %d of them within a trajectory run" % inrun if inrun else ""))
    if "windows" not in prob and not any(switch) and "search_params" not in prob:
        return res.x, float(res.fun), None
    return verify(prob, seen)


def verify(prob, seen):
    """The search's answer from seen ((cost, x, kept?) of every candidate): of those the search
    kept (the population's members, whose costs are whole; a trial that lost may hold only a
    lower bound, however early it stopped), the VERIFY cheapest without the notch and as many
    with it (where the search has the switch) costed on the whole trajectory with every run;
    (x of the cheapest, the cheapest cost without the notch, with it; None where none ran)."""
    ranked = sorted(set((c, x) for c, x, kept in seen if kept))
    groups = [[(c, x) for c, x in ranked if (notch_of(x, prob) is not None) == on][:VERIFY] for on in (False, True)]
    top = groups[0] + groups[1]
    t0 = time.time()
    whole = costs([np.array(x) for _c, x in top], prob, whole=True)
    k = int(np.argmin(whole))                   # (a tie: the first, without the notch)
    plain, notched = whole[:len(groups[0])], whole[len(groups[0]):]
    log("the search's best %d%s costed on the whole trajectory with every run (%.1f s): cost %s (in the search %s): "
        "kept number %d" % (len(top), " (%d without the notch, %d with it)" % tuple(map(len, groups))
                            if prob.get("notch") else "", time.time() - t0, " ".join("%.5f" % c for c in whole),
                            " ".join("%.5f" % c for c, _x in top), k + 1))
    return np.array(top[k][1]), float(min(plain)) if plain else None, float(min(notched)) if notched else None


# ------------------------------------------------------------------ main


def serial_plant(argv):
    """True when the command line asks for the serial plant: --plant serial, or an --ini with a
    [SERIAL] section (docs/serial.md): tools/hexaglide_tune_serial.py tunes it."""
    import hexaglide_tune_serial as ts
    args = list(sys.argv[1:] if argv is None else argv)
    val = lambda opt: next((args[i + 1] for i, x in enumerate(args[:-1]) if x == opt),
                           next((x.split("=", 1)[1] for x in args if x.startswith(opt + "=")), None))
    plant, ini = val("--plant"), val("--ini")
    return plant == "serial" or (plant is None and ini is not None and ts.is_serial_ini(ini)), plant


def main(argv=None):
    serial, plant = serial_plant(argv)
    if serial:
        import hexaglide_tune_serial as ts
        return ts.main(sys.argv[1:] if argv is None else argv)
    if plant not in (None, "hexaglide"):
        log("--plant %s: unknown plant; use hexaglide, serial" % plant)
        return 2
    ap = hg_cli.Parser(prog="hexaglide tune", description=__doc__.split("\n\n")[0])
    ap.add_argument("--plant", choices=["hexaglide", "serial"], default="hexaglide",
                    help="the machine: hexaglide (default), or serial (implied by an --ini with a [SERIAL] "
                    "section: tools/hexaglide_tune_serial.py, docs/serial.md)")
    ap.add_argument("--trajectory", help="recorded joint commands (see docs/tuning.md); "
                    "default: a generated S-curve move of every axis")
    ap.add_argument("--ini", default=os.path.join(ROOT, "configs", "hexaglide.ini"),
                    help="config with the current gains and limits (default configs/hexaglide.ini)")
    ap.add_argument("--evaluate", action="store_true",
                    help="no search: predict the INI's gains on the trajectory (exit 1 if unstable)")
    ap.add_argument("--gains", metavar="FILE",
                    help="no search: predict and plot these gains (a tune output or INI) against the INI's")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=V",
                    help="with --evaluate: override a gain on all joints, e.g. P=20")
    ap.add_argument("--max-volts", type=hg_csv.number, default=None,
                    help="peak output allowed on the trajectory in every search run, in (0, MAX_OUTPUT] V "
                    "(10 V, the DAC's range, when MAX_OUTPUT is 0); default: the current gains' median peak "
                    "over the prediction's runs, at most MAX_OUTPUT")
    ap.add_argument("--runs", type=hg_csv.integer, default=3,
                    help="closed-loop runs per candidate in the search (different settling), %d..%d; default 3"
                    % RANGES["--runs"][:2])
    ap.add_argument("--max-overshoot", type=hg_csv.number, default=0.15,
                    help="step overshoot allowed (fraction), 0..1; default 0.15")
    ap.add_argument("--bandwidth", type=hg_csv.number, default=25.0,
                    help="start bandwidth, in (0, %g] Hz (a quarter of the 1 kHz servo rate); default 25"
                    % RANGES["--bandwidth"][1])
    ap.add_argument("--damping", type=hg_csv.number, default=0.7,
                    help="start damping ratio, in (0, %g]; default 0.7" % RANGES["--damping"][1])
    ap.add_argument("--maxiter", type=hg_csv.integer, default=25,
                    help="generations of differential evolution, %d..%d; default 25" % RANGES["--maxiter"][:2])
    ap.add_argument("--popsize", type=hg_csv.integer, default=8,
                    help="population per search variable, %d..%d; default 8" % RANGES["--popsize"][:2])
    add_jobs_option(ap)
    ap.add_argument("--no-stop-early", action="store_true",
                    help="run every candidate's every trajectory run, also one whose first run already "
                    "costs more than the member it competes with (the same answer, slower: a check)")
    ap.add_argument("--param", action="append", default=[], metavar="NAME=V",
                    help="a model parameter of the machine tuned on (SI, docs/model.md), e.g. k_axial=0 "
                    "for rigid drive trains; default the board's defaults (flexible trains)")
    ap.add_argument("--whole-search", action="store_true",
                    help="run every candidate of the search on the whole trajectory, not on its critical "
                         "windows (docs/tuning.md; slower on a long trajectory, the same on a short one)")
    ap.add_argument("--search-integrator", choices=["auto", "board"], default="auto",
                    help="the scheme the search's runs integrate the machine with: auto (default) RK4 where it "
                    "needs fewer accelerations a servo period than the board's scheme (the flexible trains), "
                    "its best then costed on the board's; board: the board's throughout (docs/tuning.md)")
    ap.add_argument("--no-notch", action="store_true",
                    help="do not try a biquad notch at the drive trains' resonance")
    ap.add_argument("--seed", type=hg_csv.integer, default=1, help="the search's random seed, 0..2^32-1; default 1")
    ap.add_argument("--output", help="also write the suggestion to this file")
    ap.add_argument("--plots", help="directory for %s" % ", ".join(PLOT_NAMES))
    a = ap.parse_args(argv)

    try:
        why = hg_cli.out_of_range(a, RANGES)
        if why:
            raise BadInput(why)
        sets = {}
        for s in a.set:
            k, _, v = s.partition("=")
            if k not in hg.GAIN_KEYS:
                raise BadInput("--set %s: unknown gain (one of %s)" % (s, " ".join(hg.GAIN_KEYS)))
            try:
                sets[k] = hg_csv.number(v)
            except ValueError:
                raise BadInput("--set %s: not a number" % s)
            if not np.isfinite(sets[k]):
                raise BadInput("--set %s: not a finite number" % s)
        for s in a.param:                  # the names and numbers here; the values the C reader checks
            k, _, v = s.partition("=")
            try:
                hg.Params()[k] = hg_csv.number(v)
            except (KeyError, ValueError):
                raise BadInput("--param %s: not a model parameter with a number it accepts (names: docs/model.md)"
                               % s)
        cfg = read_config(a.ini, a.param)  # defaults, [HEXAGLIDE], --param: as sim and soak take them
        try:
            hg_config.check_period(cfg, "tune", PERIOD_S, PERIOD_WHY)
        except hg_config.ConfigError as ex:
            raise BadInput(str(ex))
        joints, axes, params = cfg.joints, cfg.axes, cfg.params
        for k, why in hg.Board(params=params).enc_scale_notes([g["INPUT_SCALE"] for g in joints]):
            log("warning: [JOINT_%d]INPUT_SCALE = %s" % (k, why))   # (the encoder's are others: said, run)
        ferror_limit = min(g["FERROR"] for g in joints)   # (the INI's gains: checked by read_config, as soak)
        vmax_dac = min(hg_config.output_limit(g) for g in joints)
        if a.max_volts is not None and not (0 < a.max_volts <= vmax_dac):
            raise BadInput("--max-volts %g: must be in (0, %g] V (the smallest [JOINT_N]MAX_OUTPUT of %s; "
                           "MAX_OUTPUT 0 means the DAC's 10 V)" % (a.max_volts, vmax_dac, a.ini))
        if a.trajectory:
            cmd = load_trajectory(a.trajectory)
            source = a.trajectory
            check_reach(source, cmd, joints)
            if not a.evaluate and not a.gains and np.ptp(cmd, 0).max() < 1.0 / (max(abs(g.get("INPUT_SCALE", 0)) for g in joints) or 1000):
                raise BadInput("%s: no joint moves by an encoder count: the search would tune the gains to standing "
                               "still; give a recorded motion (or --evaluate the INI's gains on it)" % source)
        else:
            cmd = generated_move(axes, params, a.ini)
            source = "the generated move"
        given = given_notch = None
        if a.gains and a.evaluate:             # (--evaluate took the INI's and said nothing of the file)
            raise BadInput("--gains %s with --evaluate: --evaluate predicts the INI's gains, --gains the file's; "
                           "give one of them" % a.gains)
        if a.gains:
            try:
                given, _ = hg.read_gains(a.gains)
                given_notch = hgm.read_notch(a.gains)     # (a tune output's biquad lines; an INI has none)
            except (OSError, ValueError) as ex:
                raise BadInput("--gains %s: %s" % (a.gains, getattr(ex, "strerror", None) or ex))
        cur = [dict(pid_keys(g), **sets) for g in joints]
        for what, gains, nf in (("--set %s" % " ".join(a.set), cur if a.set else None, None),
                                ("--gains %s" % a.gains, [dict(c, **g) for c, g in zip(cur, given)] if given
                                 else None, per_joint(given_notch))):
            try:                           # the loop's rules (hg_loop_config_check) now, not as a traceback later
                if gains:
                    hg.loop_config(gains, ferror_limit_mm=ferror_limit, notch=nf)
            except ValueError as ex:
                raise BadInput("%s: %s" % (what, ex))
        hg_output.refuse_stdout([("--output", a.output), ("--plots", a.plots)])   # (the suggestion is on stdout)
        hg_output.refuse_in_dir(("--output", a.output), ("--plots", a.plots), PLOT_NAMES)
        if a.output:
            hg_output.check_writable(a.output)         # a missing or unwritable directory now, not after the search
            hg_output.refuse_inputs([("--output", a.output)], [("--ini", a.ini), ("--trajectory", a.trajectory),
                                                               ("--gains", a.gains)])
        if a.plots and os.path.exists(a.plots) and not os.path.isdir(a.plots):
            raise BadInput("--plots %s is a file: give a directory (tune writes %s into it)"
                           % (a.plots, ", ".join(PLOT_NAMES)))
        if a.plots and a.evaluate:
            raise BadInput("--plots %s with --evaluate: --evaluate draws no plots; for plots of given gains "
                           "against the INI's use --gains FILE --plots DIR (docs/tuning.md)" % a.plots)
        if a.plots:                        # now, not after the search (as --output)
            try:
                hg_output.check_writable_dir(a.plots, PLOT_NAMES)
            except hg_output.OutputError as ex:
                raise BadInput("--plots %s: %s" % (a.plots, ex))
    except (BadInput, hg_output.OutputError) as ex:
        log(ex)
        return 2
    log("trajectory: %s, %d samples (%.1f s)" % (source, len(cmd), len(cmd) * PERIOD_S))
    if len(cmd) * PERIOD_S > 60:
        log("warning: a %.0f s trajectory: every closed-loop run is %d servo periods (15 runs per prediction, %d "
            "per candidate of the search): this takes long; crop it to the motion that matters"
            % (len(cmd) * PERIOD_S, len(cmd) + SETTLE + RAMP, max(1, a.runs)))
    threads = a.jobs or hg.cores()
    prob = {"cmd": cmd, "ferror_limit": ferror_limit, "max_overshoot": a.max_overshoot,
            "search_settles": [SETTLE + 137 * i for i in range(max(1, a.runs))],
            "params": params, "board_params": params.board_params(), "threads": threads}
    settles = PREDICT_SETTLES
    try:
        start = setup(a, prob, joints, cmd)
        prob["beyond_drive"] = beyond_drive(cmd, start, joints)
    except BadInput as ex:
        log(ex)
        return 2
    if prob["beyond_drive"]:
        log("warning: the trajectory asks more than the drives give: %s" % prob["beyond_drive"])
    t0 = time.time()
    try:
        prob["frf_hz"], prob["frf"] = hgm.plant_frf(start, params, threads)
    except hg.HexaglideError as ex:
        log("the plant's frequency response at HOME could not be measured: %s (the machine of --param?)" % ex)
        return 1
    prob["mode_hz"] = hgm.first_mode(prob["frf_hz"], prob["frf"])
    log("plant at HOME measured (%d tones, %.1f s): %s" % (
        len(prob["frf_hz"]), time.time() - t0,
        "first drive-train resonance the loops see at %.0f Hz" % prob["mode_hz"] if prob["mode_hz"]
        else "no drive-train resonance below %.0f Hz (rigid trains)" % (0.5 / PERIOD_S)))

    cur_pred, why = predict(cur, prob, settles)
    if a.evaluate:
        if cur_pred is None:
            log("gains of %s%s: %s" % (a.ini, " with " + " ".join(a.set) if a.set else "", why))
            return 1
        bad = hgm.verdict(cur_pred["margins"])
        log("margins: %s" % hgm.describe(cur_pred["margins"]))
        if bad:
            log("warning: gains of %s%s: %s" % (a.ini, " with " + " ".join(a.set) if a.set else "", bad))
        text = ini_text([dict({k: 0.0 for k in KEYS}, **g) for g in cur], cur_pred, source)
        if a.output:
            atomic_write(a.output, lambda f: f.write(text.encode()))
        sys.stdout.write(text)
        return 0
    if cur_pred is None:
        log("current gains: %s (tuning from the model's gains instead)" % why)
        vcur = None
    else:
        vcur = cur_pred["volts_median"]
        log("current gains: peak |f-error| %.5f mm, peak output %.3f V (median of %d runs; max %.3f V)"
            % (cur_pred["ferror"].max(), vcur, cur_pred["runs"], cur_pred["volts"].max()))
    prob["vmax"] = a.max_volts if a.max_volts is not None else min(vmax_dac, vcur if vcur else vmax_dac)
    if a.gains:
        sug = [dict(c, **g) for c, g in zip(cur, given)]
        notch, without = given_notch, None
        log("gains of %s (no search)%s" % (a.gains, ", with the biquad notch f0 %g Hz, Q %g of its hal lines"
                                           % notch if notch else ""))
        if notch:                          # (its f0 and Q biquad.comp takes: loop_config checked them)
            without, _ = predict(sug, prob, settles)
    else:
        prob["notch"] = None
        if prob["mode_hz"] and not a.no_notch:
            prob["notch"] = hgm.notch_for(gains_from_x(X0, prob), prob["frf_hz"], prob["frf"], prob["mode_hz"])
            log("the search may put LinuxCNC's biquad notch f0 %.0f Hz Q %.1f (at the resonance, for the model "
                "start's gains) in the loop: a sixth search variable (--no-notch leaves it out)" % prob["notch"])
        search_bp, line = search_scheme(params, board_params(prob), a.search_integrator)
        if search_bp is not None:
            prob["search_params"] = search_bp
        log(line)
        x, c_plain, c_notch = search(a, prob)
        sug, notch, without = hg_config.as_printed(gains_from_x(x, prob), KEYS), None, None
        if notch_of(x, prob):
            without, _ = predict(sug, prob, settles)
            notch = prob["notch"]
            log("the notch lets these gains work: cost %.5f against %.5f without it" % (c_notch, c_plain))
        elif prob["notch"]:
            log("the notch does not help (%s against %.5f without it): none proposed"
                % ("cost %.5f" % c_notch if c_notch is not None else "the search's best had none", c_plain))
    pred, why = predict(sug, prob, settles, per_joint(notch))
    if pred is None:
        log("no stable gains found: %s" % why)
        return 1
    over, settled = step_metrics(step_response(sug, prob, notch=per_joint(notch)))
    bad = hgm.verdict(pred["margins"])
    if not settled or bad or over > a.max_overshoot + 0.02:
        log("the %s do not meet the stability margins (overshoot %.0f%%, settled %s%s; %s; peak |f-error| "
            "%.5f mm, peak tool-path error %.5f mm): nothing suggested"
            % ("gains of " + a.gains if a.gains else "best gains found", 100 * over, settled,
               "; " + bad if bad else "", hgm.describe(pred["margins"]), pred["ferror"].max(), pred["tool"]))
        return 1
    log("suggested: peak |f-error| %.5f mm (current %s), peak tool-path error %.5f mm, peak output %.3f V "
        "(median of %d runs, as the limit; max %.3f V; limit %.3f V), step overshoot %.0f%%; %s"
        % (pred["ferror"].max(), "%.5f mm" % cur_pred["ferror"].max() if cur_pred else "unstable",
           pred["tool"], pred["volts_median"], pred["runs"], pred["volts"].max(), prob["vmax"], 100 * over,
           hgm.describe(pred["margins"])))
    if pred["volts_median"] > prob["vmax"] + VOLTS_SHOWN:
        log("warning: the suggestion's peak output, %.3f V (median of %d runs), is above the limit %.3f V: "
            "the search weighs %g mm of cost per volt above it, and its runs are fewer than these; give "
            "--max-volts below %.3f V to keep under it" % (pred["volts_median"], pred["runs"], prob["vmax"],
                                                          W_VOLTS, prob["vmax"]))
    cur_bad = hgm.verdict(cur_pred["margins"]) if cur_pred is not None else None
    if cur_pred is not None and pred["ferror"].max() >= cur_pred["ferror"].max():
        log("note: the suggestion is not better than the current gains on this trajectory "
            "(%.5f vs %.5f mm): %s" % (pred["ferror"].max(), cur_pred["ferror"].max(),
                                       "the current gains miss the stability margins the suggestion must meet "
                                       "(the warning below)" if cur_bad else
                                       "the current gains are already at the encoder's resolution or the "
                                       "limits (--max-volts, --max-overshoot) bind"))
    if cur_bad:
        log("warning: the current gains: %s" % cur_bad)
    text = ini_text(sug, pred, source, notch, without)
    if a.output:
        atomic_write(a.output, lambda f: f.write(text.encode()))
    sys.stdout.write(text)                 # the suggestion first: a plot that fails late loses nothing
    sys.stdout.flush()
    if a.plots:
        try:
            for p in plots(a.plots, cur if cur_pred else sug, sug, prob, source, notch):
                log("wrote", p)
        except hg_output.OutputError as ex:
            log("%s (the suggested gains are on standard output%s)" % (ex, ", and in " + a.output if a.output else ""))
            return 1
    return 0


if __name__ == "__main__":
    hg_cli.run(main, log, (hg_output.OutputError,))
