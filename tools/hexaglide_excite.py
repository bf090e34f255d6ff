#!/usr/bin/python3
"""hexaglide_excite.py - an excitation program for identification: a finite
Fourier series per world axis, optimised (scipy) for the condition number
of the base regressor, inside the config's working volume ([AXIS_*]
MIN/MAX_LIMIT), the joint ranges ([JOINT_N] MIN/MAX_LIMIT), the speed and
acceleration limits of axes and joints, and a bound on the drive volts the
prior model predicts (well below the amplifier's saturation). Written as
G-code that LinuxCNC runs: inverse-time G1 segments (G93), one per
--segment seconds. Normally started as `build/hexaglide excite`
(src/cli/cmd_excite.c); see docs/identification.md.

stdout: the G-code (or --output FILE). stderr: progress, the run time and
the condition number reached. Exit codes: 0 ok, 1 no feasible trajectory,
2 bad input.
"""
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hexaglide as hg  # noqa: E402
import hexaglide_identify as hid  # noqa: E402
import hg_config  # noqa: E402
import hg_csv  # noqa: E402
import hg_cli  # noqa: E402
import hg_output  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
AXES = "XYZABC"
# world units -> SI: mm -> m, deg -> rad
TO_SI = np.array([1e-3] * 3 + [np.pi / 180] * 3)


def log(*a):
    """Progress and results on stderr."""
    print("hexaglide excite:", *a, file=sys.stderr, flush=True)


class Fourier:
    """x_i(t) = x0_i + sum_l a_il/(l w) sin(l w t) - b_il/(l w) cos(l w t), per axis
    (world units, mm and deg), with x'(0) = x''(0) = 0 imposed through the
    last harmonic (the program starts and ends at rest, at x(0))."""

    def __init__(self, harmonics, period_s):
        self.L, self.w = harmonics, 2 * np.pi / period_s
        self.nfree = 6 * (2 * (harmonics - 1)) + 6

    def coefficients(self, theta):
        """(x0 (6), a (6, L), b (6, L)) from the free variables."""
        L = self.L
        x0 = theta[:6]
        f = theta[6:].reshape(6, 2, L - 1)
        l = np.arange(1, L + 1)
        a = np.zeros((6, L))
        b = np.zeros((6, L))
        a[:, :-1], b[:, :-1] = f[:, 0], f[:, 1]
        a[:, -1] = -a[:, :-1].sum(1)                             # x'(0) = sum a = 0
        b[:, -1] = -(b[:, :-1] * l[:-1]).sum(1) / L              # x''(0) = w sum l b = 0
        return x0, a, b

    def eval(self, theta, t):
        """x, x', x'' (n, 6) at times t (s), world units."""
        x0, a, b = self.coefficients(theta)
        l = np.arange(1, self.L + 1)
        ph = np.outer(t, l) * self.w                             # (n, L)
        s, c = np.sin(ph), np.cos(ph)
        lw = l * self.w
        x = s @ (a / lw).T - c @ (b / lw).T
        x0c = x0 - (-(b / lw).sum(1))                            # x(0) = x0
        xd = c @ a.T + s @ b.T
        xdd = -s @ (a * lw).T + c @ (b * lw).T
        return x + x0c, xd, xdd


DITHER_BAND_HZ = (200.0, 490.0)   # the trains' dither: around their first axial mode (352.75 Hz at HOME)
DITHER_SWEEP_S = 2.0              # one sweep up and down of the band
DITHER_V = 0.5                    # volts (amplitude) on each drive's DAC
DITHER_V_MAX = 2.0                # at most (the DAC's +-10 V less the program's --max-volts and a margin)


TRAIN_STROKE_MM = 30.0           # the trains' program: vertical strokes down from HOME and back ...
TRAIN_SPEEDS = (40.0, 20.0, 30.0)  # ... at these speeds in turn (mm/s; 0.8 of [AXIS_Z] MAX_VELOCITY at most): viscous friction, gravity
                                 # preload every train, at a different force each (stiffness apart from backlash)
TRAIN_ACCEL = 400.0              # ... with this acceleration (mm/s^2, 0.8 of [AXIS_Z] MAX_ACCELERATION) at the ends (reversals: backlash)


def _stroke(dt, stroke_mm, speed, accel):
    """Distances (mm) of one trapezoidal stroke, every dt, rest to rest."""
    ta = speed / accel
    tc = (stroke_mm - speed * ta) / speed
    T = 2 * ta + tc
    u = np.arange(1, int(np.ceil(T / dt)) + 1) * dt
    u = np.minimum(u, T)
    return np.where(u < ta, 0.5 * accel * u * u,
                    np.where(u < ta + tc, 0.5 * speed * ta + speed * (u - ta), stroke_mm - 0.5 * accel * (T - u) ** 2))


def strokes(n, dt, stroke_mm=TRAIN_STROKE_MM, speeds=TRAIN_SPEEDS, accel=TRAIN_ACCEL):
    """(n,) head heights (mm, 0 = HOME) of the trains' program (--trains'
    G-code as LinuxCNC's trapezoidal planner runs it): from rest at HOME
    down stroke_mm and back up, at each of speeds in turn, accel at the ends."""
    out = [np.zeros(1)]
    i = 0
    while sum(len(x) for x in out) < n:
        d = _stroke(dt, stroke_mm, speeds[i % len(speeds)], accel)
        out += [-d, -stroke_mm + d]
        i += 1
    return np.concatenate(out)[:n]


def _sweep_s(k, sweep_s):
    """Drive k's sweep time: the six differ by 10% steps, so their chirps drift apart."""
    return sweep_s * (1.0 + 0.1 * k)


def dither(n, dt, band=DITHER_BAND_HZ, amp_v=DITHER_V, sweep_s=DITHER_SWEEP_S):
    """(n, 6) volts of the trains' dither, as the HAL snippet of --dither makes
    it from stock components: siggen.N's sine at a frequency swept linearly
    up and down the band by a slow triangle (siggen.6+N's, through scale.N;
    siggen's phase accumulates f dt each period), summed into pid.N's output
    by sum2.N. Drive N sweeps in _sweep_s(N): the six chirps drift apart, so
    each drive's response is told from the others'."""
    t = np.arange(1, n + 1) * dt
    out = np.zeros((n, 6))
    for k in range(6):
        u = (t / _sweep_s(k, sweep_s)) % 2.0
        tri = np.where(u < 1.0, u, 2.0 - u)                      # 0..1..0, one up-and-down per 2 sweeps
        f = band[0] + (band[1] - band[0]) * tri
        out[:, k] = amp_v * np.sin(2 * np.pi * np.cumsum(f) * dt)
    return out


DITHER_HAL = os.path.join(ROOT, "configs", "hexaglide.hal")   # --hal's default: the HAL file the snippet follows
DAC_WRITE = "motenc.0.dac-write"          # the servo thread's function that writes pid.N.output to the DACs


def servo_thread(path):
    """The functions of the HAL file path's `addf FUNCT servo-thread [POSITION]` lines in the order
    the servo thread runs them: halcmd's, a POSITION > 0 counted from the thread's start (1: first),
    < 0 from its end (-1, as without one: last); ValueError naming the file and line of a POSITION
    halcmd refuses, or a file that cannot be read."""
    funcs = []
    try:
        with open(path) as f:
            text = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as ex:
        raise ValueError("--hal %s: cannot read it: %s" % (path, getattr(ex, "strerror", None) or ex))
    for no, line in enumerate(text, 1):
        w = line.split("#", 1)[0].split()
        if len(w) < 3 or w[0] != "addf" or w[2] != "servo-thread":
            continue
        try:
            pos = int(w[3]) if len(w) > 3 else -1
        except ValueError:
            pos = 0
        if pos == 0 or abs(pos) > len(funcs) + 1:
            raise ValueError("%s line %d: addf %s servo-thread %s: halcmd takes a position of 1..%d or -1..-%d "
                             "here" % (path, no, w[1], w[3], len(funcs) + 1, len(funcs) + 1))
        funcs.insert(pos - 1 if pos > 0 else len(funcs) + 1 + pos, w[1])
    return funcs


def dac_position(path):
    """The addf position (counted from the end, as halcmd takes it) that runs a function added
    after the HAL file path right before its DAC_WRITE, so after the pids (the dither's sum2.N
    then adds to this period's pid.N.output, as dither() says); ValueError naming the file where
    its servo thread has no DAC_WRITE, or a pid.N.do-pid-calcs after it (or none)."""
    funcs = servo_thread(path)
    if DAC_WRITE not in funcs:
        raise ValueError("%s: no `addf %s servo-thread`: the dither's functions go right before the DAC write; "
                         "give --hal the HAL file of the servo thread the snippet is loaded after" % (path, DAC_WRITE))
    k = funcs.index(DAC_WRITE)
    late = [p for p in ("pid.%d.do-pid-calcs" % j for j in range(6)) if p not in funcs[:k]]
    if late:
        raise ValueError("%s: %s is not added to the servo thread before %s: the dither adds to pid.N.output "
                         "on its way to the DAC" % (path, late[0], DAC_WRITE))
    return k - len(funcs) - 1


def dither_hal(band=DITHER_BAND_HZ, amp_v=DITHER_V, sweep_s=DITHER_SWEEP_S, hal=DITHER_HAL):
    """The HAL snippet of the trains' dither (dither() is what it makes), to
    load right after the HAL file hal (configs/hexaglide.hal): each pid.N.output
    then reaches its DAC through sum2.N, with siggen.N's chirp, all run before
    the DAC write (dac_position), in the period the pid computes."""
    pos = dac_position(hal)
    lines = ["# the drive trains' dither (hexaglide excite --dither): chirps %g..%g Hz, %g V"
             % (band[0], band[1], amp_v),
             "# load right after %s: addf's position %d runs these functions before its %s"
             % (os.path.basename(hal), pos, DAC_WRITE),
             "loadrt siggen num_chan=12", "loadrt sum2 count=6", "loadrt scale count=6"]
    for k in range(6):
        tr = 6 + k
        lines += ["addf siggen.%d.update servo-thread %d" % (tr, pos), "addf scale.%d servo-thread %d" % (k, pos),
                  "addf siggen.%d.update servo-thread %d" % (k, pos), "addf sum2.%d servo-thread %d" % (k, pos),
                  "setp siggen.%d.frequency %.6g" % (tr, 0.5 / _sweep_s(k, sweep_s)),
                  "setp siggen.%d.amplitude 0.5" % tr, "setp siggen.%d.offset 0.5" % tr,
                  "setp scale.%d.gain %.6g" % (k, band[1] - band[0]), "setp scale.%d.offset %.6g" % (k, band[0]),
                  "setp siggen.%d.amplitude %.6g" % (k, amp_v),
                  "net dither-sweep-%d siggen.%d.triangle => scale.%d.in" % (k, tr, k),
                  "net dither-f-%d scale.%d.out => siggen.%d.frequency" % (k, k, k),
                  "unlinkp pid.%d.output" % k, "unlinkp motenc.0.dac-%02d-value" % k,
                  "net pid-out-%d pid.%d.output => sum2.%d.in0" % (k, k, k),
                  "net dither-%d siggen.%d.sine => sum2.%d.in1" % (k, k, k),
                  "net dac-%d sum2.%d.out => motenc.0.dac-%02d-value" % (k, k, k)]
    return "\n".join(lines) + "\n"


def read_config(a):
    """The config of --ini as build/hexaglide reads it (tools/hg_config.py, `hexaglide config`):
    the prior machine (defaults, [HEXAGLIDE], then --set), the limits and the servo loops' keys
    ([JOINT_N]MAX_OUTPUT, OUTPUT_SCALE: the drive's reach) as soak reads them; ValueError naming the
    key, file and line of a refused value."""
    try:
        return hg_config.read(a.ini, getattr(a, "set", []), loop=True, cmd="excite", plant_option=None)
    except hg_config.ConfigError as ex:
        raise ValueError(str(ex))


class Problem:
    """Limits of the config and the prior model, evaluated on a time grid."""

    def __init__(self, a, params, cfg=None):
        """cfg: read_config(a) (read here when not given); params: the prior machine."""
        cfg = cfg or read_config(a)
        joints, axes = cfg.joints, cfg.axes
        self.margin = a.margin
        self.lim = {}
        for ax in AXES:
            lim = axes.get(ax, {})
            for key in ("MIN_LIMIT", "MAX_LIMIT", "MAX_VELOCITY", "MAX_ACCELERATION"):
                if key not in lim:
                    raise ValueError("%s: [AXIS_%s] has no %s" % (a.ini, ax, key))
            self.lim[ax] = lim
        self.jlim = []
        for j, g in enumerate(joints):
            for key in ("MIN_LIMIT", "MAX_LIMIT", "MAX_VELOCITY", "MAX_ACCELERATION"):
                if key not in g:
                    raise ValueError("%s: [JOINT_%d] has no %s" % (a.ini, j, key))
            self.jlim.append(g)
        self.xmin = np.array([self.lim[x]["MIN_LIMIT"] for x in AXES])
        self.xmax = np.array([self.lim[x]["MAX_LIMIT"] for x in AXES])
        self.amax = np.array([self.lim[x]["MAX_ACCELERATION"] for x in AXES])
        # LinuxCNC blends G1 segments that move A B C parabolically (no tangent or arc
        # blends with rotary motion, src/emc/tp/tp.c): each segment then accelerates
        # at half the axis limit for at most half its length, so an axis keeps its
        # speed from segment to segment only below 0.5 a_max * segment duration
        self.vmax = np.minimum([self.lim[x]["MAX_VELOCITY"] for x in AXES], 0.5 * self.amax * a.segment)
        self.jmin = np.array([g["MIN_LIMIT"] for g in joints])
        self.jmax = np.array([g["MAX_LIMIT"] for g in joints])
        self.jvmax = np.array([g["MAX_VELOCITY"] for g in joints])
        self.jamax = np.array([g["MAX_ACCELERATION"] for g in joints])
        self.max_volts = a.max_volts
        self.params = params
        self.reg = hid.Regressor(params)
        self.pi = hid.prior_pi(params)
        self.fpv = hid.force_per_volt(params)
        self.base = hid.StructuralBase(self.reg)
        self.fourier = Fourier(a.harmonics, a.period)
        self.t_opt = np.linspace(0, a.period, a.grid, endpoint=False)

    def evaluate(self, theta, t):
        """(regressor rows, joint positions/velocities/accelerations (mm), volts, world x, x', x'')."""
        x, xd, xdd = self.fourier.eval(theta, t)
        Y, z, zd, zdd = self.reg.pose(x * TO_SI, xd * TO_SI, xdd * TO_SI)
        volts = (Y @ self.pi) / self.fpv
        return Y, z * 1e3, zd * 1e3, zdd * 1e3, volts, x, xd, xdd

    NMARGINS = 54

    def margin_names(self):
        """What each entry of margins() bounds, in its order (for messages)."""
        def block(names):
            return (["%s above MAX_LIMIT" % n for n in names] + ["%s below MIN_LIMIT" % n for n in names] +
                    ["%s speed (MAX_VELOCITY)" % n for n in names] + ["%s acceleration (MAX_ACCELERATION)" % n
                                                                      for n in names])
        joints = ["joint %d" % j for j in range(len(self.jmin))]
        return (block(["axis %s" % x for x in AXES]) + block(joints) +
                ["%s drive volts (--max-volts %g V)" % (n, self.max_volts) for n in joints])

    def centre_check(self):
        """None, or why no program can keep within --margin: the programs' centre (the middle of
        every [AXIS_*] range, at rest) puts a position outside its band (a joint's range centre is
        not where the axes' centre puts the joint), with the smallest --margin that admits it."""
        centre = (self.xmin + self.xmax) / 2
        g, Y = self.margins(np.concatenate([centre, np.zeros(self.fourier.nfree - 6)]), self.t_opt[:1])
        if Y is None:
            return "the middle of the [AXIS_*] ranges %s is no pose the machine can take" % list(centre)
        names = self.margin_names()
        worst = max((i for i, n in enumerate(names) if "LIMIT" in n), key=lambda i: g[i])   # the positions
        if g[worst] <= 0:
            return None
        return ("--margin %g: the programs' centre (the middle of every [AXIS_*] range, at rest) already puts %s "
                "beyond the band --margin keeps (the middle %g of each range); no program fits: give --margin %.3g "
                "or more" % (self.margin, names[worst], self.margin, self.margin + 2 * g[worst]))

    def margins(self, theta, t):
        """Every limit, per axis and joint, as value / limit - margin <= 0 (the
        largest over t): world position (both ends of the range, the margin
        split between them), speed, acceleration; the same for the joints;
        the prior model's drive volts against --max-volts."""
        x, xd, xdd = self.fourier.eval(theta, t)
        m = self.margin

        def rng(v, lo, hi):
            span = hi - lo
            return [((v - hi) / span).max(0) + (1 - m) / 2, ((lo - v) / span).max(0) + (1 - m) / 2]
        out = rng(x, self.xmin, self.xmax) + [(np.abs(xd) / self.vmax).max(0) - m,
                                              (np.abs(xdd) / self.amax).max(0) - m]
        try:
            Y, z, zd, zdd = self.reg.pose(x * TO_SI, xd * TO_SI, xdd * TO_SI)
        except hg.HexaglideError:
            return np.ones(self.NMARGINS), None
        z, zd, zdd = z * 1e3, zd * 1e3, zdd * 1e3
        volts = (Y @ self.pi) / self.fpv
        out += rng(z, self.jmin, self.jmax) + [(np.abs(zd) / self.jvmax).max(0) - m,
                                               (np.abs(zdd) / self.jamax).max(0) - m,
                                               np.abs(volts).max(0) / self.max_volts - 1]
        return np.concatenate(out), Y

    def cond(self, Y):
        """Condition number of the base regressor rows Y (n, 6, NCOL)."""
        return self.base.condition(Y.reshape(-1, Y.shape[-1]))


def design(a, prob, rng):
    """Best of a.starts SLSQP runs from random feasible starts: theta, cond."""
    from scipy.optimize import minimize
    F = prob.fourier
    cache = {}

    def ev(theta):
        key = theta.tobytes()
        if key not in cache:
            if len(cache) > 64:
                cache.clear()
            g, Y = prob.margins(theta, prob.t_opt)
            cache[key] = (g, np.log(prob.cond(Y)) if Y is not None else 50.0)
        return cache[key]

    best = None
    for s in range(a.starts):
        # a random start, scaled down until it is inside every limit
        theta = np.concatenate([(prob.xmin + prob.xmax) / 2, rng.normal(size=F.nfree - 6)])
        scale = np.repeat(prob.vmax, 2 * (F.L - 1)) / (2 * F.L)
        theta[6:] *= scale
        for _ in range(60):
            if (ev(theta)[0] <= 0).all():
                break
            theta[6:] *= 0.8
        t0 = time.time()
        res = minimize(lambda th: ev(th)[1], theta, method="SLSQP",
                       constraints=[{"type": "ineq", "fun": lambda th: -ev(th)[0]}],
                       options={"maxiter": a.maxiter, "ftol": 1e-4})
        th = res.x.copy()
        for _ in range(40):                      # a slightly violated limit: shrink the motion
            if (ev(th)[0] <= 0).all():
                break
            th[6:] *= 0.99
        g, lc = ev(th)
        res.x = th
        ok = (g <= 0).all()
        log("start %d: condition number %.0f%s (%d iterations, %.0f s)"
            % (s + 1, np.exp(lc), "" if ok else " (limits not met: discarded)", res.nit, time.time() - t0))
        if ok and (best is None or lc < best[1]):
            best = (res.x, lc)
    return best


def fine_check(prob, theta, period, dt=0.001):
    """Limits on a 1 ms grid over one period: (margins, cond, volts peak, joint peaks)."""
    t = np.arange(0, period, dt)
    g, Y = prob.margins(theta, t)
    return g, prob.cond(Y) if Y is not None else np.inf


def gcode(prob, theta, a, cond):
    """The program text: approach x(0) at rest, periods x inverse-time segments, back to x(0)."""
    F = prob.fourier
    seg = a.segment
    n = int(round(a.period * a.periods / seg))
    t = np.arange(n + 1) * seg
    x, _, _ = F.eval(theta, t)
    total = n * seg
    lines = ["( hexaglide excitation for hexaglide identify: docs/identification.md )",
             "( written by: hexaglide excite %s )" % " ".join(a.argv).replace("(", "").replace(")", ""),
             "( Fourier series per world axis: %d harmonics of %.4g Hz, %d periods of %.4g s )"
             % (F.L, 1 / a.period, a.periods, a.period),
             "( condition number of the base regressor, columns scaled to unit norm: %.1f )" % cond,
             "( the excitation runs %.1f s in %d inverse-time G1 segments of %.0f ms )"
             % (total, n, seg * 1e3),
             "G21 G90 G17 G40 G49 G54 G94",
             "G64",
             "G1 %s F600" % " ".join("%s%.4f" % (ax, v) for ax, v in zip(AXES, x[0])),
             "G4 P0.5",
             "G93"]
    fword = 1.0 / (seg / 60.0)
    for i in range(1, n + 1):
        lines.append("G1 %s F%.6g" % (" ".join("%s%.4f" % (ax, v) for ax, v in zip(AXES, x[i])), fword))
    lines += ["G94", "G4 P0.5", "G1 X0 Y0 Z0 A0 B0 C0 F600", "M2", ""]
    return "\n".join(lines), total


def trains_gcode(a, axes):
    """The trains' program: vertical strokes from HOME down --stroke mm and back
    at each of TRAIN_SPEEDS (held to --margin of [AXIS_Z] MAX_VELOCITY and
    the stroke to --margin of its range), exact stop at each end (the
    reversals that show the backlash), repeated for --seconds. ValueError
    naming the limit when the config leaves no room."""
    z = axes.get("Z", {})
    lo, vmax = z.get("MIN_LIMIT"), z.get("MAX_VELOCITY")
    if lo is None or vmax is None:
        raise ValueError("%s: [AXIS_Z] needs MIN_LIMIT and MAX_VELOCITY for the trains' program" % a.ini)
    if not (0 < a.stroke <= a.margin * -lo):
        raise ValueError("--stroke %g mm: must be in (0, %g] (--margin %g of [AXIS_Z] MIN_LIMIT %g below HOME)"
                         % (a.stroke, a.margin * -lo, a.margin, lo))
    speeds = [v for v in TRAIN_SPEEDS if v <= a.margin * vmax]
    if not speeds:
        raise ValueError("[AXIS_Z] MAX_VELOCITY %g mm/s: the trains' speeds %s need at least %g"
                         % (vmax, TRAIN_SPEEDS, min(TRAIN_SPEEDS) / a.margin))
    shortest = max(speeds) ** 2 / TRAIN_ACCEL      # up to the fastest speed and down again at TRAIN_ACCEL
    if a.stroke < shortest:
        raise ValueError("--stroke %g mm: too short to reach the trains' %g mm/s (at %g mm/s^2 it takes "
                         "%g mm to get there and stop); give at least %g" % (a.stroke, max(speeds), TRAIN_ACCEL,
                                                                             shortest, shortest))
    lines = ["( hexaglide excite --trains: the drive trains' program for hexaglide identify, docs/identification.md )",
             "( vertical strokes of %g mm at %s mm/s, exact stop at the ends; load the --dither HAL snippet too )"
             % (a.stroke, "/".join("%g" % v for v in speeds)),
             "G21 G90 G17 G40 G49 G54 G94", "G61", "G1 X0 Y0 Z0 A0 B0 C0 F600"]
    t, i = 0.0, 0
    while t < a.seconds:
        v = speeds[i % len(speeds)]
        lines += ["G1 Z%.4f F%.6g" % (-a.stroke, 60 * v), "G1 Z0 F%.6g" % (60 * v)]
        t += 2 * (a.stroke / v + v / TRAIN_ACCEL)   # each way: the stroke at v, plus speeding up and stopping
        i += 1
    lines += ["M2", ""]
    return "\n".join(lines)


MAX_RUN_S = 3600.0               # --period x --periods: an hour of G-code at most
# the options' ranges (docs/identification.md): (lowest, highest, lowest allowed?, what it is)
RANGES = {
    "--period": (0.0, 120.0, False, "s: the Fourier series' period"),
    "--periods": (1, 100, True, "periods of the series run"),
    "--harmonics": (2, 20, True, "harmonics per axis: each adds 12 coefficients to the optimisation"),
    "--margin": (0.0, 1.0, False, "the fraction of every limit used"),
    "--max-volts": (0.0, 10.0, False, "V: the prior model's peak drive volts, inside the DAC's +-10 V"),
    "--segment": (0.01, 12.0, True, "s: one G1 segment; at most --period / 10"),
    "--starts": (1, 100, True, "optimisation starts"),
    "--maxiter": (1, 1000, True, "SLSQP iterations per start"),
    "--grid": (20, 2000, True, "time points per period"),
    "--seed": (0, 2 ** 32 - 1, True, "the random seed of the starts"),
    "--seconds": (0.0, 3600.0, False, "s: the trains' program's run time"),
    "--dither-volts": (0.0, DITHER_V_MAX, False, "V: the dither's amplitude"),
}


def check_options(a, names):
    """ValueError naming the first option of names outside its range (RANGES)."""
    why = hg_cli.out_of_range(a, RANGES, names)
    if why:
        raise ValueError(why)


# which options each of excite's three jobs uses (argparse dests): the Fourier program (the default),
# the trains' program (--trains) and the dither's HAL snippet (--dither, with --trains or alone)
FOURIER_OPTS = ("period", "periods", "harmonics", "max_volts", "segment", "starts", "maxiter", "grid", "seed", "set")
TRAINS_OPTS = ("stroke", "seconds")
DITHER_OPTS = ("dither_volts", "dither_band", "hal")


def unused_options(a, given):
    """ValueError naming the first option of given (the dests given on the command line) that the
    job a asks for does not use (nothing silently ignored): --output with --dither alone (it writes
    no G-code), the Fourier program's options with --trains or --dither alone, --trains' or the
    dither's without them."""
    opt = lambda d: "--" + d.replace("_", "-")
    if a.dither and not a.trains:
        if "output" in given:
            raise ValueError("--output %s with --dither and no --trains: --dither alone writes only the dither's "
                             "HAL snippet (%s), no G-code, so --output would not be written; add --trains for the "
                             "trains' program (the dither goes with it), or design the Fourier program in a run "
                             "without --dither" % (a.output or hg_output.STDOUT, a.dither))
        for d in FOURIER_OPTS + TRAINS_OPTS + ("margin",):
            if d in given:
                raise ValueError("%s: not used by --dither alone, which writes only the dither's HAL snippet (no "
                                 "program); drop it, or add --trains for the trains' program, or design the Fourier "
                                 "program in a run without --dither" % opt(d))
    for d in FOURIER_OPTS if a.trains else ():
        if d in given:
            raise ValueError("%s: an option of the Fourier program, which --trains does not design (it writes the "
                             "trains' program instead); drop it" % opt(d))
    for d, need in [(d, "--trains (the trains' program)") for d in TRAINS_OPTS if not a.trains] + \
            [(d, "--dither FILE (the dither's HAL snippet)") for d in DITHER_OPTS if not a.dither]:
        if d in given:
            raise ValueError("%s: an option of %s, not given; add it, or drop %s" % (opt(d), need, opt(d)))


MAX_VOLTS = 4.0                  # --max-volts' default: well inside the DAC's 10 V


def drive_bound(a, cfg):
    """Set a.max_volts (None: the default) within what every joint's drive reaches on the DAC
    (hg_config.drive_limit: [JOINT_N]MAX_OUTPUT through OUTPUT_SCALE and OUTPUT_OFFSET, as tune
    caps its --max-volts): a default above it is lowered to it and said; a given --max-volts above it
    is a ValueError naming the joint and keys."""
    reach = [hg_config.drive_limit(g) for g in cfg.joints]
    j = int(np.argmin(reach))
    g = cfg.joints[j]
    why = ("[JOINT_%d]MAX_OUTPUT %g of %s limits pid.%d.output; the DAC gets (output - OUTPUT_OFFSET %g) x "
           "OUTPUT_SCALE %g" % (j, g.get("MAX_OUTPUT", 0.0), a.ini, j, g.get("OUTPUT_OFFSET", 0.0),
                                g.get("OUTPUT_SCALE", 1.0)))
    if not reach[j] > 0:
        raise ValueError("joint %d's drive reaches no volts: %s; give a MAX_OUTPUT above |OUTPUT_OFFSET|" % (j, why))
    if a.max_volts is None:
        a.max_volts = min(MAX_VOLTS, reach[j])
        if reach[j] < MAX_VOLTS:
            log("drive bound %g V, below the default --max-volts %g: joint %d reaches %g V (%s)"
                % (a.max_volts, MAX_VOLTS, j, reach[j], why))
    elif a.max_volts > reach[j]:
        raise ValueError("--max-volts %g: joint %d's drive reaches only %g V (%s); give --max-volts %g or less"
                         % (a.max_volts, j, reach[j], why, reach[j]))


def main(argv=None):
    """hexaglide excite: design, check on 1 ms, write the G-code."""
    argv = sys.argv[1:] if argv is None else argv
    ap = hg_cli.Parser(prog="hexaglide excite", description=__doc__.split("\n\n")[0])
    ap.add_argument("--ini", default=os.path.join(ROOT, "configs", "hexaglide.ini"),
                    help="config with the [AXIS_*] and [JOINT_N] limits and the [HEXAGLIDE] geometry "
                    "(default configs/hexaglide.ini)")
    ap.add_argument("--output", help="write the G-code here (default, and -: stdout)")
    r = RANGES
    ap.add_argument("--period", type=hg_csv.number, default=8.0, help="period of the series, s, in (0, %g] (default 8)"
                    % r["--period"][1])
    ap.add_argument("--periods", type=hg_csv.integer, default=3, help="periods run, %d..%d, at most %g s in all (default 3)"
                    % (r["--periods"][0], r["--periods"][1], MAX_RUN_S))
    ap.add_argument("--harmonics", type=hg_csv.integer, default=5, help="harmonics per axis, %d..%d (default 5)"
                    % r["--harmonics"][:2])
    ap.add_argument("--margin", type=hg_csv.number, default=0.8,
                    help="fraction of every range, speed and acceleration limit used, in (0, 1] (default 0.8)")
    ap.add_argument("--max-volts", type=hg_csv.number, default=None,
                    help="peak drive volts the prior model may need, in (0, 10] and at most what every joint's pid "
                    "output reaches on the DAC ([JOINT_N]MAX_OUTPUT x OUTPUT_SCALE); default %g, or that reach "
                    "where it is lower" % MAX_VOLTS)
    ap.add_argument("--segment", type=hg_csv.number, default=0.2,
                    help="G1 segment duration, s, in [%g, period/10] (default 0.2; speeds are held below "
                    "0.5 a_max x segment)" % r["--segment"][0])
    ap.add_argument("--starts", type=hg_csv.integer, default=4, help="optimisation starts, %d..%d (default 4)"
                    % r["--starts"][:2])
    ap.add_argument("--maxiter", type=hg_csv.integer, default=200, help="SLSQP iterations per start, %d..%d (default 200)"
                    % r["--maxiter"][:2])
    ap.add_argument("--grid", type=hg_csv.integer, default=160, help="time points per period in the optimisation, %d..%d "
                    "(default 160)" % r["--grid"][:2])
    ap.add_argument("--seed", type=hg_csv.integer, default=1, help="random seed of the starts, 0..2^32-1 (default 1)")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="prior parameter (spec name, SI unit as sim --list-params), e.g. m_head=8; after "
                    "the config's [HEXAGLIDE]")
    ap.add_argument("--trains", action="store_true",
                    help="the drive trains' program instead: vertical strokes (with --dither's HAL snippet)")
    ap.add_argument("--stroke", type=hg_csv.number, default=TRAIN_STROKE_MM, help="--trains: stroke, mm (default %(default)s)")
    ap.add_argument("--seconds", type=hg_csv.number, default=30.0, help="--trains: run time, s, in (0, %g] (default "
                    "%%(default)s)" % r["--seconds"][1])
    ap.add_argument("--dither", metavar="FILE",
                    help="write the trains' dither as a HAL snippet (stock siggen, scale, sum2 between pid.N.output "
                    "and the DACs) to FILE")
    ap.add_argument("--dither-volts", type=hg_csv.number, default=DITHER_V,
                    help="the dither's amplitude, V, in (0, %g] (default %%(default)s)" % DITHER_V_MAX)
    ap.add_argument("--hal", metavar="FILE", default=DITHER_HAL,
                    help="with --dither: the HAL file the snippet is loaded right after (default "
                    "configs/hexaglide.hal): its servo thread's addf order places the dither before %s"
                    % DAC_WRITE)
    ap.add_argument("--dither-band", type=hg_csv.number, nargs=2, default=DITHER_BAND_HZ, metavar=("LO", "HI"),
                    help="the chirps' band, Hz, 0 < LO < HI < half the servo rate of --ini's [EMCMOT]SERVO_PERIOD "
                    "(500 at 1 ms; default %g %g: about the trains' axial mode)"
                    % DITHER_BAND_HZ)
    a = ap.parse_args(argv)
    a.argv = argv
    ap.set_defaults(**{d: None for d in vars(a) if d != "argv"})     # the options given on the command line
    given = {d for d, v in vars(ap.parse_args(argv)).items() if v is not None}   # (abbreviated or not)
    if a.output == hg_output.STDOUT:        # the program on standard output, as without --output
        a.output = None
    try:
        unused_options(a, given)
        hg_output.refuse_stdout([("--dither", a.dither)])
        for p in (a.output, a.dither):
            if p:
                hg_output.check_writable(p)            # a missing or unwritable directory now, not after the design
        hg_output.refuse_inputs([("--output", a.output), ("--dither", a.dither)], [("--ini", a.ini), ("--hal", a.hal)])
        hg_output.refuse_same([("--output", a.output), ("--dither", a.dither)])
    except (ValueError, hg_output.OutputError) as ex:
        log(ex)
        return 2
    if a.dither or a.trains:
        try:
            check_options(a, ("--seconds", "--margin", "--dither-volts") if a.trains else ("--dither-volts",))
            cfg = read_config(a)
            ns = cfg.servo_period_ns or 1e6      # siggen's chirps run in the servo thread: below its Nyquist
            lo, hi = a.dither_band
            if not (0 < lo < hi < 0.5e9 / ns):
                raise ValueError("--dither-band %g %g: need 0 < LO < HI < %g Hz (below half the %g Hz servo rate%s)"
                                 % (lo, hi, 0.5e9 / ns, 1e9 / ns, ", [EMCMOT]SERVO_PERIOD = %.0f ns of %s"
                                    % (ns, a.ini) if cfg.servo_period_ns else ""))
            text = trains_gcode(a, cfg.axes) if a.trains else None
            snippet = dither_hal(tuple(a.dither_band), a.dither_volts, hal=a.hal) if a.dither else None
        except ValueError as ex:
            log(ex)
            return 2
        if a.dither:
            hid.atomic_write(a.dither, lambda f: f.write(snippet.encode()))
            log("wrote the dither's HAL snippet to %s" % a.dither)
        if text is None:
            return 0
        if a.output:
            hid.atomic_write(a.output, lambda f: f.write(text.encode()))
        else:
            sys.stdout.write(text)
        return 0
    try:
        check_options(a, ("--period", "--periods", "--harmonics", "--margin", "--segment", "--starts", "--maxiter",
                          "--grid", "--seed") + (("--max-volts",) if a.max_volts is not None else ()))
        if a.period * a.periods > MAX_RUN_S:
            raise ValueError("--period %g x --periods %d = %g s: the program may run at most %g s"
                             % (a.period, a.periods, a.period * a.periods, MAX_RUN_S))
        if a.segment > a.period / 10:
            raise ValueError("--segment %g: must be at most --period / 10 = %g s (ten segments per period)"
                             % (a.segment, a.period / 10))
        hid.params_with(a.set)               # the names and numbers here; the values the C reader checks
        cfg = read_config(a)                 # defaults, [HEXAGLIDE], --set: as sim and soak take them
        drive_bound(a, cfg)
        prob = Problem(a, cfg.params, cfg)
        why = prob.centre_check()
        if why:
            raise ValueError(why)
    except ValueError as ex:
        log(ex)
        return 2
    rng = np.random.default_rng(a.seed)
    log("%d harmonics of %.4g Hz per axis, %d free coefficients, %d starts"
        % (a.harmonics, 1 / a.period, prob.fourier.nfree, a.starts))
    best = design(a, prob, rng)
    if best is None:
        log("no start met every limit: try more --starts, fewer --harmonics, a longer --period or a larger "
            "--margin")
        return 1
    theta = best[0]
    g, cond = fine_check(prob, theta, a.period)
    shrink = 1.0
    while (g > 0).any() and shrink > 0.5:        # between the grid points: shrink a little
        shrink *= 0.98
        theta = np.concatenate([theta[:6], theta[6:] * 0.98])
        g, cond = fine_check(prob, theta, a.period)
    if (g > 0).any():
        log("the trajectory leaves a limit between the optimisation's grid points; use a finer --grid")
        return 1
    text, total = gcode(prob, theta, a, cond)
    if a.output:
        hid.atomic_write(a.output, lambda f: f.write(text.encode()))
    else:
        sys.stdout.write(text)
    Y, z, zd, zdd, volts, x, xd, xdd = prob.evaluate(theta, np.arange(0, a.period, 0.001))
    log("condition number %.1f (base regressor, columns scaled to unit norm, 1 ms grid)" % cond)
    log("runs %.1f s (%d periods of %.4g s) plus the approach and return moves" % (total, a.periods, a.period))
    log("peaks: world %s; joints %.1f mm, %.1f mm/s, %.0f mm/s^2; drive %.2f V (prior model; bound %g V)"
        % (" ".join("%s %.1f..%.1f" % (ax, lo, hi) for ax, lo, hi in zip(AXES, x.min(0), x.max(0))),
           np.abs(z).max(), np.abs(zd).max(), np.abs(zdd).max(), np.abs(volts).max(), a.max_volts))
    return 0


if __name__ == "__main__":
    hg_cli.run(main, log, (hg_output.OutputError,))
