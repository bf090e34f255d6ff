"""hg_identify_base.py - what identify's fits share, below all of them: the
rigid least squares (tools/hexaglide_identify.py), the drive trains'
(tools/hexaglide_trainid.py) and the serial plant's
(tools/hexaglide_identify_serial.py). The regressor's column names, the
DAC's output and the drive force per volt, the C record reader's bindings
(src/hg_record.h, src/hg_board_rec.h), how a run's usable stretches and
clamped periods are found, the fits' settings, and the residuals'
correlation time. It imports none of those three. tune reads its
recorded trajectories with the same record reader (record_columns)."""
import ctypes as C
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hexaglide as hg  # noqa: E402

_dp = np.ctypeslib.ndpointer(dtype=np.float64, flags="C_CONTIGUOUS")
_reg_column = hg._sig("hg_regressor_column", C.c_char_p, C.c_int, C.POINTER(C.c_char_p),
                      C.POINTER(C.c_int))


def _columns():
    """[(name, unit, carriage)] of the regressor's columns, in order (src/hg_regressor.c)."""
    out = []
    j = 0
    while True:
        unit, car = C.c_char_p(), C.c_int()
        name = _reg_column(j, C.byref(unit), C.byref(car))
        if name is None:
            return out
        out.append((name.decode(), unit.value.decode(), car.value))
        j += 1


COLUMNS = _columns()
NCOL = len(COLUMNS)


def column_name(j):
    """Display name of column j: 'm_head', 'm_drive[3]', 'c_visc[3]'."""
    n, _, k = COLUMNS[j]
    return n if k < 0 else "%s[%d]" % (n, k)


NAMES = [column_name(j) for j in range(NCOL)]
NIN = sum(1 for _, _, k in COLUMNS if k < 0)


def fric_col(name, k):
    """Index of friction column `name` ('c_visc', ...) of carriage k."""
    return NAMES.index("%s[%d]" % (name, k))


def params_copy(params):
    """A copy of an hg.Params."""
    p = hg.Params()
    C.memmove(p.buf, params.buf, C.sizeof(p.buf))
    return p


# ---------------------------------------------------------------- the DAC, the drive
_dac_output = hg._sig("hg_dac_output", C.c_double, C.c_double)


def dac_output(volts):
    """What the MOTENC-100's 13-bit DAC puts out for commanded volts (clamped to
    +-10 V, truncated to steps of 20/8191 V: on average 1.2 mV above the command;
    src/hg_sensors.c, the board's own model of it)."""
    v = np.asarray(volts, dtype=float)
    return np.vectorize(_dac_output, otypes=[float])(v)


def force_per_volt(params):
    """Drive force per DAC volt, N/V: ka kt 2 pi / lead (what a user must know beforehand)."""
    return params["ka"] * params["kt"] * 2 * np.pi / params["lead"]


# ---------------------------------------------------------------- the C record reader
class RecErr(C.Structure):
    _fields_ = [("code", C.c_int), ("line", C.c_long), ("column", C.c_long), ("field", C.c_int),
                ("msg", C.c_char * 320)]


rec_open = hg._sig("hg_record_open", C.c_int, C.c_void_p, C.c_char_p, C.c_size_t, C.POINTER(RecErr))
_rec_bind_plant = hg._sig("hg_board_rec_bind_plant", C.c_int, C.c_void_p, C.c_int, C.c_int, C.POINTER(RecErr))
rec_next = hg._sig("hg_record_next", C.c_int, C.c_void_p, _dp, C.POINTER(RecErr))
REC_MAGICS = hg.RECORD_MAGICS   # the formats identify reads
REC_BYTES = 1 << 16           # room for the reader's struct (hg_record: 12,352 bytes on x86-64)


class RecEvent(C.Structure):
    """hg_board_rec_event: one parameter event of a format-2 record (src/hg_board_rec.h)."""
    _fields_ = [("entry", C.c_uint), ("value", C.c_double), ("at", C.c_ulong)]


rec_event_of = hg._sig("hg_board_rec_event_of", C.c_int, C.c_double, C.c_double, C.c_double, C.c_ulong,
                        C.POINTER(RecEvent))


def rec_bind(r, header, first_row):
    """Every column of the board's record table for the record's plant and
    model variant (its first row's in.plant, in.model; format 1: the
    Hexaglide) needed in the opened reader r and checked as its pin's type
    on every row, as `hexaglide replay` checks them (src/hg_board_rec_read.h):
    None, or the reader's message. Without a first row (or with one the
    reader will refuse) nothing is bound: the reading says what is wrong."""
    try:
        f = first_row.split(b",")
        variant = int(float(f[header.index("in.model")]))
        plant = int(float(f[header.index("in.plant")])) if "in.plant" in header else 0
    except (ValueError, IndexError):
        return None
    e = RecErr()
    return e.msg.decode(errors="replace") if _rec_bind_plant(r, plant, variant, C.byref(e)) else None


class RecordError(Exception):
    """A record file that cannot be read (the message names the file, line and cause)."""


def record_bytes(path):
    """A record file's bytes, read whole; RecordError naming the path and the cause."""
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError as ex:
        raise RecordError("%s: cannot read it: %s; give a record file" % (path, ex.strerror or ex))


def record_columns(path, need, why_missing, optional=(), data=None):
    """The columns need of a record of tools/hg_record.py (docs/replay.md)
    through the C reader (src/hg_record.c), every column typed as its pin on
    every row and every sample in turn, as `hexaglide replay` reads it:
    (rows: the columns need, then those of optional the header has; header;
    the header's line number; the format-2 parameter events [(entry, value,
    period)], in the record's order). data: the file's bytes when the caller
    has read them (record_bytes), else the file is read here. RecordError naming
    the line and the cause: an unreadable file, the reader's refusal, or the
    first column of need the header lacks (why_missing: what that means)."""
    if data is None:
        data = record_bytes(path)
    r = C.create_string_buffer(REC_BYTES)
    e = RecErr()
    if rec_open(r, data, len(data), C.byref(e)):
        raise RecordError("%s: %s" % (path, e.msg.decode(errors="replace")))
    lines = data.split(b"\n", 64)
    hdr_no = next(i for i, l in enumerate(lines) if l.startswith(b"sample,")) + 1
    header = lines[hdr_no - 1].decode().rstrip("\r").split(",")
    for name in need:
        if name not in header:
            raise RecordError("%s: line %d, column %d (the header): no column '%s': %s"
                              % (path, hdr_no, len(lines[hdr_no - 1]) + 1, name, why_missing))
    first = lines[hdr_no].split(b"\n", 1)[0].rstrip(b"\r") if len(lines) > hdr_no else b""
    why = rec_bind(r, header, first)
    if why:
        raise RecordError("%s: %s" % (path, why))
    slots = [[header.index("in.pev-%d-%s" % (k, part)) for part in ("entry", "value", "age")]
             for k in range(2) if "in.pev-%d-entry" % k in header]
    cols = [header.index(x) for x in need] + [header.index(x) for x in optional if x in header]
    row = np.zeros(len(header) + 8)
    out, events = [], []
    while True:
        rc = rec_next(r, row, C.byref(e))
        if rc == 0:
            break
        if rc < 0:
            raise RecordError("%s: %s" % (path, e.msg.decode(errors="replace")))
        for c_entry, c_value, c_age in slots:
            ev = RecEvent()
            if rec_event_of(row[c_entry], row[c_value], row[c_age], len(out), C.byref(ev)):
                events.append((ev.entry, ev.value, ev.at))
        out.append(row[cols].copy())
    return np.array(out).reshape(-1, len(cols)), header, hdr_no, events


# ---------------------------------------------------------------- a run's stretches
class Settings:
    """How recordings become equations (the defaults are docs/identification.md's)."""
    cutoff_hz = 10.0          # zero-phase low-pass of the equations (parallel filter of Y and F) before decimation
    diff_ratio = 1.0          # positions (counts) are differentiated after a low-pass at diff_ratio x cutoff
    order = 4                 # Butterworth order (filtfilt doubles it, zero phase)
    source = "counts"         # counts: encoder counts only (as on a real machine); state: a board record's exact z, z'
    slow_mps = 0.002          # rows of a carriage slower than this are left out (stick: friction unknown)
    slow_window = 3.0         # ... and within this many cutoff periods of such a moment
    margin_s = 0.3            # trimmed at both ends of every usable stretch (filter transients)
    timing = "auto"           # start / mid: where the volts of a period act (auto: the record's integrator; mid)
    second_cutoff = 1.5       # a second fit at this x cutoff: the difference is the cutoff's cost, in the sigmas
    stribeck_band = 2.5       # below this many v_stribeck a carriage may stick and slip
    stick_s = 0.015           # breakaway: a carriage whose count has not changed for this long is stuck
    event_s = 0.06            # ... and is simulated from there for at most this long
    event_check_s = (0.04, 0.1)  # ... and, as a check of the model, this long: the differences join the sigma
    huber_counts = 5.0        # ... its position error (counts) weighs quadratically up to this, linearly beyond
    boot = 200                # ... block bootstrap replicates over the slow stretches, their spread
    same_motion_m = 1e-3      # ... times sqrt(stretches / distinct motions): stretches with an event
    same_motion_mps = 5e-3    # ... starting with every carriage within this (m) and this (m/s) of
    #                           another's are one motion (a program's repeats: not independent)
    draws = 16                # ... draws of the other estimates (their uncertainty in the breakaway's)


def butter_lp(s, dt, hz=None):
    """Butterworth low-pass coefficients (b, a) at hz (default the cutoff) for period dt."""
    from scipy.signal import butter
    return butter(s.order, (hz or s.cutoff_hz) * 2 * dt)


def dilate(mask, n):
    """mask true within n samples of a true sample."""
    if n <= 0 or not mask.any():
        return mask
    k = np.ones(2 * n + 1)
    return np.convolve(mask.astype(float), k, mode="same") > 0


def cutoff_floor(run, s):
    """The lowest cutoff (Hz) whose filtering fits in run at all: usable_stretches needs ten
    decimated samples (four per cutoff period: 2.5 / cutoff s) beside the two margin_s margins
    of a stretch; inf when the run is shorter than its margins."""
    room = len(run.ok) - 2 * int(round(s.margin_s / run.dt)) - 3
    return 2.5 / (room * run.dt) if room > 0 else float("inf")


def usable_stretches(run, s):
    """Contiguous usable stretches (i0, i1) of a run, long enough for the filters."""
    dt = run.dt
    dec = max(1, int(1.0 / (4 * s.cutoff_hz * dt)))
    edge = int(round(s.margin_s / dt))
    idx = np.flatnonzero(run.ok)
    pieces = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1) if len(idx) else []
    return [(seg[0], seg[-1]) for seg in pieces if len(seg) >= 2 * edge + 10 * dec + 3]


def clamped_periods(run, params):
    """Periods whose drive current is (nearly) at the amplifier's limit: force unknown."""
    return np.abs(params["ka"] * dac_output(run.volts)) >= 0.98 * params["i_max"]


def autocorr_time(r, maxlag=200):
    """Integrated autocorrelation time of a residual series (samples; 1 = white):
    1 + 2 sum of the autocorrelation up to its first non-positive value."""
    r = r - r.mean()
    v = np.dot(r, r)
    if v == 0 or len(r) < 10:
        return 1.0
    tau = 1.0
    for lag in range(1, min(maxlag, len(r) // 4)):
        rho = np.dot(r[:-lag], r[lag:]) / v
        if rho <= 0:
            break
        tau += 2 * rho
    return tau
