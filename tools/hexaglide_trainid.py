#!/usr/bin/python3
"""hexaglide_trainid.py - the drive trains' stiffness, damping and rotor
masses from a record's fast motion, for `hexaglide identify`
(docs/identification.md: the drive train).

The encoder counts the motor. Around the trains' first axial modes (a few
hundred Hz) the motor's response to its force tells the spring between
it and the carriage: above the modes the motor moves as its own mass
m_r, below them with the carriage side, between them the spring. The
fast part of the record (high-passed) is predicted by hg_trainid_response
(src/hg_trainid.h: six rotors, trains and the carriages' mass matrix of
the rigid estimate, stepped as the machine steps) from the motors' force
(hg_trainid_drive: the amplifiers and windings under the recorded DAC
volts), and scipy's least_squares fits k_axial, c_axial and m_r per drive
to the high-passed counts (output error: unbiased under the quantization
of the counts, which is white, in closed loop too: the encoder noise of a
period reaches the force only in the next). Not a program: imported by
hexaglide_identify.py.
"""
import ctypes as C
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hexaglide as hg  # noqa: E402

_d6 = C.c_double * 6
_dp = np.ctypeslib.ndpointer(dtype=np.float64, flags="C_CONTIGUOUS")


class TrainParams(C.Structure):
    """hg_trainid_params."""
    _fields_ = [("k", _d6), ("c", _d6), ("m_rotor", _d6), ("c_visc", _d6)]


NSTATE = 24
_response = hg._sig("hg_trainid_response", C.c_int, C.POINTER(TrainParams), C.c_int, C.c_int, C.c_double,
                    C.c_long, _dp, C.c_long, _dp, _dp, _dp, C.c_void_p)
_drive = hg._sig("hg_trainid_drive", C.c_int, C.c_void_p, C.c_int, C.c_double, C.c_long, _dp, _dp, _dp)


def response(k, c, m_rotor, c_visc, scheme, ns, dt, mass, every, u, load=False):
    """Rotor (and carriage) positions (np, 6) of hg_trainid_response from rest."""
    p = TrainParams(_d6(*k), _d6(*c), _d6(*m_rotor), _d6(*c_visc))
    np_ = len(u) // ns
    x = np.zeros(NSTATE)
    motor = np.zeros((np_, 6))
    car = np.zeros((np_, 6)) if load else None
    rc = _response(C.byref(p), int(scheme), int(ns), dt, np_, np.ascontiguousarray(mass, dtype=np.float64),
                   int(every), np.ascontiguousarray(u, dtype=np.float64), x, motor,
                   car.ctypes.data_as(C.c_void_p) if load else None)
    if rc:
        raise hg.HexaglideError("train response", rc)
    return (motor, car) if load else motor


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
SCHEMES = {"improved-euler": 0, "heun": 1, "rk4": 2}
CONTINUOUS = (2, 16)          # a real machine: RK4 on 16 substeps of the period (converged at these modes)


def board_substeps(params, scheme, dt, asked=1):
    """The substeps the virtual board runs for params (its stability rule, src/hg_stability.h)."""
    st = _Stability()
    rc = _stability(params.buf, int(scheme), dt, int(asked), SUBSTEPS_MAX, C.byref(st))
    return int(st.substeps) if rc == 0 and st.substeps else SUBSTEPS_MAX


class Settings:
    """How the fast part of a record becomes the trains' estimate (docs/identification.md)."""
    highpass_hz = 80.0        # the fit sees the record above this (Butterworth order 4, forwards and backwards)
    check_ratio = 1.5         # a second fit above check_ratio x highpass: the difference joins the sigmas
    rms_window_s = 0.05       # the excitation is where the high-passed drive force's RMS over this ...
    excited_n = 30.0          # ... is above this many N (and above excited_share of its 99th percentile)
    excited_share = 0.3
    min_segment_s = 0.5       # excited stretches shorter than this are not used
    pad_s = 0.2               # filter transients: the response starts this much before a stretch
    settle_s = 0.05           # ... and the residuals this much after it starts
    speed_margin = 3.0        # rows kept: carriage speed above this x the fast motion's RMS speed ...
    force_margin = 3.0        # ... and the train's slow force above this x its fast force's RMS
    k_grid = np.geomspace(0.1, 10.0, 41)   # the first search: the prior's stiffness times these


def _hp(s, fs, hz):
    """Butterworth high-pass (b, a) of order 4 at hz for sampling rate fs."""
    from scipy.signal import butter
    return butter(4, hz * 2 / fs, "high")


def excited_rows(F, dt, s):
    """(n,) rows where every drive's high-passed force has the RMS of an excitation."""
    from scipy.signal import filtfilt
    b, a = _hp(s, 1 / dt, s.highpass_hz)
    h = filtfilt(b, a, F, axis=0)
    w = max(1, int(round(s.rms_window_s / dt)))
    r = np.sqrt(np.apply_along_axis(lambda x: np.convolve(x * x, np.ones(w) / w, "same"), 0, h))
    lim = np.maximum(s.excited_n, s.excited_share * np.percentile(r, 99, axis=0))
    return (r > lim).all(1)


class Segment:
    """One excited stretch of a run, as the fit needs it."""


def segments(run, reg, params, base, theta, s, mass_of):
    """The excited stretches of run (Segment: force per substep, mass matrices,
    measured high-passed counts, slow carriage speed and train force)."""
    from scipy.signal import filtfilt, butter
    import hexaglide_identify as hid
    dt = run.dt
    fpv = hid.force_per_volt(params)
    V = hid.dac_output(run.volts)
    out = []
    pad, settle = int(round(s.pad_s / dt)), int(round(s.settle_s / dt))
    for i0, i1 in hid._pieces(run, hid.Settings()):
        F = fpv * V[i0:i1 + 1]
        ex = excited_rows(F, dt, s)
        idx = np.flatnonzero(ex)
        if not len(idx):
            continue
        for seg in np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1):
            if len(seg) * dt < s.min_segment_s:
                continue
            a, b = max(0, seg[0] - pad), min(i1 - i0 + 1, seg[-1] + 1 + pad)
            g = Segment()
            g.run, g.i0 = run, i0 + a
            pos = run.counts[i0 + a:i0 + b] / run.count_scale
            bl, al = butter(4, 10.0 * 2 * dt)
            g.z = filtfilt(bl, al, pos, axis=0)
            g.v = np.gradient(g.z, dt, axis=0)
            g.acc = np.gradient(g.v, dt, axis=0)
            bs, as_ = butter(4, min(0.4, 200.0 * 2 * dt))
            g.speed = np.gradient(filtfilt(bs, as_, pos, axis=0), dt, axis=0)
            g.volts = V[i0 + a:i0 + b]
            g.F_lf = filtfilt(bl, al, F[a:b], axis=0)
            g.pos = pos
            g.every = 10
            g.mass = mass_of(g.z[::g.every], g.v[::g.every]).reshape(-1, 36)
            g.fit = np.zeros(b - a, bool)
            g.fit[seg[0] - a + settle:seg[-1] - a + 1] = True
            g.clamped = hid._clamped(run, params)[i0 + a:i0 + b].any(1)
            out.append(g)
    return out


class Fit:
    """The trains' estimate: k, c, m_rotor (6 each), their sigmas, what was used."""


def _prepare(segs, reg, scheme, ns, s, hz):
    """Per segment: the high-passed force per substep and the high-passed counts at cutoff hz."""
    from scipy.signal import filtfilt
    for g in segs:
        dt = g.run.dt
        bu, au = _hp(s, ns / dt, hz)
        by, ay = _hp(s, 1 / dt, hz)
        g.u = filtfilt(bu, au, drive_force(reg, g.volts, g.speed, ns, dt), axis=0)
        g.y = filtfilt(by, ay, filtfilt(by, ay, g.pos, axis=0), axis=0)
        g.hp = (by, ay)


def _simulate(g, k, c, mr, cv, scheme, ns, load=False):
    """High-passed rotor (and carriage) response of segment g."""
    from scipy.signal import filtfilt
    r = response(k, c, mr, cv, scheme, ns, g.run.dt, g.mass, g.every, g.u, load)
    if load:
        return filtfilt(*g.hp, r[0], axis=0), r[1]
    return filtfilt(*g.hp, r, axis=0)


def _masks(segs, k, c, mr, cv, scheme, ns, s):
    """Rows of each segment the fit uses: excited, not clamped, the carriage fast
    enough that the fast motion keeps its speed's sign, the train's slow force
    far enough from 0 that the fast one keeps it (no free play crossed)."""
    for g in segs:
        _, car = _simulate(g, k, c, mr, cv, scheme, ns, load=True)
        dt = g.run.dt
        vh = np.gradient(car, dt, axis=0)
        ym = response(k, c, mr, cv, scheme, ns, dt, g.mass, g.every, g.u)
        fh = np.asarray(k) * (ym - car)
        sel = g.fit
        vr = np.sqrt((vh[sel] ** 2).mean(0)) if sel.any() else np.zeros(6)
        fr = np.sqrt((fh[sel] ** 2).mean(0)) if sel.any() else np.zeros(6)
        f_lf = g.F_lf - np.asarray(mr) * g.acc
        g.use = (sel[:, None] & ~g.clamped[:, None] & (np.abs(g.v) > s.speed_margin * vr) &
                 (np.abs(f_lf) > s.force_margin * fr))


def fit(runs, reg, params, base, theta, cvisc, mass_of, s=None, log=None, scheme_ns=None):
    """k_axial, c_axial, m_rotor per drive (Fit) from the excited stretches of runs,
    or None when no run has any (with fit.why)."""
    from scipy.optimize import least_squares
    s = s or Settings()
    segs = [g for r in runs for g in segments(r, reg, params, base, theta, s, mass_of)]
    f = Fit()
    f.segments = len(segs)
    f.seconds = sum(g.fit.sum() * g.run.dt for g in segs)
    if not segs:
        f.why = ("no excitation near the trains' modes (the drive force's content above %g Hz is the "
                 "servo loop's alone): record a program with the trains' dither (hexaglide excite)"
                 % s.highpass_hz)
        return f
    k0 = params["k_axial"] if params["k_axial"] > 0 else hg.Params()["k_axial"]
    c0 = max(params["c_axial"], 100.0)
    m0 = params["j_rotor"] * (2 * np.pi / params["lead"]) ** 2
    scheme, ns = scheme_ns(k0 * np.ones(6), m0 * np.ones(6)) if scheme_ns else CONTINUOUS
    cv = np.asarray(cvisc, float)

    def resid(x, w, hz_segs):
        k, c, mr = k0 * x[:6], c0 * x[6:12], m0 * x[12:]
        out = []
        for g in hz_segs:
            r = (g.y - _simulate(g, k, c, mr, cv, scheme, ns)) * w
            out.append(r[g.use])
        return np.concatenate(out)

    def solve(x0, hz):
        _prepare(segs, reg, scheme, ns, s, hz)
        w = np.ones(6)
        for g in segs:
            g.use = g.fit[:, None] & ~g.clamped[:, None] & np.ones((1, 6), bool)
        x = x0.copy()
        for it in range(3):
            if it:
                _masks(segs, k0 * x[:6], c0 * x[6:12], m0 * x[12:], cv, scheme, ns, s)
            res = least_squares(resid, x, args=(w, segs), bounds=(np.r_[[0.01] * 6, [0.0] * 6, [0.2] * 6],
                                                                  np.r_[[100.0] * 6, [50.0] * 6, [5.0] * 6]),
                                x_scale=np.r_[[0.01] * 6, [0.3] * 6, [0.005] * 6], method="trf")
            x = res.x
            r = np.concatenate([((g.y - _simulate(g, k0 * x[:6], c0 * x[6:12], m0 * x[12:], cv, scheme, ns))
                                 [g.use.any(1)]) for g in segs])
            w = 1.0 / np.maximum(r.std(0), 1e-12)
        return res, w

    # the first search: one stiffness for all on a grid (a resonance far from the
    # prior's is a local minimum of the output error), the prior's damping and rotors
    costs = []
    for q in s.k_grid:
        sch = scheme_ns(q * k0 * np.ones(6), m0 * np.ones(6)) if scheme_ns else (scheme, ns)
        if sch != (scheme, ns) or not costs:
            scheme, ns = sch
            _prepare(segs, reg, scheme, ns, s, s.highpass_hz)
            for g in segs:
                g.use = g.fit[:, None] & ~g.clamped[:, None] & np.ones((1, 6), bool)
        try:
            c = np.sum(resid(np.r_[[q] * 6, [1.0] * 12], np.ones(6), segs) ** 2)
        except hg.HexaglideError:
            c = np.inf
        costs.append(c if np.isfinite(c) else np.inf)
    q = s.k_grid[int(np.argmin(costs))]
    if log:
        log("drive trains: %d excited stretches (%.1f s), first search: k_axial %.3g N/m"
            % (len(segs), f.seconds, q * k0))
    if scheme_ns:                      # the board's substeps for that stiffness
        scheme, ns = scheme_ns(q * k0 * np.ones(6), m0 * np.ones(6))
    res, w = solve(np.r_[[q] * 6, [1.0] * 12], s.highpass_hz)
    if scheme_ns:
        sch2 = scheme_ns(k0 * res.x[:6], m0 * res.x[12:])
        if sch2 != (scheme, ns):
            scheme, ns = sch2
            res, w = solve(res.x, s.highpass_hz)
    J = res.jac
    r = res.fun
    k1, c1, m1 = k0 * res.x[:6], c0 * res.x[6:12], m0 * res.x[12:]
    tau = np.mean([_corr_time(((g.y - _simulate(g, k1, c1, m1, cv, scheme, ns))[:, j])[g.use[:, j]])
                   for g in segs for j in range(6) if g.use[:, j].sum() > 20])
    dof = max(1, len(r) - len(res.x))
    cov = np.linalg.pinv(J.T @ J) * (r @ r) / dof * tau
    scale = np.r_[[k0] * 6, [c0] * 6, [m0] * 6]
    x1 = res.x
    # the model's check: the same fit above a higher cutoff
    res2, _ = solve(x1, s.highpass_hz * s.check_ratio)
    diff = np.abs(res2.x - x1) * scale
    sig = np.sqrt(np.diag(cov)) * scale
    f.value = x1 * scale
    f.sigma_stat = sig
    f.check = diff
    f.sigma = np.sqrt(sig ** 2 + diff ** 2)
    f.k, f.c, f.m_rotor = f.value[:6], f.value[6:12], f.value[12:]
    f.sk, f.sc, f.sm = f.sigma[:6], f.sigma[6:12], f.sigma[12:]
    f.scheme, f.ns, f.tau = scheme, ns, tau
    f.rows = len(r)
    _prepare(segs, reg, scheme, ns, s, s.highpass_hz)
    f.rms = np.array([np.sqrt(np.mean(np.concatenate([(g.y - _simulate(g, f.k, f.c, f.m_rotor, cv, scheme, ns))
                                                       [g.use[:, j], j] for g in segs]) ** 2)) for j in range(6)])
    f.rms_y = np.array([np.sqrt(np.mean(np.concatenate([g.y[g.use[:, j], j] for g in segs]) ** 2))
                        for j in range(6)])
    return f


def _corr_time(r, maxlag=200):
    """Integrated autocorrelation time of residuals (samples)."""
    import hexaglide_identify as hid
    return hid.autocorr_time(r, maxlag)
