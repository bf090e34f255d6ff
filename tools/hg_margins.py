"""hg_margins.py - stability margins of the servo loops on the machine as
modelled (flexible drive trains included), for `hexaglide tune`
(tools/hexaglide_tune.py; the method: docs/tuning.md "Margins").

The plant: the board seen by the pids, DAC volts u_k of period k to the
encoder positions y_k read at the start of period k (mm), six in, six out,
measured on the closed loop hg_loop runs (src/hg_loop.c, through hg.batch):
at HOME, friction off (the linear part; sticking carriages have no FRF),
encoders of 1 nm (counts_per_rev raised: the quantization of 1 um would
swamp the high frequencies), six runs each exciting one joint's DAC with a
periodic multi-sine (Schroeder phases) through pid.N.FF0 while a slow
holding loop keeps the machine at HOME. Y = P U over the six runs gives the
6 x 6 frequency response P(f) at every tone, the servo period's delay (read,
compute, write) and the zero-order hold in it; the holding loop's gains drop
out (u and y are both measured).

The loop: L(f) = diag(C_j(f) N_j(f)) P(f), C_j LinuxCNC's pid on the
feedback (pid.c: P + I T / (1 - z^-1) + D (1 - z^-1) / T, z = e^{j 2 pi f T};
feed-forward does not enter the loop) and N_j a biquad.N notch
(src/hg_biquad.c's response). Six pids closing six loops: the margins are
those of L's characteristic loci (the eigenvalues of L(f), tracked across
f; generalized Nyquist): the gain margin is the factor on every P, I, D
that brings a locus through -1, the phase margin the phase lag that does,
the modulus margin min |1 + lambda| (1 / the peak sensitivity).
"""
import functools
import re
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import hexaglide as hg
import hg_csv
from hg_program import PERIOD_S   # (tune's one servo period)

MEAS_BANDWIDTH_HZ = 20.0      # the holding loop during the measurement
WINDOW = 2000                 # periods per multi-sine period: tones on a 0.5 Hz grid
SETTLE = 500                  # periods from HOME before the excitation starts
TONE_STEP = 4                 # every 4th bin: tones 2 Hz apart
TONES_LOW = (1, 2, 3)         # and 0.5, 1, 1.5 Hz
TONE_V = 0.04                 # volts per tone on the DAC (peak about 1.3 V)
FF0_PER_MM = 1000.0           # the excitation's command (mm) times this is its volts
MODE_BAND = 0.7               # "near the mode": from this fraction of the first mode's frequency up
MIN_GM_DB = 6.0               # what tune asks of a loop
MIN_PM_DEG = 30.0
MIN_MODULUS = 0.5             # |1 + lambda| >= 0.5: peak sensitivity <= 6 dB


def tone_bins():
    """The multi-sine's DFT bins of the WINDOW-period cycle."""
    return np.r_[list(TONES_LOW), np.arange(TONE_STEP, WINDOW // 2, TONE_STEP)]


def multisine(bins):
    """One period (WINDOW samples) of unit tones at bins with Schroeder phases (low crest factor)."""
    k = np.arange(WINDOW)
    n = len(bins)
    ph = -np.pi * np.arange(1, n + 1) * np.arange(n) / n
    return np.sum(np.cos(2 * np.pi * np.outer(bins, k) / WINDOW + ph[:, None]), axis=0)


def pid_from_bandwidth(start, hz, zeta):
    """P, I, D (per joint) placing the closed-loop poles of m s^3 + (c + D) s^2 + P s + I at
    (s + w)(s^2 + 2 zeta w s + w^2), w = 2 pi hz (SI, then mm and volts); start: tune's
    model start (mass_kg, c_visc, fpv: the rigid machine's per-joint mass, damping, N/V)."""
    w = 2 * np.pi * hz
    m, c, fpv = start["mass_kg"], start["c_visc"], start["fpv"]
    P = m * (1 + 2 * zeta) * w * w / fpv / 1000.0
    D = np.maximum(m * (2 * zeta + 1) * w - c, 0.0) / fpv / 1000.0
    I = m * w ** 3 / fpv / 1000.0
    return P, I, D


def holding_gains(start, hz=MEAS_BANDWIDTH_HZ, zeta=0.7):
    """The measurement's holding loop: the model start's PID at hz, its gravity BIAS, 1 nm counts."""
    P, I, D = pid_from_bandwidth(start, hz, zeta)
    return [dict(P=P[j], I=I[j], D=D[j], BIAS=start["BIAS"][j], INPUT_SCALE=1e6) for j in range(6)]


def measurement_params(params=None):
    """The machine of the measurement: params (default the board's defaults) with friction off
    and encoders of 1 nm."""
    p = hg.Params()
    if params is not None:
        p.buf.raw = params.buf.raw
    p["f_coulomb"] = p["f_static"] = 0.0
    p["counts_per_rev"] = p["lead"] * 1e9
    return p


def plant_frf(start, params=None, threads=0):
    """(freqs Hz, P (nf, 6, 6) mm/V): the plant's frequency response as the module says,
    measured in six hg_loop runs through hg.batch (threads: as hg.batch's)."""
    bins = tone_bins()
    x = multisine(bins) * TONE_V / FF0_PER_MM
    n = SETTLE + 2 * WINDOW                   # settle, one cycle of transient, one measured
    bp = measurement_params(params).board_params()
    base = holding_gains(start)
    jobs = []
    for j in range(6):
        g = [dict(b) for b in base]
        g[j]["FF0"] = FF0_PER_MM
        cmd = np.zeros((n, 6))
        cmd[SETTLE:, j] = np.tile(x, 2)
        jobs.append(hg.Job(hg.loop_config(g), bp, cmd, keep=True, tool_error=False))   # f-errors only
    res = hg.batch(jobs, threads)
    k0 = SETTLE + WINDOW
    Y = np.zeros((len(bins), 6, 6), complex)
    U = np.zeros((len(bins), 6, 6), complex)
    for j, (job, r) in enumerate(zip(jobs, res)):
        if not r.ok or r.ferror_mm is None or len(r.ferror_mm) < n:
            raise hg.HexaglideError("plant measurement run %d" % j, r.rc or -1)
        y = np.vstack([np.zeros((1, 6)), job.cmd[:-1] - r.ferror_mm[1:]])   # f-error = previous cmd - fb
        u = r.output_v
        Y[:, :, j] = np.fft.fft(y[k0:k0 + WINDOW], axis=0)[bins]
        U[:, :, j] = np.fft.fft(u[k0:k0 + WINDOW], axis=0)[bins]
    P = np.einsum("fij,fjk->fik", Y, np.linalg.inv(U))
    return bins / (WINDOW * PERIOD_S), P


def pid_response(gains, freqs, period_s=PERIOD_S):
    """(nf, 6): pid.N's response from feedback to output, negated (output = -C y + ...)."""
    z1 = np.exp(-2j * np.pi * np.asarray(freqs) * period_s)       # z^-1
    out = np.zeros((len(z1), 6), complex)
    for j, g in enumerate(gains):
        out[:, j] = g.get("P", 0.0) + g.get("I", 0.0) * period_s / (1 - z1) + g.get("D", 0.0) * (1 - z1) / period_s
    return out


def notch_responses(notch, freqs, period_ns=1000000):
    """(nf, 6): biquad.N's responses (1 where a joint has none); notch as hg.loop_config's."""
    out = np.ones((len(freqs), 6), complex)
    for j, nf in enumerate(notch or []):
        if nf is not None:
            out[:, j] = _notch_column(float(nf[0]), float(nf[1]), np.asarray(freqs, float).tobytes(), period_ns)
    return out


@functools.lru_cache(maxsize=32)
def _notch_column(f0, q, freqs_bytes, period_ns):
    """hg.notch_response's values at the frequencies of freqs_bytes (a float64 buffer), kept: the
    search asks the same notch for every candidate."""
    h = hg.notch_response(f0, q, np.frombuffer(freqs_bytes), period_ns)[0]
    h.flags.writeable = False
    return h


def loci(gains, freqs, P, notch=None):
    """(nf, 6): the eigenvalues of L(f) = diag(C N) P(f), each column one locus (loci_many)."""
    return loci_many([gains], freqs, P, [notch])[0]


def eigvals_threads(M, threads=1):
    """np.linalg.eigvals of the stack of matrices M (m, ..., n, n), its first axis split over
    `threads` Python threads: numpy's LAPACK loop releases the GIL, and each matrix's
    eigenvalues are the same bits however the stack is split."""
    parts = np.array_split(M, max(1, min(int(threads), len(M))))
    if len(parts) == 1:
        return np.linalg.eigvals(M)
    with ThreadPoolExecutor(len(parts)) as ex:
        return np.concatenate(list(ex.map(np.linalg.eigvals, parts)))


def loci_many(gains, freqs, P, notches, threads=1):
    """(m, nf, 6): loci of each of m gain sets (with notches[i]) on one plant, tracked by nearest
    neighbour from one frequency to the next: each previous eigenvalue in turn takes the nearest
    one not yet taken, in |log| of their ratio (a distance that is NaN counts as infinite; where
    every one left is infinite, the first left). Every frequency's and gain set's eigenvalues in
    one go (eigvals_threads over `threads`), the tracking for every gain set at once."""
    if not len(gains):
        return np.zeros((0, len(freqs), 6), complex)
    cn = np.array([pid_response(g, freqs) * notch_responses(nf, freqs) for g, nf in zip(gains, notches)])
    evs = eigvals_threads(cn[:, :, :, None] * P, threads)   # (m, nf, 6)
    with np.errstate(divide="ignore", invalid="ignore"):
        dist = np.abs(np.log(evs[:, 1:, None, :] / evs[:, :-1, :, None]))   # [c][i - 1][p][q]
    dist[np.isnan(dist)] = np.inf
    m, nf = evs.shape[:2]
    rows = np.arange(m)
    order = np.empty((m, nf, 6), int)                    # order[c][i][p]: locus p's eigenvalue at f_i
    order[:, 0] = np.arange(6)
    for i in range(1, nf):
        taken = np.zeros((m, 6), bool)
        for p in range(6):
            d = dist[rows, i - 1, order[:, i - 1, p]]    # (m, 6): from locus p's previous eigenvalue
            d[taken] = np.inf
            k = np.argmin(d, axis=1)
            k = np.where(taken[rows, k], np.argmin(taken, axis=1), k)   # all left infinite: the first left
            order[:, i, p] = k
            taken[rows, k] = True
    return np.take_along_axis(evs, order, axis=2)


def margins_of_locus(freqs, l):
    """Crossings of one locus l(f) of a stable loop: [(gm_db, f)] at each phase crossover
    (-180 mod 360) where |l| < 1 (the gain increase that reaches -1; crossings above 1 are
    the margins for a gain decrease),
    [(pm_deg, f)] at each gain crossover (|l| = 1), linear in log |l| and phase between
    frequencies; both in the order of frequency."""
    ph = np.degrees(np.unwrap(np.angle(l)))
    mag = np.log(np.abs(l))
    a, b = ph[:-1] + 180.0, ph[1:] + 180.0        # between f_i and f_i+1, phase + 180
    m0, m1 = np.floor(np.minimum(a, b) / 360.0), np.floor(np.maximum(a, b) / 360.0)
    inner = np.arange(1, len(l)) < len(l) - 1       # f_i+1 is not the last frequency
    rows, turns, ws = [], [], []
    for k in range(int(np.nan_to_num(m1 - m0, nan=0.0).max(initial=0.0)) + 1):
        c = 360.0 * (m0 + k)                          # the phase crossing -180 + 360 (m0 + k)
        hit = (m0 + k <= m1) & ((a - c) * (b - c) <= 0) & (a != b) & ~((b == c) & inner)
        i = np.nonzero(hit)[0]
        rows.append(i)
        turns.append(np.full(len(i), k))
        ws.append((c[i] - a[i]) / (b[i] - a[i]))
    o = np.lexsort((np.concatenate(turns), np.concatenate(rows)))
    i, w = np.concatenate(rows)[o], np.concatenate(ws)[o]
    lm = mag[i] + w * (mag[i + 1] - mag[i])
    s = lm < 0                                        # |l| < 1: the factor up to -1 (a stable loop's margin)
    i, w = i[s], w[s]
    gms = list(zip((-20 * np.log10(np.e) * lm[s]).tolist(), (freqs[i] + w * (freqs[i + 1] - freqs[i])).tolist()))
    i = np.nonzero((mag[:-1] >= 0) != (mag[1:] >= 0))[0]
    w = mag[i] / (mag[i] - mag[i + 1])
    r = (ph[i] + w * (ph[i + 1] - ph[i]) + 180.0) % 360.0
    pms = list(zip(np.where(r > 180.0, r - 360.0, r).tolist(), (freqs[i] + w * (freqs[i + 1] - freqs[i])).tolist()))
    return gms, pms


def first_mode(freqs, P):
    """The first drive-train resonance the loops see: the lowest frequency above 50 Hz where
    the largest singular value of P(f) (2 pi f)^2 (the plant's acceleration per volt) peaks
    above 1.2 times the rigid-body level below it; None if there is none (a rigid train)."""
    s = np.array([np.linalg.svd(p, compute_uv=False)[0] for p in P]) * (2 * np.pi * freqs) ** 2
    base = None
    for i in range(1, len(freqs) - 1):
        if freqs[i] < 50:
            continue
        base = s[i] if base is None else min(base, s[i])
        if s[i] >= s[i - 1] and s[i] >= s[i + 1] and s[i] > 1.2 * base:
            return float(freqs[i])
    return None


def margins(gains, freqs, P, notch=None, mode_hz=None):
    """The loop's margins: dict gm_db, gm_hz (the smallest over the loci's phase crossovers:
    +inf if none), pm_deg, pm_hz (the smallest over the gain crossovers), modulus, modulus_hz
    (min |1 + lambda| over every locus and frequency), mode_hz and mode_modulus, mode_at_hz
    (the same from MODE_BAND * mode_hz up; None without a mode)."""
    return margins_many([gains], freqs, P, [notch], mode_hz)[0]


def margins_many(gains, freqs, P, notches, mode_hz=None, threads=1):
    """margins of each of a list of gain sets (with notches[i]) on one plant (loci_many)."""
    return [margins_of_loci(lam, freqs, mode_hz) for lam in loci_many(gains, freqs, P, notches, threads)]


def margins_of_loci(lam, freqs, mode_hz=None):
    """margins' dict from the loci lam (nf, 6)."""
    gm, pm = (np.inf, None), (np.inf, None)
    for c in range(6):
        g, p = margins_of_locus(freqs, lam[:, c])
        for x in g:
            if x[0] < gm[0]:
                gm = x
        for x in p:
            if x[0] < pm[0]:
                pm = x
    d = np.abs(1 + lam)
    i, c = np.unravel_index(np.argmin(d), d.shape)
    out = {"gm_db": gm[0], "gm_hz": gm[1], "pm_deg": pm[0], "pm_hz": pm[1],
           "modulus": float(d[i, c]), "modulus_hz": float(freqs[i]), "mode_hz": mode_hz,
           "mode_modulus": None, "mode_at_hz": None}
    if mode_hz:
        band = freqs >= MODE_BAND * mode_hz
        if band.any():
            dm = d[band].min(1)
            k = int(np.argmin(dm))
            out["mode_modulus"], out["mode_at_hz"] = float(dm[k]), float(freqs[band][k])
    return out


def verdict(m):
    """None if the margins are what tune asks (MIN_GM_DB, MIN_PM_DEG, MIN_MODULUS near the
    mode), else the reason, naming the mode and the margin."""
    why = []
    if m["mode_modulus"] is not None and m["mode_modulus"] < MIN_MODULUS:
        why.append("under-damped near the axial mode at %.0f Hz: |1 + L| = %.2f at %.0f Hz (peak sensitivity "
                   "%.1f dB, at most %.0f dB asked)" % (m["mode_hz"], m["mode_modulus"], m["mode_at_hz"],
                                                        -20 * np.log10(m["mode_modulus"]),
                                                        -20 * np.log10(MIN_MODULUS)))
    if m["gm_db"] < MIN_GM_DB:
        why.append("%s: gain margin %.1f dB at %.0f Hz (at least %.0f dB asked)"
                   % ("unstable" if m["gm_db"] <= 0 else "too little gain margin", m["gm_db"], m["gm_hz"], MIN_GM_DB))
    if m["pm_deg"] < MIN_PM_DEG:
        why.append("phase margin %.0f deg at %.0f Hz (at least %.0f deg asked)" % (m["pm_deg"], m["pm_hz"], MIN_PM_DEG))
    return "; ".join(why) or None


def describe(m):
    """One line of the margins."""
    s = "gain margin %s, phase margin %s, modulus margin %.2f at %.0f Hz" % (
        "%.1f dB at %.0f Hz" % (m["gm_db"], m["gm_hz"]) if np.isfinite(m["gm_db"]) else "inf",
        "%.0f deg at %.0f Hz" % (m["pm_deg"], m["pm_hz"]) if np.isfinite(m["pm_deg"]) else "inf",
        m["modulus"], m["modulus_hz"])
    if m["mode_modulus"] is not None:
        s += ", |1 + L| %.2f near the %.0f Hz mode (at %.0f Hz)" % (m["mode_modulus"], m["mode_hz"], m["mode_at_hz"])
    return s


# ------------------------------------------------------------------ notch (LinuxCNC's biquad)
NOTCH_Q = (0.5, 0.7, 1.0, 1.4, 2.0)     # biquad.comp accepts 0.5 <= Q <= 2
NOTCH_FORMAT = "%.6g"                   # f0 and Q in the hal lines (notch_hal), as read_notch reads them back


def as_printed(v):
    """v as notch_hal prints it (NOTCH_FORMAT)."""
    return float(NOTCH_FORMAT % v)


def notch_for(gains, freqs, P, mode_hz):
    """(f0, Q) of a biquad notch for the loops' resonance: f0 at the resonance's peak of
    |L| (the worst locus's largest |lambda| from MODE_BAND * mode_hz up), Q of NOTCH_Q
    that leaves the largest modulus margin; None without a mode."""
    if not mode_hz:
        return None
    lam = loci(gains, freqs, P)
    band = (freqs >= MODE_BAND * mode_hz) & (freqs < 0.5 / PERIOD_S)
    f0 = as_printed(float(freqs[band][np.argmax(np.abs(lam[band]).max(1))]))   # (searched as LinuxCNC gets it)
    best = None
    for q in NOTCH_Q:
        m = margins(gains, freqs, P, [(f0, q)] * 6, mode_hz)
        if best is None or m["modulus"] > best[0]:
            best = (m["modulus"], q)
    return f0, best[1]


HAL_NETS = ["z11", "z12", "z21", "z22", "z31", "z32"]   # configs/hexaglide.hal's net name of joint N


def notch_hal(f0, q, joints=6):
    """The hal lines that put a biquad.N notch (f0 Hz, Q) between pid.N.output and
    motenc.0.dac-NN-value of configs/hexaglide.hal, as comment-free text: the addf lines
    belong after `addf pid.5.do-pid-calcs`, before `addf motenc.0.dac-write` (the servo
    thread runs functions in the order added); the nets replace the zNN-output nets."""
    out = ["loadrt biquad count=%d" % joints]
    out += ["addf biquad.%d servo-thread" % j for j in range(joints)]
    for j in range(joints):
        out += ["setp biquad.%d.type 2" % j, "setp biquad.%d.f0 %s" % (j, NOTCH_FORMAT % f0),
                "setp biquad.%d.Q %s" % (j, NOTCH_FORMAT % q),
                "setp biquad.%d.enable 1" % j,
                "net %s-output  <= pid.%d.output => biquad.%d.in" % (HAL_NETS[j], j, j),
                "net %s-notched <= biquad.%d.out => motenc.0.dac-%02d-value" % (HAL_NETS[j], j, j)]
    return "\n".join(out) + "\n"


NOTCH_SETP = re.compile(r"#?\s*setp\s+biquad\.(\d+)\.(type|f0|Q|enable)\s+(\S+)\s*$")
NOTCH_PINS = {"type": 2.0, "enable": 1.0}     # what notch_hal sets besides f0 and Q: a notch, switched on


def read_notch(path, joints=6):
    """The notch (f0 Hz, Q) of a tune output's hal lines (notch_hal's, in comment lines: `#   setp
    biquad.N.f0 176`), or None where the file has no `setp biquad.` line (an INI, or an output
    without a notch). tune's notch is one biquad on every joint: biquad.0..joints-1 each set
    type 2, f0, Q and enable 1, with the same f0 and Q; anything else (a joint left out, a pin set
    twice, another type, enable 0, a value that is not a finite number, f0 <= 0, joints that
    differ) is a ValueError naming the file and line."""
    pins, where = {}, {}                      # (joint, pin) -> value, line
    with open(path) as f:
        for no, line in enumerate(f, 1):
            m = NOTCH_SETP.match(line.strip())
            if not m:
                continue
            j, pin, text = int(m.group(1)), m.group(2), m.group(3)
            if j >= joints:
                raise ValueError("%s line %d: biquad.%d: the notch is biquad.0..%d, one per joint"
                                 % (path, no, j, joints - 1))
            if (j, pin) in where:
                raise ValueError("%s line %d: biquad.%d.%s is set twice (line %d too): keep one"
                                 % (path, no, j, pin, where[j, pin]))
            try:
                v = hg_csv.number(text)
            except ValueError:
                v = float("nan")
            if not np.isfinite(v):
                raise ValueError("%s line %d: biquad.%d.%s %s: not a finite number" % (path, no, j, pin, text))
            if pin in NOTCH_PINS and v != NOTCH_PINS[pin]:
                raise ValueError("%s line %d: biquad.%d.%s %s: tune's notch is biquad type 2, enable 1 (the "
                                 "lines tune writes); the loop it predicts has no other filter"
                                 % (path, no, j, pin, text))
            if pin == "f0" and not v > 0:
                raise ValueError("%s line %d: biquad.%d.f0 %s: must be above 0 Hz" % (path, no, j, text))
            pins[j, pin], where[j, pin] = v, no
    if not pins:
        return None
    for j in range(joints):
        for pin in ("type", "f0", "Q", "enable"):
            if (j, pin) not in pins:
                raise ValueError("%s: no setp biquad.%d.%s line: tune's notch sets type 2, f0, Q and enable 1 of "
                                 "biquad.0..%d, one per joint (the lines tune writes, line %d on)"
                                 % (path, j, pin, joints - 1, min(where.values())))
        for pin in ("f0", "Q"):
            if pins[j, pin] != pins[0, pin]:
                raise ValueError("%s line %d: biquad.%d.%s %g, biquad.0's %g: tune's notch is one f0 and Q on every "
                                 "joint" % (path, where[j, pin], j, pin, pins[j, pin], pins[0, pin]))
    return pins[0, "f0"], pins[0, "Q"]
