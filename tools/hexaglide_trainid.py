#!/usr/bin/python3
"""hexaglide_trainid.py - the drive trains' stiffness k_axial, damping
c_axial and backlash per drive from a recording, for `hexaglide identify`
(docs/identification.md: the drive trains). Not a program: imported by
hexaglide_identify.py.

What it uses: the encoder (the motor's side), the DAC volts (the motor's
force through the amplifier's ka and the motor's kt / lead) and the
carriage's own position (the load's side): on the virtual board its
joint-N.pos pin (a board record's out.z), on a real machine a linear scale
on the carriage. The encoder alone sees too little of the trains (the
rotors are seven times the carriages' share of the load: the axial mode is
the carriage ringing against a nearly still motor), so without the
carriage's position nothing is estimated here, and identify says so.

Two fits:
- slow (stiffness, backlash): below `cutoff_hz` the train's force is the
  motor's force less the rotor's inertia, f = F - m_r zr'' (m_r = j_rotor
  (2 pi / lead)^2, a datasheet value), and the deflection is
  d = zr - zc = f / k + sgn(f) b / 2 (+ an offset: the encoder's and the
  scale's zeros) while the flanks touch. Linear least squares per drive on
  the low-passed d, f and sgn(f), away from the moments the train's force
  changes sign (within `zero_window` cutoff periods of |f| < zero_band_n).
  The sigmas: a block bootstrap over `block_s` blocks, and the difference
  from a second fit at `second_cutoff` x the cutoff.
- fast (damping): the trains' small motion about the slow one
  (src/hg_trainid.h: six rotors, their trains and the carriages' mass
  matrix of the rigid estimate, stepped as the board steps, or as a
  continuous machine: RK4 on 16 substeps of the period) driven by the
  motors' force (hg_trainid_drive: the amplifiers under the recorded
  volts), fitted to the high-passed deflection (output error, scipy's
  least_squares over k and c per drive) on the stretches with the trains'
  dither (`hexaglide excite --dither`) whose train force keeps its sign
  and whose carriages keep their direction (the small motion is linear
  there). The sigmas: the fit's covariance times the residuals'
  correlation time, and the difference from a second fit above
  `check_ratio` x the high-pass.
"""
import copy
import ctypes as C
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hexaglide as hg  # noqa: E402
import hg_identify_base as ib  # noqa: E402

_d6 = C.c_double * 6
_dp = np.ctypeslib.ndpointer(dtype=np.float64, flags="C_CONTIGUOUS")


class TrainParams(C.Structure):
    """hg_trainid_params."""
    _fields_ = [("k", _d6), ("c", _d6), ("m_rotor", _d6), ("c_visc", _d6)]


NSTATE = 24
_response = hg._sig("hg_trainid_response", C.c_int, C.POINTER(TrainParams), C.c_int, C.c_int, C.c_double,
                    C.c_long, _dp, C.c_long, _dp, _dp, _dp, C.c_void_p)
_drive = hg._sig("hg_trainid_drive", C.c_int, C.c_void_p, C.c_int, C.c_double, C.c_long, _dp, _dp, _dp)
OUTPUT = os.environ.get("TRAINID_OUTPUT", "carriage")
CONTINUOUS = (2, 16)
K_NOMINAL = 3e7               # N/m: the fast force's scale in the row choice when the prior is a rigid train          # a real machine: RK4 on 16 substeps of the period


def response(k, c, m_rotor, c_visc, scheme, ns, dt, mass, every, u):
    """Rotor and carriage positions (np, 6 each) of hg_trainid_response from rest."""
    p = TrainParams(_d6(*k), _d6(*c), _d6(*m_rotor), _d6(*c_visc))
    np_ = len(u) // ns
    x = np.zeros(NSTATE)
    motor, car = np.zeros((np_, 6)), np.zeros((np_, 6))
    rc = _response(C.byref(p), int(scheme), int(ns), dt, np_, np.ascontiguousarray(mass, dtype=np.float64),
                   int(every), np.ascontiguousarray(u, dtype=np.float64), x, motor, car.ctypes.data_as(C.c_void_p))
    if rc:
        raise hg.HexaglideError("train response", rc)
    return motor, car


def drive_force(reg, volts, speed, ns, dt):
    """The motors' force (len(volts) * ns, 6) over each substep (hg_trainid_drive)."""
    n = len(volts)
    u = np.zeros((n * ns, 6))
    rc = _drive(reg.buf, int(ns), dt, n, np.ascontiguousarray(volts, dtype=np.float64),
                np.ascontiguousarray(speed, dtype=np.float64), u)
    if rc:
        raise hg.HexaglideError("train drive", rc)
    return u


class _Stability(C.Structure):
    """hg_stability."""
    _fields_ = [("substeps", C.c_uint), ("param", C.c_char_p), ("dt_max_s", C.c_double)]


_stability = hg._sig("hg_stability_check", C.c_int, C.c_void_p, C.c_int, C.c_double, C.c_uint, C.c_uint,
                     C.POINTER(_Stability))
SUBSTEPS_MAX = 64             # HG_SUBSTEPS_MAX


def board_scheme(run, params, k):
    """(integrator, substeps) the fast fit steps a run with: a board record's
    (its integrator, and the substeps its stability rule runs for these
    trains: src/hg_stability.h), else a continuous machine's (CONTINUOUS)."""
    if run.integrator is None or getattr(run, "substeps", None) is None:
        return CONTINUOUS
    p = ib.params_copy(params)
    p["k_axial"] = float(np.max(k))
    st = _Stability()
    rc = _stability(p.buf, int(run.integrator), run.dt, max(1, int(run.substeps)), SUBSTEPS_MAX, C.byref(st))
    return int(run.integrator), int(st.substeps) if rc == 0 and st.substeps else SUBSTEPS_MAX


class Settings:
    """How a recording becomes the trains' estimate (docs/identification.md: the drive trains)."""
    cutoff_hz = 10.0          # slow fit: zero-phase Butterworth low-pass (order 4, forwards and backwards)
    second_cutoff = 1.5       # ... a second fit at this x cutoff: the difference joins the sigmas
    zero_band_n = 30.0        # ... rows within zero_window cutoff periods of |f| below this are left out
    zero_window = 3.0
    window_check = 0.5        # ... a third fit with window_check x the zero_window: the difference joins the sigmas
    margin_s = 0.3            # ... and the first and last margin_s of a stretch (filter transients)
    block_s = 0.5             # ... block bootstrap: blocks of this length
    boot = 200                # ... replicates
    highpass_hz = 100.0       # fast fit: the deflection above this (Butterworth order 4, twice forwards and backwards)
    check_ratio = 1.5         # ... a second fit above this x highpass_hz: the difference joins the sigmas
    excited_v = 0.1           # ... excited: the high-passed volts' RMS over rms_window_s above this on every drive
    rms_window_s = 0.05
    dither_pad_s = 0.3        # the rigid fit leaves out the dither and this much either side
    preload = 4.0             # ... linear: |slow train force| above this x its fast part's RMS on every drive
    speed_margin = 3.0        # ... and |slow carriage speed| above this x its fast part's RMS
    settle_s = 0.1            # ... each stretch simulated from rest: residuals from settle_s on
    min_stretch_s = 0.25      # ... stretches shorter than settle_s + this are not used
    every = 10                # ... a new mass matrix every this many periods
    seed = 5


def rotor_mass(params):
    """The rotor's reflected mass j_rotor (2 pi / lead)^2 (kg)."""
    return params["j_rotor"] * (2 * np.pi / params["lead"]) ** 2


def _lp(dt, hz):
    from scipy.signal import butter
    return butter(4, hz * 2 * dt)


class Slow:
    """One stretch's slow signals: rows n (run indexes), zr, zc, d, f (n, 6), filtered at hz."""


def slow_signals(run, params, pieces, hz, hp_hz=Settings.highpass_hz):
    """The stretches' low-passed encoder position zr, deflection d = zr - zc and
    train force f = F - m_r zr'' (F of the periods either side of a reading:
    its acceleration's), per usable piece (list of Slow)."""
    from scipy.signal import filtfilt, butter
    dt = run.dt
    b, a = _lp(dt, hz)
    mr = rotor_mass(params)
    F = ib.force_per_volt(params) * ib.dac_output(run.volts)
    out = []
    for i0, i1 in pieces:
        g = Slow()
        n = np.arange(i0, i1)                       # F[n], F[n + 1]: into and out of reading n
        zr = filtfilt(b, a, run.counts[i0:i1] / run.count_scale, axis=0)
        g.n = n
        g.zr = zr
        g.d = filtfilt(b, a, run.counts[i0:i1] / run.count_scale - run.carriage[i0:i1], axis=0)
        acc = np.gradient(np.gradient(zr, dt, axis=0), dt, axis=0)
        g.f = filtfilt(b, a, 0.5 * (F[n] + F[n + 1]), axis=0) - mr * acc
        # the fast part of the deflection (the dither's): its RMS (m)
        bh, ah = butter(4, min(0.45, hp_hz * 2 * dt), "high")
        draw = run.counts[i0:i1] / run.count_scale - run.carriage[i0:i1]
        g.fast = _rms(filtfilt(bh, ah, draw, axis=0), max(1, int(round(0.05 / dt))))
        g.b, g.a = b, a
        out.append(g)
    return out


def _slow_rows(g, run, s, hz, k_nom):
    """Rows of a stretch the slow fit uses, per drive (len, 6): away from the
    train force's sign changes, by zero_band_n and by preload x the fast
    (dither's) force k_nom x its deflection's RMS (it chatters through the
    free play there)."""
    w = int(round(s.zero_window / (hz * run.dt)))
    edge = int(round(s.margin_s / run.dt))
    use = np.zeros(g.f.shape, bool)
    band = s.zero_band_n + s.preload * k_nom * g.fast
    for k in range(6):
        use[:, k] = ~ib.dilate(np.abs(g.f[:, k]) < band[:, k], w)
    use[:edge] = use[-edge:] = False
    return use


def slow_fit(runs, params, pieces, s, hz, rng=None):
    """k (N/m), backlash (m), offset (m) per drive from the slow signals at cutoff hz,
    and (with rng) block-bootstrap sigmas. Returns dict of arrays (6,) and rows used."""
    from scipy.signal import filtfilt
    A_all = [[] for _ in range(6)]
    y_all = [[] for _ in range(6)]
    blk = [[] for _ in range(6)]
    nb = npc = 0
    for run, pcs in zip(runs, pieces):
        for g in slow_signals(run, params, pcs, hz):
            use = _slow_rows(g, run, s, hz, params["k_axial"] if params["k_axial"] > 0 else K_NOMINAL)
            sg = filtfilt(g.b, g.a, np.sign(g.f), axis=0)
            bl = nb + (np.arange(len(g.n)) * run.dt // s.block_s).astype(int)
            nb = bl[-1] + 1
            npc += 1
            for k in range(6):
                u = use[:, k]
                A_all[k].append(np.c_[g.f[u, k], sg[u, k], np.ones(u.sum()), np.full(u.sum(), npc - 1)])
                y_all[k].append(g.d[u, k])
                blk[k].append(bl[u])
    out = dict(k=np.full(6, np.nan), backlash=np.full(6, np.nan), offset=np.full(6, np.nan),
               sk=np.full(6, np.nan), sb=np.full(6, np.nan), rows=np.zeros(6, int), rms=np.full(6, np.nan),
               span=np.zeros(6))
    for k in range(6):
        if not A_all[k]:
            continue
        A, y, bl = np.vstack(A_all[k]), np.concatenate(y_all[k]), np.concatenate(blk[k])
        # an offset per stretch (the encoder's and the scale's zeros: a reset, a homing between)
        pc = A[:, 3].astype(int)
        live = np.unique(pc)
        A = np.c_[A[:, :2], (pc[:, None] == live[None, :]).astype(float)]
        has_rev = (A[:, 0] > 0).any() and (A[:, 0] < 0).any()
        cols = ([0, 1] if has_rev else [0]) + list(range(2, A.shape[1]))
        if len(y) < 50:
            continue
        x, *_ = np.linalg.lstsq(A[:, cols], y, rcond=None)
        out["rows"][k] = len(y)
        out["span"][k] = np.ptp(A[:, 0])
        out["rms"][k] = np.sqrt(np.mean((y - A[:, cols] @ x) ** 2))
        out["k"][k] = 1.0 / x[0]
        out["backlash"][k] = 2 * x[1] if has_rev else np.nan
        out["offset"][k] = x[cols.index(2)]        # the first stretch's
        if rng is None:
            continue
        ub = np.unique(bl)
        reps = []
        for _ in range(s.boot):
            pick = rng.choice(ub, len(ub))
            idx = np.concatenate([np.flatnonzero(bl == q) for q in pick])
            xb, *_ = np.linalg.lstsq(A[idx][:, cols], y[idx], rcond=None)
            reps.append([1.0 / xb[0], 2 * xb[1] if has_rev else np.nan])
        reps = np.array(reps)
        # the replicates' spread, half the 16..84 percentile range (a replicate drawn with
        # (nearly) no reversal has no backlash to speak of: robust to those)
        out["sk"][k] = _spread(reps[:, 0])
        out["sb"][k] = _spread(reps[:, 1]) if has_rev else np.nan
    return out


def _spread(x):
    """Half the 16..84 percentile range of x (a standard deviation when normal)."""
    lo, hi = np.percentile(x, [15.865, 84.135])
    return 0.5 * (hi - lo)


def deflection(run, params, k_axial, backlash, s):
    """The deflection zr - zc (n, 6) of a run for its carriages' motion: the
    measured one (encoder - carriage) when the run has the carriage's
    position, else f / k + sgn(f) b / 2 from the slow train force (the
    rigid fit on a flexible machine without a scale: its k_axial and
    backlash known). Zero where k_axial is 0 (rigid)."""
    if getattr(run, "carriage", None) is not None:
        return run.counts / run.count_scale - run.carriage
    out = np.zeros(run.counts.shape)
    k = np.broadcast_to(np.asarray(k_axial, float), (6,))
    if not (k > 0).all():
        return out
    from scipy.signal import filtfilt
    dt = run.dt
    b, a = _lp(dt, s.cutoff_hz)
    F = ib.force_per_volt(params) * ib.dac_output(run.volts)
    Fn = np.vstack([F[1:], F[-1:]])
    for i0, i1 in ib.usable_stretches(run, ib.Settings()):
        zr = filtfilt(b, a, run.counts[i0:i1 + 1] / run.count_scale, axis=0)
        acc = np.gradient(np.gradient(zr, dt, axis=0), dt, axis=0)
        f = filtfilt(b, a, 0.5 * (F[i0:i1 + 1] + Fn[i0:i1 + 1]), axis=0) - rotor_mass(params) * acc
        out[i0:i1 + 1] = f / k + np.sign(f) * 0.5 * np.asarray(backlash, float)
    return out


def dithered(run, s):
    """(n,) rows of a run within dither_pad_s of the trains' dither (the
    high-passed volts' RMS above excited_v on any drive): left out of the
    rigid fit, whose 10 Hz machine has no trains."""
    from scipy.signal import filtfilt, butter
    if len(run.volts) < 30:
        return np.zeros(len(run.volts), bool)
    bh, ah = butter(4, s.highpass_hz * 2 * run.dt, "high")
    w = max(1, int(round(s.rms_window_s / run.dt)))
    on = (_rms(filtfilt(bh, ah, ib.dac_output(run.volts), axis=0), w) > s.excited_v).any(1)
    return ib.dilate(on, int(round(s.dither_pad_s / run.dt)))


# ---------------------------------------------------------------- the fast fit
class Stretch:
    """One excited, linear stretch: volts, slow speeds, mass matrices, measured high-passed deflection."""


def mass_matrices(reg, pi, z):
    """The rigid model's 6x6 mass matrices (len(z), 36) at carriage positions z (m): Y(z, 0, e_j) pi - Y(z, 0, 0) pi."""
    n = len(z)
    zero = np.zeros((n, 6))
    Y0, _ = reg.joints(z, zero, zero)
    M = np.zeros((n, 6, 6))
    for j in range(6):
        e = np.zeros((n, 6))
        e[:, j] = 1.0
        Yj, _ = reg.joints(z, zero, e)
        M[:, :, j] = (Yj - Y0) @ pi
    return M.reshape(n, 36)


def _rms(x, w):
    ker = np.ones(w) / w
    return np.sqrt(np.apply_along_axis(lambda c: np.convolve(c * c, ker, "same"), 0, x))


def stretches(runs, pieces, reg, params, pi, k_slow, s):
    """The stretches of the runs where the dither excites every train and the
    small motion is linear (list of Stretch)."""
    from scipy.signal import filtfilt, butter
    out = []
    for run, pcs in zip(runs, pieces):
        dt = run.dt
        bh, ah = butter(4, s.highpass_hz * 2 * dt, "high")
        w = max(1, int(round(s.rms_window_s / dt)))
        V = ib.dac_output(run.volts)
        for g in slow_signals(run, params, pcs, s.cutoff_hz):
            i0, i1 = g.n[0], g.n[-1] + 1
            d = run.counts[i0:i1] / run.count_scale - run.carriage[i0:i1]
            zc = run.carriage[i0:i1]
            vh = _rms(filtfilt(bh, ah, V[i0:i1], axis=0), w)
            fh = _rms(k_slow * filtfilt(bh, ah, d, axis=0), w)
            vfast = _rms(np.gradient(filtfilt(bh, ah, zc, axis=0), dt, axis=0), w)
            vslow = np.gradient(filtfilt(g.b, g.a, zc, axis=0), dt, axis=0)
            ok = ((vh > s.excited_v) & (np.abs(g.f) > s.preload * fh) &
                  (np.abs(vslow) > s.speed_margin * vfast)).all(1)
            ok &= ~ib.clamped_periods(run, params)[i0:i1].any(1)
            idx = np.flatnonzero(ok)
            for seg in np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1) if len(idx) else []:
                if len(seg) * dt < s.settle_s + s.min_stretch_s:
                    continue
                a, b = seg[0] + i0, seg[-1] + 1 + i0
                t = Stretch()
                t.dt = dt
                t.scheme = board_scheme(run, params, k_slow)
                t.volts = V[a:b]
                t.speed = np.gradient(g.zr[a - i0:b - i0], dt, axis=0)
                t.mass = mass_matrices(reg, pi, g.zr[a - i0:b - i0:s.every] - g.d[a - i0:b - i0:s.every])
                t.d = d[a - i0:b - i0]
                t.zc = zc[a - i0:b - i0]
                t.settle = int(round(s.settle_s / dt))
                t.every = s.every
                out.append(t)
    return out


def _prepare(segs, reg, hz):
    """Per stretch: the high-passed motor force per substep and the twice high-passed deflection at hz."""
    from scipy.signal import filtfilt, butter
    for t in segs:
        scheme, ns = t.scheme
        bu, au = butter(4, hz * 2 * t.dt / ns, "high")
        t.hp = butter(4, hz * 2 * t.dt, "high")
        t.u = filtfilt(bu, au, drive_force(reg, t.volts, t.speed, ns, t.dt), axis=0)
        t.y = filtfilt(*t.hp, filtfilt(*t.hp, t.zc if OUTPUT == "carriage" else t.d, axis=0), axis=0)


def _sim(t, k, c, mr, cv, dm):
    """The high-passed carriage (or deflection) response of stretch t, the carriages' masses + dm (kg)."""
    from scipy.signal import filtfilt
    scheme, ns = t.scheme
    mass = t.mass + (np.diag(dm).ravel() if np.any(dm) else 0.0)
    m, l = response(k, c, mr, cv, scheme, ns, t.dt, mass, t.every, t.u)
    return filtfilt(*t.hp, l if OUTPUT == "carriage" else m - l, axis=0)


def fast_fit(segs, reg, params, pi, k, s, sk=None):
    """c_axial per drive from the stretches, the stiffness k held (the slow
    fit's, sigmas sk: carried into c's through the fit's sensitivity to k),
    with a correction dm of each carriage's mass (the rigid estimate knows
    the rotor plus carriage, m_drive, well, the carriage behind the spring
    less well; the mode's frequency tells it): dict."""
    from scipy.optimize import least_squares
    mr = np.full(6, rotor_mass(params))
    cv = np.array([pi[ib.fric_col("c_visc", j)] for j in range(6)])
    c0 = max(float(params["c_axial"]), 100.0)
    k = np.asarray(k, float)
    load = min(np.min(t.mass[:, ::7] - mr) for t in segs)     # the lightest carriage behind its spring (kg)

    def resid(x, kk=k):
        return np.concatenate([((t.y - _sim(t, kk, c0 * x[:6], mr, cv, x[6:]))[t.settle:]).ravel()
                               for t in segs]) * 1e6

    def solve(hz, x0):
        _prepare(segs, reg, hz)
        return least_squares(resid, x0, x_scale=np.r_[[0.1] * 6, [0.1] * 6],
                             bounds=(np.r_[[0.0] * 6, [-0.8 * load] * 6], np.r_[[100.0] * 6, [5 * load] * 6]))
    res = solve(s.highpass_hz, np.r_[[1.0] * 6, [0.0] * 6])
    r = res.fun.reshape(-1, 6)
    tau = np.mean([ib.autocorr_time(r[:, j]) for j in range(6)])
    dof = max(1, r.size - 12)
    cov = np.linalg.pinv(res.jac.T @ res.jac) * (res.fun @ res.fun) / dof * tau
    scale = np.r_[[c0] * 6, [1.0] * 6]
    val = res.x * scale
    sig = np.sqrt(np.diag(cov)) * scale
    # the stiffness held: its uncertainty moves the fit by -pinv(J_x) J_k dk (J_k by finite differences)
    dk_sig = np.zeros(6)
    if sk is not None:
        Jk = np.stack([(resid(res.x, k * (1 + 1e-3 * (np.arange(6) == j))) - res.fun) / (1e-3 * k[j])
                       for j in range(6)], 1)
        S = -np.linalg.pinv(res.jac) @ Jk                       # dx / dk (x scaled)
        dk_sig = np.sqrt(np.diag(S @ np.diag(np.asarray(sk, float) ** 2) @ S.T)) * scale
    rms = np.sqrt((r ** 2).mean(0)) * 1e-6
    yr = np.sqrt((np.concatenate([t.y[t.settle:] for t in segs]) ** 2).mean(0))
    res2 = solve(s.highpass_hz * s.check_ratio, res.x)
    diff = np.abs(res2.x - res.x) * scale
    return dict(schemes=[t.scheme for t in segs], c=val[:6], dm=val[6:], sc_stat=sig[:6], sdm=sig[6:],
                dc=diff[:6], sc_k=dk_sig[:6], sc=np.sqrt(sig[:6] ** 2 + diff[:6] ** 2 + dk_sig[:6] ** 2),
                rms=rms, y_rms=yr, tau=tau, stretches=len(segs),
                seconds=sum((len(t.d) - t.settle) * t.dt for t in segs))


# ---------------------------------------------------------------- for identify
class Trains:
    """The trains' estimate of identify: slow (dict of slow_fit), fast (dict of fast_fit or None), why (str)."""
    slow = fast = None
    why = fast_why = ""


def estimate_slow(runs, params, pieces, s, log=None):
    """The slow fit (Trains) when every run has the carriages' positions, else Trains.why."""
    t = Trains()
    if not all(getattr(r, "carriage", None) is not None for r in runs):
        t.why = ("no carriage position in %s: the drive trains need the load's side (a linear scale; the "
                 "virtual board's motenc-hexaglide.0.joint-N.pos) beside the encoder (docs/identification.md: "
                 "the drive trains); the rigid fit takes the encoder for the carriage%s"
                 % (", ".join(r.path for r in runs if getattr(r, "carriage", None) is None),
                    " less the deflection of the known k_axial" if params["k_axial"] > 0 else ""))
        return t
    t.slow = slow_fit(runs, params, pieces, s, s.cutoff_hz, np.random.default_rng(s.seed))
    t.slow2 = slow_fit(runs, params, pieces, s, s.cutoff_hz * s.second_cutoff)
    wide = copy.copy(s)
    wide.zero_window = s.zero_window * s.window_check
    t.slow3 = slow_fit(runs, params, pieces, wide, s.cutoff_hz)
    for key, sk in (("k", "sk"), ("backlash", "sb")):
        t.slow["d" + key] = np.abs(t.slow2[key] - t.slow[key])
        t.slow["w" + key] = np.abs(t.slow3[key] - t.slow[key])
        t.slow[sk + "_stat"] = t.slow[sk].copy()
        t.slow[sk] = np.sqrt(t.slow[sk] ** 2 + t.slow["d" + key] ** 2 + t.slow["w" + key] ** 2)
    if log:
        log("drive trains: stiffness and backlash from %s rows per drive" % "/".join("%d" % x for x in t.slow["rows"]))
    return t


def _stiff(sl, k):
    """Drive k's slow fit found a stiffness (the deflection follows the train force), else a rigid train."""
    return bool(np.isfinite(sl["k"][k]) and sl["k"][k] > 0 and sl["sk"][k] < 0.3 * sl["k"][k])


def flexible(t):
    """Every drive's train found flexible by the slow fit."""
    return t.slow is not None and all(_stiff(t.slow, k) for k in range(6))


def estimate_fast(t, runs, pieces, reg, params, pi, s, log=None):
    """The fast fit (t.fast) on the dither's stretches, else t.fast_why."""
    if t.slow is None:
        return
    if not flexible(t):
        t.fast_why = "the slow fit found no flexible train on every drive"
        return
    k0 = t.slow["k"]
    segs = stretches(runs, pieces, reg, params, pi, k0, s)
    if not segs:
        t.fast_why = ("no stretch with the trains' dither (high-passed volts above %g V RMS on every drive) "
                      "whose train forces keep their sign and carriages their direction: record `hexaglide "
                      "excite --trains` with its --dither HAL snippet (docs/identification.md)" % s.excited_v)
        return
    if log:
        log("drive trains: damping from %d dithered stretches" % len(segs))
    try:
        t.fast = fast_fit(segs, reg, params, pi, k0, s, t.slow["sk"])
    except hg.HexaglideError as ex:
        t.fast_why = ("the rigid estimate's carriage masses leave no load behind the rotors (%s): identify "
                      "the rigid parameters too (a record of hexaglide excite's program beside the trains')" % ex)


def _scheme_text(sch):
    if tuple(sch) == CONTINUOUS:
        return "RK4 on %d substeps: a continuous machine" % CONTINUOUS[1]
    return "the board's %s on %d substeps" % (("improved Euler", "Heun", "RK4")[sch[0]], sch[1])


def report_lines(t, params, s):
    """identify's lines of the trains: NAME[k] = VALUE ± SIGMA UNIT and '#' notes."""
    out = []
    if t.slow is None:
        return ["# drive trains not estimated: " + t.why]
    sl = t.slow
    out.append("# drive trains: the encoder (motor side) against the carriage's position (load side: a linear "
               "scale, the board's joint-N.pos); train force = DAC force - m_r zr'' (m_r = j_rotor (2 pi/lead)^2 "
               "= %.4g kg, known beforehand)" % rotor_mass(params))
    out.append("# k_axial, backlash: deflection = f/k + sgn(f) backlash/2 + offset below %.3g Hz, %s rows per "
               "drive (|f| spans %s N); sigma: block bootstrap (%g s blocks, the 16..84%% spread), the differences at %.3g Hz and with "
               "%g x the window left out about the force's sign changes"
               % (s.cutoff_hz, "/".join("%d" % x for x in sl["rows"]), "/".join("%.0f" % x for x in sl["span"]),
                  s.block_s, s.cutoff_hz * s.second_cutoff, s.window_check))
    for k in range(6):
        if _stiff(sl, k):
            out.append("k_axial[%d] = %.6g ± %.2g N/m" % (k, sl["k"][k], sl["sk"][k]))
        else:
            out.append("# k_axial[%d], backlash[%d] not estimated: the deflection does not follow the train force "
                       "(%.3g ± %.2g N/m); a rigid train (k_axial 0) or too little force" % (k, k, sl["k"][k], sl["sk"][k]))
    for k in range(6):
        if not _stiff(sl, k):
            continue
        if np.isfinite(sl["backlash"][k]):
            out.append("backlash[%d] = %.4g ± %.2g m" % (k, sl["backlash"][k], sl["sb"][k]))
        else:
            out.append("# backlash[%d] not estimated: the train force never changes sign" % k)
    f = t.fast
    if f is None:
        out.append("# c_axial not estimated: " + t.fast_why)
        return out
    out.append("# c_axial: output error of the trains' small motion (%s, the rigid estimate's mass matrix, k_axial "
               "held) against "
               "the carriage's position above %.3g Hz on %d dithered stretches (%.1f s); residual RMS %s nm of "
               "%s nm; sigma: covariance x correlation time %.1f, the difference above %.3g Hz, and k_axial's sigma "
               "through the fit's sensitivity to it"
               % (", ".join(sorted(set(_scheme_text(x) for x in f["schemes"]))), s.highpass_hz, f["stretches"],
                  f["seconds"],
                  "/".join("%.0f" % (x * 1e9) for x in f["rms"]), "/".join("%.0f" % (x * 1e9) for x in f["y_rms"]),
                  f["tau"], s.highpass_hz * s.check_ratio))
    for k in range(6):
        out.append("c_axial[%d] = %.5g ± %.2g N s/m" % (k, f["c"][k], f["sc"][k]))
    out.append("# the carriages' masses behind the springs, as the mode's frequency tells them: the rigid "
               "estimate's %s kg" % " ".join("%+.3g±%.1g" % (f["dm"][k], f["sdm"][k]) for k in range(6)))
    return out


def spec(t):
    """{spec name: [six values]} of the trains for identify's setp lines."""
    out = {}
    if flexible(t):
        out["k_axial"] = list(t.slow["k"])
        if np.isfinite(t.slow["backlash"]).all():
            out["backlash"] = list(np.maximum(t.slow["backlash"], 0.0))
    if t.fast is not None:
        out["c_axial"] = list(t.fast["c"])
    return out
