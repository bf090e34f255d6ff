#!/usr/bin/python3
"""hexaglide_identify_serial.py - `hexaglide identify` for the serial-axis
plant (docs/serial.md): per axis, from board records (format 2, `plant
serial`) of a run, the reflected moving mass, viscous friction c, sliding
(Coulomb) friction, the breakaway excess where the record has slow sliding,
and on a vertical axis the net weight (gravity less counterbalance), by
linear least squares on the axis's force balance (src/hg_plant_serial.c,
rigid train: the encoder counts the motor, the load follows it within
force / k_axial):

    kt 2 pi / lead  i  =  M a + c v + F_c sgn v + (F_s - F_c) exp(-(v/v_s)^2) sgn v + W
    M = mass + j_rotor (2 pi / lead)^2       (the reflected total: load and rotor)
    W = mass g - counterbalance              (axes with gravity only)

i is the drive's winding current (out.current-K, the drive's current
monitor), x the motor's travel from the encoder counts (lead / counts_per_rev
per count), v and a its derivatives after a zero-phase Butterworth low-pass
applied alike to both sides. Known beforehand (from the record's parameter
events or --set, the motor's and encoder's data sheets): kt, lead,
counts_per_rev, j_rotor, g, v_stribeck. Periods slower than v_stribeck (3
v_stribeck when the record has too little slow sliding for the breakaway
column) are left out (stick, or about to), with the filter's response time
around them, as are periods with the amplifier off or a fault, periods with
the load at a hard stop or a limit switch tripped (the balance has no stop force:
at_stop) and periods with the drive at its bus voltage (the current moves within
them: at_bus). Rotary axes: the same with N m, kg m^2 and rad (ratio instead of 2 pi / lead).

A result the board would refuse (a mass at or below zero, a negative c_visc or
f_coulomb, f_coulomb above f_static: physical_refusals) is reported and not written.

stdout: NAME = VALUE ± SIGMA UNIT lines, '#' lines for the rest; --output:
setp lines (HAL units) and [SERIAL] INI lines. Exit 0 ok, 1 a result that is
not physically possible (no --output written), 2 bad input."""
import ctypes as C
import io
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hexaglide as hg  # noqa: E402
import hg_csv  # noqa: E402
import hg_identify_base as ib  # noqa: E402
import hg_cli  # noqa: E402
import hg_output  # noqa: E402

CUTOFF_HZ = 25.0
ORDER = 4
MIN_SAMPLES = 500
SLOW = 1.0          # v_stribeck: slower periods are not the sliding fit's (stick, or about to) ...
SLOW_NO_BREAKAWAY = 3.0   # ... and slower than this when the breakaway is not excited (the Stribeck
                          # excess, exp(-9) of it at 3 v_stribeck, is then not in the fit)
KNOWN = ("kt", "lead", "ratio", "counts_per_rev", "j_rotor", "g", "v_stribeck",
         "amp_mode", "kp_vel", "ki_vel", "v_rated",     # the amplifier's settings: the substeps' current
         "r_winding", "l_winding", "v_bus",              # the winding and the bus: where the drive is at its bus
         "k_axial")                                      # the board's train: rigid (0) or not, ditto
DEFAULTED = ("amp_mode", "kp_vel", "ki_vel", "v_rated", "r_winding", "l_winding", "v_bus",
             "k_axial")                                  # of KNOWN: the plant's default if not told
DAC_VOLTS_MAX = 10.0   # the drives' command range, +-10 V (src/hg_analog.h HG_DAC_VOLTS_MAX)
MC_FITS = 20        # fits at most while M settles (period_mean_current); the stock config takes 8
RANK_TOL = 1e-4     # a column within this (relative, columns scaled to unit norm) of the others' span: not identifiable
MIN_BREAKAWAY = 300  # sliding periods with exp(-(v/v_s)^2) > 0.05 that make the breakaway identifiable
INPUTS_PER_CHANNEL = 4   # the board's digital inputs per axis: limit-, limit+, home, amplifier fault
LIMIT_BITS = (0, 1)      # ... of which the limit switches (src/hg_sensors.h HG_IN_LIMIT_MIN, HG_IN_LIMIT_MAX)
INPUTS_PER_WORD = 32     # out.in-word-N packs inputs 32 N .. 32 N + 31, bit i input 32 N + i (src/hg_board_rec.c)


class BadInput(Exception):
    pass


def log(*a):
    print("hexaglide identify:", *a, file=sys.stderr, flush=True)


def is_serial_record(path, data=None):
    """True for a board record of the serial plant: its header's "# plant serial" line (hexaglide sim,
    hg.Recorder) or its first row's in.plant column (tools/hg_record.py's records). data: the file's
    bytes when the caller has read them (read_record), else the file's head is read here."""
    try:
        with io.BytesIO(data) if data is not None else open(path, "rb") as f:
            if f.readline().rstrip(b"\r\n") not in hg.RECORD_MAGICS:
                return False
            for _ in range(64):
                line = f.readline()
                if line.strip() == b"# plant serial":
                    return True
                if line.startswith(b"sample,"):
                    header = line.decode().rstrip("\r\n").split(",")
                    row = f.readline().decode().split(",")
                    if "in.plant" not in header or len(row) != len(header):
                        return False
                    return int(float(row[header.index("in.plant")])) == hg.plant_names().index("serial")
    except (OSError, ValueError, UnicodeDecodeError):
        return False
    return False


class Record:
    """What the fit needs of one record: per period current, counts, amplifier state, the parameters."""


def read_record(path):
    """The record at path, read once (its bytes passed to the plant check and the column reader)."""
    try:
        data = ib.record_bytes(path)
    except ib.RecordError as ex:
        raise BadInput(str(ex))
    if not is_serial_record(path, data) and not ib.rec_open(C.create_string_buffer(ib.REC_BYTES), data,
                                                             len(data), C.byref(ib.RecErr())):
        raise BadInput("%s: not a record of the serial plant (its in.plant, '# plant'): give a serial machine's "
                       "records alone (docs/serial.md)" % path)
    header = next((l for l in data.split(b"\n", 64) if l.startswith(b"sample,")), b"").decode(errors="replace")
    n = sum(1 for h in header.rstrip("\r").split(",") if h.startswith("out.current-"))   # the plant's axes
    words = sorted({INPUTS_PER_CHANNEL * k // INPUTS_PER_WORD for k in range(n)})
    need = ["in.period-ns", "in.model", "out.amps-on", "out.fault"] + ["out.count-%02d" % k for k in range(n)] + \
        ["out.current-%d" % k for k in range(n)] + ["in.dac-v-%02d" % k for k in range(n)] + \
        ["out.z-%d" % k for k in range(n)] + ["out.zd-%d" % k for k in range(n)] + \
        ["out.in-word-%d" % w for w in words] + ["in.substeps", "in.integrator"]
    try:
        a, _, hdr_no, evs = ib.record_columns(path, need, "not a serial plant's board record", data=data)
    except ib.RecordError as ex:
        raise BadInput(str(ex))
    told = {e: v for e, v, _ in evs}
    if len(a) < MIN_SAMPLES:
        raise BadInput("%s: %d periods; identify needs at least %d" % (path, len(a), MIN_SAMPLES))
    if np.ptp(a[:, 0]) > 0 or np.ptp(a[:, 1]) > 0:
        raise BadInput("%s: the servo period or the model changes within the record" % path)
    rec = Record()
    rec.path, rec.n, rec.dt, rec.hdr_no = path, n, a[0, 0] * 1e-9, hdr_no
    plant = hg.plant_names().index("serial")
    rec.variant = int(a[0, 1])
    rec.names = [x.name.decode() for x in hg.params_table(plant, rec.variant)]
    rec.told = {rec.names[i]: v for i, v in told.items() if i < len(rec.names)}
    rec.ok = (a[:, 2] > 0.5) & (a[:, 3] < 0.5)
    rec.counts = a[:, 4:4 + n]
    rec.current = a[:, 4 + n:4 + 2 * n]
    rec.volts = ib.dac_output(a[:, 4 + 2 * n:4 + 3 * n])     # what the board's DAC puts out
    rec.load = a[:, 4 + 3 * n:4 + 4 * n]                      # the loads' positions and speeds (at_stop)
    rec.load_v = a[:, 4 + 4 * n:4 + 5 * n]
    rec.in_words = {w: a[:, 4 + 5 * n + i].astype(np.int64) for i, w in enumerate(words)}
    if np.ptp(a[:, -2]) > 0 or np.ptp(a[:, -1]) > 0:
        raise BadInput("%s: the substeps or the integrator change within the record" % path)
    rec.substeps = substeps_run(rec, told, int(a[0, -2]), int(a[0, -1]), int(a[0, 0]))
    rec.rotary = [("inertia_%d" % k) in rec.names for k in range(n)]
    ran = record_params(rec, told)
    rec.at_stop = [at_stop(rec, k, ran) for k in range(n)]
    rec.stops = [(ran["stop_min_%d" % k], ran["stop_max_%d" % k]) for k in range(n)]
    return rec


def record_params(rec, told):
    """The serial plant's parameters of the record's model: its defaults, then the told entries."""
    pp = hg.PlantParams("serial")
    pp.variant, pp.names = rec.variant, rec.names
    hg._plant_defaults(pp.plant, pp.variant, C.byref(pp.v))
    for i, v in told.items():
        if i < len(rec.names):
            pp.v[i] = v
    return pp


def substeps_run(rec, told, substeps, integrator, period_ns):
    """The plant steps per servo period the board ran: the record's substeps, raised by the
    board's stability check for its parameters (src/hg_board.c), found by one period of it."""
    pp = record_params(rec, told)
    try:
        b = hg.Board(None, pp, substeps=max(1, substeps), integrator=integrator, period_ns=period_ns, plant="serial")
    except hg.HexaglideError as ex:     # (an edited record: the board that ran it took its set)
        raise BadInput("%s: the record's parameters are no machine the board runs (an edited record?): %s" % (rec.path, ex))
    return int(b.step([0.0] * rec.n).substeps_run)


def period_mean_current(rec, k, kn, v, force_per_amp, j_refl, m_fit, c_fit):
    """The drive's current averaged over each servo period, from the one it ends with (the record's).
    In velocity mode with s > 1 substeps of h = dt / s the amplifier's loop,
    i = kp (v_ref - v) + ki integral, runs every substep while the DAC's v_ref holds for the period:
    the speed error e relaxes by q = 1 - h (kp kt' + c) / M a substep, so with the period's speed
    change dv (= a dt) the mean exceeds the end by kp dv [(1 - q^s) / (s (1 - q)) - q^(s-1)] / (1 - q^s)
    ((s - 1) / (2 s) of kp dv for a loose loop), less ki's growth within the period,
    ki (v_ref - v) h (s - 1) / 2. The mass that relaxes is the rotor's (reflected, c 0) behind a
    flexible train, whose spring hardly moves within a substep (k h^2 / m_rotor ~ 0.05 on the stock
    config), else the fit's M and c (iterated). Torque mode and s = 1: the end. force_per_amp
    and j_refl: axis_rows' kt' and reflected rotor."""
    i_end = rec.current[:, k]
    s = rec.substeps
    get = lambda name: kn[name + "_%d" % k]
    if s <= 1 or get("amp_mode") != 1.0:
        return i_end
    h = rec.dt / s
    if get("k_axial") > 0:
        m_fit, c_fit = j_refl, 0.0
    q = 1.0 - h * (get("kp_vel") * force_per_amp + c_fit) / m_fit
    phi = (s - 1) / (2.0 * s) if abs(1 - q) < 1e-9 else ((1 - q ** s) / (s * (1 - q)) - q ** (s - 1)) / (1 - q ** s)
    dv = np.append(0.0, np.diff(v))                       # period n: from row n-1 to row n
    v_mid = np.append(v[0], 0.5 * (v[1:] + v[:-1]))
    v_ref = rec.volts[:, k] * get("v_rated") / DAC_VOLTS_MAX        # src/hg_drive.c's speed command
    return i_end + get("kp_vel") * dv * phi - get("ki_vel") * (v_ref - v_mid) * h * (s - 1) / 2


def at_stop(rec, k, pp):
    """Axis k's periods whose force balance holds a force the fit has no column for, as two masks:
    (stop, limit). stop: the load (out.z, the position the stop acts on: src/hg_stop.h, a spring
    in contact only) beyond a hard stop of pp, the parameters the board ran, or within its own
    travel in the period, |out.zd| dt, of one (it may have touched it between two samples). The
    load's own position needs no margin for the train's deflection, which the motor's (the
    encoder's) would: it is off the load's by force / k_axial and up to half the backlash. limit:
    a limit switch tripped (out.in-word): the board's rules place it before the stop, so the stop
    is near, and it is the record's word for that even where the parameters misplace the stop."""
    name = lambda f: "%s_%d" % (f, k)
    z, reach = rec.load[:, k], np.abs(rec.load_v[:, k]) * rec.dt
    stop = (z <= pp[name("stop_min")] + reach) | (z >= pp[name("stop_max")] - reach)
    first = INPUTS_PER_CHANNEL * k
    word = rec.in_words[first // INPUTS_PER_WORD]
    limit = np.zeros(len(z), bool)
    for b in LIMIT_BITS:
        limit |= ((word >> (first % INPUTS_PER_WORD + b)) & 1) == 1
    return stop, limit


def at_bus(rec, k, kn, v, force_per_amp):
    """Axis k's periods with its drive at the bus voltage: the winding needs r_winding i + the back-EMF
    (kt 2 pi/lead v) + l_winding di/dt, and where that reaches v_bus the amplifier applies the whole
    bus all period and the current falls short of its command, moving within the period
    (src/hg_drive.c, winding): the record's last current is not the period's mean. v: the motor's
    speed (axis_rows'), force_per_amp: kt 2 pi/lead (or kt ratio)."""
    get = lambda name: kn[name + "_%d" % k]
    i = rec.current[:, k]
    di = np.diff(i, prepend=i[0]) / rec.dt               # period n: from row n-1 to row n
    return np.abs(get("r_winding") * i + force_per_amp * v + get("l_winding") * di) >= get("v_bus")


def known(rec, sets):
    """The known parameters per axis: the record's events, then --set (spec names, SI); the
    amplifier's settings and the train's stiffness not told are the plant's defaults."""
    pp = record_params(rec, {})
    kn = {name: pp[name] for name in rec.names if name.rsplit("_", 1)[0] in DEFAULTED}
    for name, v in rec.told.items():
        base = name.rsplit("_", 1)[0]
        if base in KNOWN:
            kn[name] = v
    for s in sets:
        k, _, v = s.partition("=")
        if k.rsplit("_", 1)[0] not in KNOWN or k not in rec.names:
            raise BadInput("--set %s: not a known-beforehand parameter of this record (%s, per axis _K)"
                           % (s, ", ".join(KNOWN)))
        try:
            kn[k] = hg_csv.number(v)
        except ValueError:
            raise BadInput("--set %s: not a number" % s)
    pp = record_params(rec, rec_told_index(rec))
    for name, v in kn.items():
        given = [x for x in sets if x.partition("=")[0] == name]
        try:
            pp[name] = v
        except ValueError:             # (PlantParams takes finite numbers only)
            raise BadInput("%s: must be finite (SI units)" % ("--set " + given[-1] if given else
                                                            "%s: %s = %r" % (rec.path, name, v)))
    for name, v, why in pp.refused():
        given = [x for x in sets if x.partition("=")[0] == name]
        if given:
            raise BadInput("--set %s: %s" % (given[-1], why))
        if name in kn:
            raise BadInput("%s: %s = %r: %s" % (rec.path, name, v, why))
    return kn


def rec_told_index(rec):
    """rec.told by table index (record_params' form)."""
    return {rec.names.index(name): v for name, v in rec.told.items()}


def axis_rows(rec, k, kn, slow_vs=SLOW, mc=(None, 0.0)):
    """Rows (X, y, used mask, info) of axis k's force balance from one record, periods slower than
    slow_vs v_stribeck (and the filter's response time around them) left out; mc: the fit's (M, c)
    for the period-mean current (None: the loose-loop limit)."""
    from scipy.signal import butter, filtfilt
    rot = rec.rotary[k]
    get = lambda name: kn[name + "_%d" % k]
    if rot:
        per_rev = 2 * np.pi / get("ratio")               # axis rad per motor rev
        force_per_amp = get("kt") * get("ratio")
        j_refl = get("j_rotor") * get("ratio") ** 2
    else:
        per_rev = get("lead")
        force_per_amp = get("kt") * 2 * np.pi / get("lead")
        j_refl = get("j_rotor") * (2 * np.pi / get("lead")) ** 2
    x = rec.counts[:, k] * per_rev / get("counts_per_rev")
    dt = rec.dt
    b, a = butter(ORDER, CUTOFF_HZ * 2 * dt)
    xf = filtfilt(b, a, x)
    v = np.gradient(xf, dt)
    i_per = period_mean_current(rec, k, kn, v, force_per_amp, j_refl, mc[0] or np.inf, mc[1])
    i_eff = np.append(0.5 * (i_per[:-1] + i_per[1:]), i_per[-1])   # the current over steps n and n+1, which
    f = filtfilt(b, a, force_per_amp * i_eff)                        # the central differences at n span
    acc = np.gradient(v, dt)
    vs = get("v_stribeck")
    sg = np.sign(v)
    shape = np.exp(-(v / vs) ** 2)
    margin = int(3 / (CUTOFF_HZ * dt))                    # the filter's edges and the amplifier's switching
    bad = ib.dilate(~rec.ok, margin - 1)
    bad[:margin] = bad[-margin:] = True
    slow = np.abs(v) <= slow_vs * vs                         # and where the friction's sign change, smoothed
    near = ib.dilate(slow, margin - 1)                    # by the filter, is still in the force: the
    #                                                       filter's response time around each slow stretch
    stop, limit = rec.at_stop[k]                          # a stop's force, spread by the filter likewise
    near_stop = ib.dilate(stop | limit, margin - 1)
    at_v_bus = at_bus(rec, k, kn, v, force_per_amp)        # the current moving within the period: likewise
    near_bus = ib.dilate(at_v_bus, margin - 1)
    use = ~bad & ~near & ~near_stop & ~near_bus
    grav = (not rot) and get("g") != 0.0
    cols = [acc, v, sg, shape * sg] + ([np.ones_like(v)] if grav else [])
    return np.column_stack(cols), f, use, dict(j_refl=j_refl, grav=grav, g=get("g") if not rot else 0.0,
                                              excited=int(((shape > 0.05) & use).sum()), margin=margin,
                                              stop=int(stop.sum()), limit=int(limit.sum()),
                                              stop_out=int((near_stop & ~bad & ~near).sum()), bus=int(at_v_bus.sum()),
                                              bus_out=int((near_bus & ~bad & ~near & ~near_stop).sum()))


COUNTED = ("excited", "stop", "limit", "stop_out", "bus", "bus_out")   # axis_rows' counts, summed over the records


def stop_words(info, stops, rot):
    """What fit_axis's info says of the periods at a hard stop or a tripped limit switch, in words."""
    if not (info["stop"] or info["limit"]):
        return "none at either"
    u = "rad" if rot else "m"
    return ("%d periods with the load at a hard stop (stop_min %g %s, stop_max %g %s; out.z) and %d with a limit "
            "switch tripped (out.in-word): with the filter's response time (%d periods) around them, %d periods "
            "left out that were usable otherwise" % (info["stop"], stops[0], u, stops[1], u, info["limit"],
                                                     info["margin"], info["stop_out"]))


def fit_axis(recs, k, kns):
    """Axis k's force balance fitted on every record: (estimates {name: (value, sigma)}, info)."""
    excited = sum(axis_rows(rec, k, kn)[3]["excited"] for rec, kn in zip(recs, kns))
    slow_vs = SLOW if excited >= MIN_BREAKAWAY else SLOW_NO_BREAKAWAY
    # the period-mean current depends on M and c when the substeps split the period (period_mean_current):
    # fitted again with the last fit's M and c until M settles; one fit otherwise
    modelled = [r.substeps > 1 and kn["amp_mode_%d" % k] == 1.0 for r, kn in zip(recs, kns)]
    iterate = any(m and kn["k_axial_%d" % k] == 0 for m, kn in zip(modelled, kns))
    mc, m_prev = (None, 0.0), None
    for fits in range(1, (MC_FITS if iterate else 1) + 1):
        X, y, info = [], [], None
        for rec, kn in zip(recs, kns):
            Xi, yi, use, inf = axis_rows(rec, k, kn, slow_vs, mc)
            X.append(Xi[use])
            y.append(yi[use])
            if info is None:
                info = inf
            else:
                for c in COUNTED:
                    info[c] += inf[c]
        X, y = np.vstack(X), np.concatenate(y)
        names = ["M", "c_visc", "f_coulomb", "f_breakaway"] + (["net_weight"] if info["grav"] else [])
        keep = [i for i, nm in enumerate(names) if nm != "f_breakaway" or info["excited"] >= MIN_BREAKAWAY]
        if len(y) < MIN_SAMPLES:
            raise BadInput("axis %d: %d usable periods (amplifier on, sliding faster than %g v_stribeck, the drive "
                           "below its bus voltage (%d periods at it), away from the hard stops and limit switches: "
                           "%s); identify needs %d: a longer or faster excitation%s"
                           % (k, len(y), slow_vs, info["bus"], stop_words(info, recs[0].stops[k], recs[0].rotary[k]),
                              MIN_SAMPLES, ", inside the limit switches" if info["stop_out"] else ""))
        Xk = X[:, keep]
        scale = np.sqrt((Xk ** 2).sum(0))
        scale = np.where(scale > 0, scale, 1.0)
        sv, vt = np.linalg.svd(Xk / scale, full_matrices=False)[1:]
        if not sv[-1] > RANK_TOL * sv[0]:         # a combination these data cannot see: no estimate of it
            null = vt[-1]
            raise BadInput("%s: axis %d: these data cannot separate %s (they move the force alike: the axis never "
                           "accelerates or never reverses in its %d usable periods%s); identify needs an excitation "
                           "that speeds up, slows down and reverses (docs/serial.md)"
                           % (", ".join(r.path for r in recs), k, ", ".join(names[keep[i]] for i in np.flatnonzero(np.abs(null) > 0.1)), len(y),
                              "; " + stop_words(info, recs[0].stops[k], recs[0].rotary[k]) if info["stop_out"] else ""))
        theta, *_ = np.linalg.lstsq(Xk / scale, y, rcond=None)
        theta /= scale
        if not (theta[0] > 0):
            break                                   # no mass to iterate with: reported as fitted
        if m_prev is not None and abs(theta[0] - m_prev) <= 1e-9 * theta[0]:
            break
        m_prev, mc = theta[0], (theta[0], theta[1])
    r = y - Xk @ theta
    tau = ib.autocorr_time(r, maxlag=2000)
    s2 = r @ r / (len(y) - len(keep))
    cov = np.linalg.inv(Xk.T @ Xk) * s2 * tau
    sig = np.sqrt(np.diag(cov))
    est = {names[i]: (theta[j], sig[j]) for j, i in enumerate(keep)}
    u, sv, vt = np.linalg.svd(Xk / scale, full_matrices=False)
    info.update(substeps=max(r.substeps for r in recs) if any(modelled) else 1, fits=fits,
                flexible=kns[0]["k_axial_%d" % k] > 0, rows=len(y), tau=tau, slow_vs=slow_vs, excited=excited, rms=np.sqrt(s2), cond=sv[0] / sv[-1], dropped=[names[i] for i in range(len(names)) if i not in keep])
    return est, info


# What most likely made an identified value one the board refuses (physical_refusals), by field
LOAD_CAUSE = ("M came out at or below the known rotor's j_rotor %s: a force the fit has no column for moved the "
              "axis (a hard stop or a clamp the record's parameters do not place, a cable's pull), or a known "
              "parameter is wrong: --set the data sheet's j_rotor, kt and %s")
CAUSES = {
    "mass": LOAD_CAUSE % ("(2 pi/lead)^2", "lead"),
    "inertia": LOAD_CAUSE % ("ratio^2", "ratio"),
    "c_visc": "the speed's column took up a force the fit has no column for, or the speeds span too narrow a range "
              "to part c_visc from f_coulomb; a wrong kt or lead scales every force",
    "f_coulomb": "the speed's sign took up a force the fit has no column for, or the speeds span too narrow a "
                 "range to part f_coulomb from c_visc; a wrong kt or lead scales every force",
    "f_static": {True: "too little slow sliding near v_stribeck for the breakaway, or a wrong v_stribeck",
                 False: "kt or lead too large (the drive's force is kt 2 pi/lead i), or the record's f_static below "
                        "the machine's"},
    "v_bus": "the identified net weight needs more current than the bus drives: a wrong kt or lead, or a force the "
             "fit has no column for (a hard stop the record's parameters do not place)",
}
RELATED = {"f_static": ("f_coulomb",), "v_bus": ("mass", "counterbalance")}   # identified values in a rule


def physical_refusals(rec, kn, spec):
    """The identified values spec (spec names, SI) the board would refuse beside the record's other
    parameters and the known kn: its own rules (src/hg_plant_serial.c, PlantParams.refused), so a
    mass at or below zero, a negative c_visc or f_coulomb and an f_coulomb above f_static are among
    them. [(the identified names it concerns, a message naming them, the rule and the likely
    cause)]; [] when the result is physically possible."""
    pp = record_params(rec, rec_told_index(rec))
    for name, v in list(kn.items()) + list(spec.items()):
        pp[name] = v
    units = {e.name.decode(): e.unit.decode() for e in hg.params_table(hg.plant_names().index("serial"), rec.variant)}
    value = lambda name, v: "%s = %.6g %s" % (name, v, units[name])
    out = []
    for name, v, why in pp.refused():
        field, k = name.rsplit("_", 1)
        related = [r + "_" + k for r in RELATED.get(field, ()) if r + "_" + k in spec]
        cause = CAUSES.get(field, "a known parameter is wrong (--set it), or a force the fit has no column for")
        if field == "f_static":
            cause = "the sliding friction came out above the breakaway: " + cause[name in spec]
        if name in spec:
            names = [name]
            what = "%s (identified%s): %s" % (value(name, v), "".join(": f_coulomb + f_breakaway, " + value(r, spec[r])
                                                                    for r in related), why)
        else:
            names = related
            what = "%s (identified) with the record's %s: %s %s" % (" and ".join(value(r, spec[r]) for r in related),
                                                                   value(name, v), name, why)
        out.append((names, "axis %s: %s: not physically possible; likely cause: %s" % (k, what, cause)))
    return out


def unit(rot, what):
    """The unit of an estimate (M, c_visc, ...) on a linear (rot 0) or rotary axis."""
    return {("M", 0): "kg", ("M", 1): "kg m^2", ("c_visc", 0): "N s/m", ("c_visc", 1): "N m s/rad",
            ("f_coulomb", 0): "N", ("f_coulomb", 1): "N m", ("f_breakaway", 0): "N", ("f_breakaway", 1): "N m",
            ("net_weight", 0): "N", ("mass", 0): "kg", ("counterbalance", 0): "N", ("f_static", 0): "N",
            ("f_static", 1): "N m", ("inertia", 1): "kg m^2"}[(what, int(rot))]


def main(argv):
    """hexaglide identify on serial records: read, fit, report, check, write."""
    ap = hg_cli.Parser(prog="hexaglide identify (serial plant)")
    ap.add_argument("records", nargs="+")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE")
    ap.add_argument("--output")
    a, rest = ap.parse_known_args(argv)
    try:
        if rest:
            raise BadInput("%s: not an option of identify for the serial plant (it takes RECORD... --set "
                           "--output)" % " ".join(rest))
        hg_output.refuse_inputs([("--output", a.output)], [("", r) for r in a.records])
        recs = [read_record(p) for p in a.records]
        if len({(r.n, tuple(r.names)) for r in recs}) > 1:
            raise BadInput("the records are of different models")
        kns = [known(r, a.set) for r in recs]
        n = recs[0].n
        for k in range(n):
            for nm in ("kt", "ratio" if recs[0].rotary[k] else "lead", "counts_per_rev", "j_rotor", "v_stribeck"):
                if nm + "_%d" % k not in kns[0]:
                    raise BadInput("%s: no %s_%d in the record: --set %s_%d=VALUE (SI)" % (a.records[0], nm, k, nm, k))
        fits = [fit_axis(recs, k, kns) for k in range(n)]
        if a.output:
            hg_output.check_writable(a.output)
    except (BadInput, hg_output.OutputError) as ex:
        log(ex)
        return 2
    out = ["# hexaglide identify (serial plant): %s" % ", ".join("%s (%d periods)" % (r.path, len(r.ok)) for r in recs),
           "# force balance per axis (docs/serial.md): kt 2 pi/lead i = M a + c_visc v + f_coulomb sgn v + "
           "f_breakaway exp(-(v/v_stribeck)^2) sgn v [+ net_weight]; zero-phase low-pass %g Hz (Butterworth "
           "order %d); periods slower than %g v_stribeck left out (%g without the breakaway), those at a hard stop "
           "or a tripped limit switch (the balance has no stop force) and those with the drive at its bus voltage"
           % (CUTOFF_HZ, ORDER, SLOW, SLOW_NO_BREAKAWAY)]
    for r in recs:              # left out, and said: an E-STOP or a fault on the way
        if not r.ok.all():
            out.append("# %s: %d of %d periods with the amplifiers off or the fault latched (the first at line %d): "
                       "left out" % (r.path, int((~r.ok).sum()), len(r.ok), r.hdr_no + 1 + int(np.argmax(~r.ok))))
    spec = {}
    for k, (est, info) in enumerate(fits):
        rot = recs[0].rotary[k]
        kn = kns[0]
        out.append("# axis %d: %d periods, residual RMS %.3g %s, correlation time %.1f periods (sigmas include "
                   "it), condition number %.1f; known: kt %g, %s, counts_per_rev %g, j_rotor %g, v_stribeck %g"
                   % (k, info["rows"], info["rms"], "N m" if rot else "N", info["tau"], info["cond"],
                      kn["kt_%d" % k], ("ratio %g" % kn["ratio_%d" % k]) if rot else ("lead %g m" % kn["lead_%d" % k]),
                      kn["counts_per_rev_%d" % k], kn["j_rotor_%d" % k], kn["v_stribeck_%d" % k]))
        if info["stop"] or info["limit"]:
            out.append("# axis %d: %s: the force balance has no stop force"
                       % (k, stop_words(info, recs[0].stops[k], rot)))
        if info["bus"]:
            out.append("# axis %d: %d periods with the drive at its bus voltage (r_winding i + back-EMF + l_winding "
                       "di/dt at v_bus %g V): the current moves within them, the record holds the last; with the "
                       "filter's response time around them, %d periods left out that were usable otherwise"
                       % (k, info["bus"], kn["v_bus_%d" % k], info["bus_out"]))
        if info["substeps"] > 1:
            out.append("# axis %d: velocity mode, %d substeps a period: the period's mean current modelled from its "
                       "last (%s); the model's residual, up to about 1 %% of M (docs/serial.md), is not in the sigmas"
                       % (k, info["substeps"], "the rotor relaxing behind the flexible train" if info["flexible"]
                          else "M and c from %d fits" % info["fits"]))
        elif info["flexible"]:
            out.append("# axis %d: %s mode behind a flexible train (k_axial %g %s): fitted as a rigid one (the encoder "
                       "counts the motor, the load follows it within force / k_axial); the model's residual, growing "
                       "as 1 / k_axial (0.01 %% of M and c_visc at 1.5e8 N/m, 0.2 %% and 1.3 %% at 2e6 N/m: "
                       "docs/serial.md), is not in the sigmas"
                       % (k, "velocity" if kn["amp_mode_%d" % k] == 1.0 else "torque", kn["k_axial_%d" % k],
                          "N m/rad" if rot else "N/m"))
        M, sM = est["M"]
        out.append("M_%d = %.6g ± %.2g %s   # reflected total: the load and the rotor, %s + j_rotor %s"
                   % (k, M, sM, unit(rot, "M"), "inertia" if rot else "mass",
                      "ratio^2" if rot else "(2 pi/lead)^2"))
        load = "inertia" if rot else "mass"
        mval = M - info["j_refl"]
        out.append("%s_%d = %.6g ± %.2g %s   # M less the known rotor (%.6g)" % (load, k, mval, sM, unit(rot, load), info["j_refl"]))
        spec["%s_%d" % (load, k)] = mval
        for nm in ("c_visc", "f_coulomb"):
            v, s = est[nm]
            out.append("%s_%d = %.6g ± %.2g %s" % (nm, k, v, s, unit(rot, nm)))
            spec["%s_%d" % (nm, k)] = v
        if "f_breakaway" in est:
            v, s = est["f_breakaway"]
            fc = est["f_coulomb"][0]
            out.append("f_breakaway_%d = %.6g ± %.2g %s   # f_static - f_coulomb" % (k, v, s, unit(rot, "f_breakaway")))
            out.append("f_static_%d = %.6g ± %.2g %s" % (k, fc + v, np.hypot(s, est["f_coulomb"][1]), unit(rot, "f_static")))
            spec["f_static_%d" % k] = fc + v
        else:
            out.append("# f_breakaway_%d not estimated: %d sliding periods near v_stribeck (exp(-(v/v_s)^2) > 0.05), "
                       "%d needed: the excitation never slides slowly" % (k, info["excited"], MIN_BREAKAWAY))
        if "net_weight" in est:
            v, s = est["net_weight"]
            g = info["g"]
            out.append("net_weight_%d = %.6g ± %.2g N   # mass g - counterbalance" % (k, v, s))
            cb = mval * g - v
            out.append("counterbalance_%d = %.6g ± %.2g N   # mass g - net_weight, g %g" % (k, cb, np.hypot(sM * g, s), g))
            spec["counterbalance_%d" % k] = cb
    refusals = physical_refusals(recs[0], kns[0], spec)
    if refusals:
        out.append("# not physically possible: %s (stderr says why); nothing written"
                   % ", ".join(n for names, _ in refusals for n in names))
    sys.stdout.write("\n".join(out) + "\n")
    if refusals:
        for _, m in refusals:
            log(m)
        log("the result is not physically possible: not written%s (exit 1)" % (" to %s" % a.output if a.output else ""))
        return 1
    if a.output:
        table = {x.name.decode(): x for x in hg.params_table(hg.plant_names().index("serial"), recs[0].variant)}
        lines = ["# hexaglide identify (serial plant) of %s: setp lines (HAL units)" % ", ".join(a.records)]
        for name, v in spec.items():
            e = table[name]
            lines.append("setp motenc-hexaglide.0.%s %.6g" % (e.hal_name.decode(), v * e.hal_scale))
        lines.append("# the same as [SERIAL] INI lines")
        lines.append("[SERIAL]")
        for name, v in spec.items():
            e = table[name]
            lines.append("%s = %.6g" % (e.ini_key.decode(), v * e.hal_scale))
        hg_output.atomic_write(a.output, lambda f: f.write(("\n".join(lines) + "\n").encode()))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
