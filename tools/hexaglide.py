"""hexaglide.py - the virtual Hexaglide's C core from Python (ctypes).

The same code the LinuxCNC modules run, built as build/libhexaglide.so
(`make lib`; `make` builds it too). See docs/python.md.

    import hexaglide as hg
    z = hg.ik([0, 0, -50, 8, -6, 10])             # joints (mm) of a pose (mm, deg)
    pose = hg.fk(z)                               # and back
    m = hg.Model("reduced-cartesian")             # the dynamics, SI inside
    m.step([1.0] * 6, 0.001)                      # one step with six DAC volts
    loop = hg.Loop()                              # six LinuxCNC pids + the board
    res = loop.run(cmd_mm)                        # cmd_mm: (n, 6) joint commands
    res.ferror_mm, res.output_v, res.peak_ferror_mm

Units at this interface are the user's (mm, degrees, volts) except Model,
which is the core's own (m, rad, s) as in src/hg_dynamics.h.
"""
import configparser
import copy
import ctypes as C
import decimal
import difflib
import fractions
import functools
import math
import os
import re
import reprlib

import numpy as np

import hg_csv  # (numbers as the C tools read them; pure Python, imports no tool)

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_INI = os.path.normpath(os.path.join(HERE, "..", "configs", "hexaglide.ini"))
BUILT_LIB = os.path.normpath(os.path.join(HERE, "..", "build", "libhexaglide.so"))   # `make lib`'s
LIB_PATH = os.environ.get("HEXAGLIDE_LIB") or BUILT_LIB    # (HEXAGLIDE_LIB empty: not set)
_LIB_WHENCE = ("HEXAGLIDE_LIB=%s" % LIB_PATH if os.environ.get("HEXAGLIDE_LIB") else LIB_PATH)
_LIB_REMEDY = "run `make lib` in %s%s" % (os.path.dirname(os.path.dirname(BUILT_LIB)), (
    " (it builds %s), or unset HEXAGLIDE_LIB to load that one" % BUILT_LIB if os.environ.get("HEXAGLIDE_LIB") else ""))
JOINTS = 6
RECORD_MAGICS = (b"# hexaglide-record 1", b"# hexaglide-record 2")   # line 1 of a record, per format (docs/replay.md)
MODELS = ["standard", "reduced-joints", "reduced-cartesian", "fused-cartesian"]

try:
    _lib = C.CDLL(LIB_PATH)
except OSError as ex:  # pragma: no cover - a message the user can act on
    raise ImportError("cannot load %s (%s): %s" % (_LIB_WHENCE, ex, _LIB_REMEDY)) from None

_d6 = C.c_double * 6
_P = C.c_void_p


class HexaglideError(RuntimeError):
    """A core function returned a negative code (src/hg_errors.h)."""

    def __init__(self, what, code, detail=""):
        self.code = code
        super().__init__("%s: %s (code %d)%s" % (what, strerror(code), code, ": " + detail if detail else ""))


def _sig(name, res, *args):
    """The library's function name with its C signature (restype res, argtypes args), else
    ImportError: the library loaded lacks it (another library, or one built from other sources)."""
    try:
        f = getattr(_lib, name)
    except AttributeError:
        raise ImportError("%s has no function %s: it is not this project's libhexaglide.so, or one built from "
                          "older sources; %s" % (_LIB_WHENCE, name, _LIB_REMEDY)) from None
    f.restype = res
    f.argtypes = list(args)
    return f


_strerror = _sig("hg_strerror", C.c_char_p, C.c_int)


def strerror(code):
    """Text of an error code."""
    return _strerror(code).decode()


def _vector(name, values, n, finite=False, what=""):
    """values as a float64 array of exactly n numbers (n None: of any length), else TypeError
    (not numbers: _real_array's reason) or ValueError naming the argument, the length expected
    and the length got; finite: also ValueError naming the first entry that is NaN or infinite.
    what: the n values' meaning, for the message ("X Y Z (mm) A B C (deg)")."""
    try:
        v = _real_array(values)
    except TypeError as ex:
        raise TypeError("%s must be %snumbers%s, got %s: %s" % (name, "" if n is None else "%d " % n, " (%s)" % what
                                                              if what else "", reprlib.repr(values), ex)) from None
    if v.ndim != 1 or (n is not None and v.shape[0] != n):
        got = "%d values" % v.shape[0] if v.ndim == 1 else "shape %s" % (v.shape,)
        raise ValueError("%s needs %s%s, got %s" % (name, "%d values" % n if n is not None else "a vector of values",
                                                    " (%s)" % what if what else "", got))
    if finite and not np.isfinite(v).all():
        i = int(np.argmin(np.isfinite(v)))
        raise ValueError("%s[%d] = %r is not finite" % (name, i, float(v[i])))
    return v


def _real(name, value, unit=""):
    """value as a float (a Python or numpy integer or float, not a bool, a string or a complex),
    else TypeError naming the argument; ValueError naming it for an int beyond a float's range
    (float() would raise a bare OverflowError)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError("%s must be a number%s, got %r" % (name, " (%s)" % unit if unit else "", value))
    try:
        return float(value)
    except OverflowError:                      # (Decimal prints an int of any length in short)
        raise ValueError("%s = %s: beyond a float's range (at most about 1.8e308 in magnitude); give a finite "
                         "number%s" % (name, "{:.6g}".format(decimal.Decimal(value).normalize()),
                                       " (%s)" % unit if unit else ""))


def _param_value(name, value, unit):
    """value of the parameter name as a finite float, else TypeError (not a number, _real) or
    ValueError (NaN or infinite: hg_params_set's rule, for every plant's parameters)."""
    v = _real(name, value, unit)
    if not math.isfinite(v):
        raise ValueError("%s = %r: not finite; a parameter is a finite number (%s)" % (name, value, unit))
    return v


def _param_name(name):
    """name (a parameter's spec name) as str, else TypeError."""
    if not isinstance(name, str):
        raise TypeError("a parameter is named by its spec name, a str (params_table()), got %r" % (name,))
    return name


def _real_array(values):
    """values as a float64 array when they are real numbers (ints or floats, of any shape), else
    TypeError saying why: numpy would read the strings '1.5' as numbers, cut complex ones to their
    real part and take a bool among numbers ([True, 0.5]) as 1 or 0."""
    try:
        v = np.asarray(values)
    except (TypeError, ValueError):
        raise TypeError("not an array of numbers") from None
    if v.dtype.kind not in "iuf":
        raise TypeError("ints or floats expected, got %s (numpy dtype %s)" % (
            {"U": "strings", "S": "bytes", "c": "complex numbers", "b": "bools"}.get(v.dtype.kind, "other objects"),
            v.dtype))
    if not isinstance(values, np.ndarray):    # (a list's bools became numbers above: look at its items)
        flat = values if v.ndim == 1 and isinstance(values, (list, tuple)) else \
            np.asarray(values, dtype=object).reshape(-1)      # (a flat list, per period: looked at as it is)
        kinds = set(map(type, flat))
        if bool in kinds or np.bool_ in kinds:
            raise TypeError("a bool (True or False) is not a number here: give 1 or 0")
    return v.astype(np.float64)


def _whole(name, value, unit=""):
    """value as an int (a Python or numpy integer), else TypeError naming the argument."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError("%s must be a whole number%s (an int), got %r%s" % (
            name, " of " + unit if unit else "", value,
            ": give int(round(x))" if isinstance(value, (float, np.floating)) else ""))
    return int(value)


def _c_range(ctype):
    """(least, greatest) integer a ctypes integer type carries; ctypes wraps any other silently
    (2**64 + 1000000 stored in a C long is 1000000)."""
    bits = 8 * C.sizeof(ctype)
    if ctype(-1).value < 0:
        return -(1 << (bits - 1)), (1 << (bits - 1)) - 1
    return 0, (1 << bits) - 1


def _whole_why(name, value, ctype, why_refused, unit=""):
    """(value as an int, else TypeError; why the core refuses it, or None).
    why_refused(v) asks the core's own check about v, a value ctype carries, and returns its
    reason for refusing v, or None. A value ctype cannot carry must never reach the core
    (ctypes would wrap it), so it is always refused; its reason is the one the core gives for
    the type's extreme on the value's side (or for the other extreme, when the core takes
    that one: -1 for an unsigned field), which states the core's own range. Only when the
    core takes both extremes (it has no range of its own) is the type's range the reason."""
    v = _whole(name, value, unit)
    lo, hi = _c_range(ctype)
    if lo <= v <= hi:
        return v, why_refused(v)
    near, far = (lo, hi) if v < lo else (hi, lo)
    return v, (why_refused(near) or why_refused(far) or
               "beyond what the C type (ctypes.%s) carries, %d..%d" % (ctype.__name__, lo, hi))


def _refusal(name, v, why, unit=""):
    """The message of a refused whole number: its name, the value as given and the rule."""
    return "%s = %d%s: %s" % (name, v, " " + unit if unit else "", why)


def _whole_checked(name, value, ctype, why_refused=lambda v: None, unit=""):
    """value as an int the core takes (_whole_why), else TypeError (not an int) or ValueError
    naming the argument, the value as given and the rule it breaks."""
    v, why = _whole_why(name, value, ctype, why_refused, unit)
    if why:
        raise ValueError(_refusal(name, v, why, unit))
    return v


def _name(arg, value, choices):
    """value as bytes of a name (str), else TypeError naming the argument and the choices."""
    if not isinstance(value, str):
        raise TypeError("%s must be a name (str), one of %s; got %r" % (arg, choices, value))
    return value.encode()


class _Record(C.Structure):
    """A C struct mirrored by ctypes, whose instances take only its fields (and the names in
    _own) as attributes: ctypes keeps any other name as a Python attribute that never reaches
    the C code, so a typo (b.inputs.estop_buton = 1) or a name the struct lacks
    (b.inputs.period_ns = 0) did nothing; it raises AttributeError naming the nearest fields."""
    _own = ()

    def __init_subclass__(cls, **kw):
        super().__init_subclass__(**kw)
        cls._fields = [n for k in reversed(cls.__mro__) for n, *_ in k.__dict__.get("_fields_", ())]
        cls._settable = frozenset(cls._fields) | frozenset(cls._own)

    def __setattr__(self, name, value):
        if name not in self._settable:
            near = difflib.get_close_matches(name, self._fields, 3, 0.6)
            raise AttributeError("%s has no field %r; %s (ctypes would keep another name as a Python attribute "
                                 "that never reaches the C struct)" % (type(self).__name__, name, "did you mean %s?" % (
                                     " or ".join(map(repr, near))) if near else "its fields: " + ", ".join(self._fields)))
        C.Structure.__setattr__(self, name, value)


class PidGains(_Record):
    """hg_pid_gains: the pid.N pins (names as LinuxCNC's, units mm and V)."""
    _fields_ = [(n, C.c_double) for n in
                ("pgain", "igain", "dgain", "bias", "ff0", "ff1", "ff2", "ff3", "deadband",
                 "maxerror", "maxerror_i", "maxerror_d", "maxcmd_d", "maxcmd_dd", "maxcmd_ddd",
                 "maxoutput")] + [("error_previous_target", C.c_int)]


CHANNELS_MAX = 8            # HG_CHANNELS_MAX: the MOTENC-100's channels, the most any plant uses
_dc = C.c_double * CHANNELS_MAX
BIQUAD_NOTCH = 2            # biquad.N.type of a notch (src/hg_biquad.h)


class Biquad(_Record):
    """hg_biquad: one biquad.N of LinuxCNC's biquad component, its pins and parameters (src/hg_biquad.h)."""
    _fields_ = [("in_", C.c_double), ("out", C.c_double), ("enable", C.c_int), ("valid", C.c_int),
                ("type", C.c_uint), ("f0", C.c_double), ("Q", C.c_double)] + \
        [(n, C.c_double) for n in ("d1", "d2", "n0", "n1", "n2", "s1", "s2")] + [("last_enable", C.c_int)]


class LoopConfig(_Record):
    """hg_loop_config."""
    _fields_ = [("pid", PidGains * CHANNELS_MAX), ("biquad", Biquad * CHANNELS_MAX), ("input_scale", _dc),
                ("output_scale", _dc), ("output_offset", _dc), ("ferror_limit_mm", C.c_double),
                ("period_ns", C.c_long), ("plant", C.c_int), ("variant", C.c_int)]


class LoopSummary(_Record):
    """hg_loop_summary."""
    _fields_ = [("peak_ferror_mm", _dc), ("peak_output_v", _dc), ("rms_ferror_mm", _dc),
                ("peak_tool_error_mm", C.c_double), ("periods", C.c_long), ("tripped_at", C.c_long)]


class LoopCheckReport(_Record):
    """hg_loop_check_report: the field hg_loop_config_check refused."""
    _fields_ = [("joint", C.c_int), ("component", C.c_char_p), ("field", C.c_char_p), ("ini_key", C.c_char_p),
                ("why", C.c_char_p), ("value", C.c_double)]


class PidSetting(_Record):
    """hg_pid_setting: one pid.N setting (pin name, INI key, offset in hg_pid_gains, rule)."""
    _fields_ = [("pin", C.c_char_p), ("ini_key", C.c_char_p), ("offset", C.c_ulong), ("kind", C.c_int)]


_board_sizeof = _sig("hg_loop_sizeof", C.c_ulong, C.c_int)
_hexaglide_sizeof = _sig("hg_hexaglide_sizeof", C.c_ulong, C.c_int)


def _sizeof(which):
    """sizeof of the board's (hg_loop_sizeof) or the Hexaglide's (4, 5, 6, 12) types."""
    return _hexaglide_sizeof(which) if which in (4, 5, 6, 12) else _board_sizeof(which)


class GuardReport(_Record):
    """hg_guard_report: the mechanical limit a failed step crossed (src/hg_guard.h)."""
    _fields_ = [("kind", C.c_int), ("bar", C.c_int), ("other", C.c_int), ("value", C.c_double),
                ("limit", C.c_double)]


_DATA_STATE = [("t_s", C.c_double), ("z_m", _d6), ("zd_mps", _d6), ("zdd_mps2", _d6),
               ("pose", _d6), ("posed", _d6), ("bar_rad", C.c_double * 12),
               ("bar_radps", C.c_double * 12), ("current_a", _d6), ("vloop_int_m", _d6),
               ("amp_enabled", C.c_uint), ("stuck", C.c_uint), ("fric_n", _d6), ("force_n", _d6),
               ("residual_m", C.c_double), ("last_error", C.c_int), ("guard", GuardReport),
               ("broken_bars", C.c_uint), ("zr_m", _d6), ("zrd_mps", _d6),
               ("trig_key_rad", C.c_double * 3), ("trig_sc", _d6), ("trig_valid", C.c_int)]


class _DataState(_Record):
    _fields_ = _DATA_STATE


class Data(_Record):
    """hg_data: the dynamics state (SI), then hg_step's scratch (opaque, hg_work)."""
    _fields_ = _DATA_STATE + [("work", C.c_double * max(0, (_sizeof(5) - C.sizeof(_DataState)) // 8))]


for _i, _s in ((1, LoopConfig), (2, LoopSummary), (3, PidGains), (5, Data), (12, _DataState), (13, Biquad),
               (14, LoopCheckReport), (15, PidSetting)):
    if _sizeof(_i) != C.sizeof(_s):
        raise ImportError("%s: layout differs from the library's (%d vs %d bytes): rebuild both"
                          % (_s.__name__, C.sizeof(_s), _sizeof(_i)))

DEFAULT_INTEGRATOR = _sig("hg_integrator_default", C.c_int)()  # the board's scheme at load
_integrator_name = _sig("hg_integrator_name", C.c_char_p, C.c_int)
_integrator_from_name = _sig("hg_integrator_from_name", C.c_int, C.c_char_p)
_scheme_tableau = _sig("hg_scheme_tableau", C.c_int, C.c_int, C.POINTER(C.POINTER(C.c_double)),
                       C.POINTER(C.POINTER(C.c_double)))


def _integrators():
    """The board's scheme names by number: hg_integrator_name's up to the first it has none for."""
    names = []
    while _integrator_name(len(names)) is not None:
        names.append(_integrator_name(len(names)).decode())
    return names


INTEGRATORS = _integrators()


def integrator_name(integrator):
    """The board's name of a time integration scheme ("improved-euler", "heun", "rk4"), else
    TypeError (not an int) or ValueError naming the schemes."""
    i = _whole_checked("integrator", integrator, C.c_int, lambda v: None if _integrator_name(v) is not None else
                       "not one of the board's schemes (%s)" % ", ".join(
                           "%d %s" % (k, n) for k, n in enumerate(INTEGRATORS)))
    return _integrator_name(i).decode()


def integrator_id(name):
    """The board's number of the scheme named name (hg_integrator_from_name), else ValueError."""
    i = _integrator_from_name(name.encode())
    if i < 0:
        raise ValueError("integrator %r: not one of the board's schemes (%s)"
                         % (name, ", ".join(INTEGRATORS)))
    return i


def integrator_stages(integrator):
    """The accelerations one step of the scheme evaluates: its Runge-Kutta stages
    (hg_scheme_tableau), one for improved Euler."""
    integrator_name(integrator)          # a scheme of the board's, else TypeError or ValueError
    c, b = C.POINTER(C.c_double)(), C.POINTER(C.c_double)()
    return max(1, _scheme_tableau(int(integrator), C.byref(c), C.byref(b)))


PLANT_PARAMS_MAX = 256      # HG_PLANT_PARAMS_MAX
PLANT_EXTRA_MAX = 16        # HG_PLANT_EXTRA_MAX
PLANT_INJECT_MAX = 4        # HG_PLANT_INJECT_MAX


class BoardParams(_Record):
    """hg_board_params: the plant's parameters (SI, entry i of its table at plant[i]), substeps, integrator.
    origin: (plant, model variant, the call) of a block Params.board_params or PlantParams.board_params
    made, whose entries are that plant's table's; None for one built otherwise (its plant unknown)."""
    _fields_ = [("plant", C.c_double * PLANT_PARAMS_MAX), ("substeps", C.c_uint), ("integrator", C.c_uint)]
    _own = ("origin",)
    origin = None


class PlantReport(_Record):
    """hg_plant_report: what a failed step struck (the plant describes it)."""
    _fields_ = [("kind", C.c_int), ("channel", C.c_int), ("other", C.c_int), ("value", C.c_double),
                ("limit", C.c_double)]


_e8i, _e8d, _e8u = C.c_int * 8, C.c_double * 8, C.c_uint * 8


class BoardInputs(_Record):
    """hg_board_inputs: one servo period's inputs (src/hg_board.h)."""
    _fields_ = [("dac_v", _e8d), ("dac_written", C.c_int), ("dac_stale", C.c_int), ("dout_values", C.c_uint),
                ("dout_inverts", C.c_uint), ("estop_loop_out", C.c_int), ("estop_button", C.c_int),
                ("reset", C.c_int), ("watchdog_control", C.c_uint), ("watchdog_reset", C.c_int),
                ("index_enable", _e8i), ("enc_reset", _e8i), ("enc_scale", _e8d), ("adc_read", C.c_int),
                ("adc_gain", _e8d), ("adc_offset", _e8d), ("adc_volts_per_amp", C.c_double),
                ("amp_fail", _e8i), ("stuck", _e8u), ("tripped", _e8u), ("index_lost", _e8i),
                ("enc_glitch", _e8i), ("inject", _e8u), ("pos_cmd", _e8d), ("params", BoardParams)]


class BoardOutputs(_Record):
    """hg_board_outputs: one servo period's outputs (src/hg_board.h)."""
    _fields_ = [("count", _e8i), ("position", _e8d), ("index", _e8i), ("index_latched", _e8i),
                ("enc_scale", _e8d), ("in_", C.c_ubyte * 68), ("dout_word", C.c_uint), ("estop_in", C.c_int),
                ("adc", _e8d), ("channels", C.c_int), ("rotary", C.c_uint), ("pos", _e8d), ("vel", _e8d),
                ("motor_pos", _e8d), ("volts", _e8d), ("current_a", _e8d), ("force", _e8d),
                ("extra", C.c_double * PLANT_EXTRA_MAX), ("tool_error", C.c_double), ("sim_time_s", C.c_double),
                ("steps", C.c_uint), ("fault", C.c_int), ("fault_code", C.c_int),
                ("fault_report", PlantReport), ("amps_on", C.c_int), ("watchdog_expired", C.c_int),
                ("param_error", C.c_int), ("dac_nan", C.c_int), ("params", BoardParams), ("events", C.c_uint),
                ("refused", C.c_ulonglong * 5), ("param_rc", C.c_int), ("reset_refused_channel", C.c_int),
                ("reset_refused_injection", C.c_int), ("fault_cause", C.c_int),
                ("injected", C.c_uint * PLANT_INJECT_MAX), ("dac_nan_new", C.c_uint),
                ("enc_scale_bad", C.c_uint), ("enc_scale_odd", C.c_uint), ("substeps_run", C.c_uint), ("stiff_param", C.c_int),
                ("stiff_dt_max_s", C.c_double), ("stiff_value", C.c_double), ("stiff_integrator", C.c_int),
                ("adc_nan_new", C.c_uint), ("pos_cmd_bad_new", C.c_uint), ("estop_loop_out", C.c_int),
                ("adc_volts_per_amp", C.c_double)]

    @property
    def pose(self):
        """The Hexaglide's head pose (SI: m, rad): its first six plant outputs."""
        return self.extra[:6]


for _i, _s in ((7, BoardParams), (9, BoardInputs), (10, BoardOutputs)):
    if _sizeof(_i) != C.sizeof(_s):
        raise ImportError("%s: layout differs from the library's (%d vs %d bytes): rebuild both"
                          % (_s.__name__, C.sizeof(_s), _sizeof(_i)))

_board_init = _sig("hg_board_init", C.c_int, _P, C.c_int, C.c_int, _P)
_board_params_check = _sig("hg_board_params_check", C.c_int, _P, _P, _P, _P)
_board_params_default = _sig("hg_board_params_default", C.c_int, C.c_int, C.c_int, C.POINTER(BoardParams))
_plant_find = _sig("hg_plant_find", C.c_int, C.c_char_p)
_plant_variant_named = _sig("hg_plant_variant_named", C.c_int, C.c_int, C.c_char_p)
_board_inputs_default = _sig("hg_board_inputs_default", None, _P, C.POINTER(BoardInputs))
_board_peek = _sig("hg_board_peek", None, _P, C.POINTER(BoardOutputs))
_board_step = _sig("hg_board_step", None, _P, C.POINTER(BoardInputs), C.POINTER(BoardOutputs), C.c_long)
_params_default = _sig("hg_params_default", None, _P)
_params_set = _sig("hg_params_set", C.c_int, _P, C.c_char_p, C.c_double)
_params_field = _sig("hg_params_field", C.POINTER(C.c_double), _P, C.c_char_p)
_params_check_kinematics = _sig("hg_params_check_kinematics", C.c_int, _P, _P, _P)
_model_init = _sig("hg_model_init", C.c_int, _P, _P, C.c_int, C.POINTER(C.c_char_p), C.POINTER(C.c_char_p))
_model_from_name = _sig("hg_model_from_name", C.c_int, C.c_char_p)
_data_reset = _sig("hg_data_reset", C.c_int, _P, _P)
_step = _sig("hg_step", C.c_int, _P, _P, _d6, C.c_double)
STEP_DT_MAX_S = _sig("hg_step_dt_max_s", C.c_double)()   # HG_DT_MAX_S: the longest step hg_step takes
_ERR_BAD_PARAM = -7                                       # HG_ERR_BAD_PARAM (src/hg_errors.h): a parameter refused
_ERR_BAD_DT = -10                                         # HG_ERR_BAD_DT: hg_step's dt refused
_ERR_STIFF = -16                                          # HG_ERR_STIFF: a step the scheme cannot integrate


class _Stability(_Record):                                # hg_stability (src/hg_stability.h)
    _fields_ = [("substeps", C.c_uint), ("param", C.c_char_p), ("dt_max_s", C.c_double)]


_stability_check = _sig("hg_stability_check", C.c_int, _P, C.c_int, C.c_double, C.c_uint, C.c_uint,
                        C.POINTER(_Stability))
_energy = _sig("hg_energy", None, _P, _P, C.POINTER(C.c_double), C.POINTER(C.c_double))
_ik = _sig("hg_inverse_kinematics_guarded", C.c_int, _P, _d6, _d6, _P)
_fk = _sig("hg_forward_kinematics", C.c_int, _P, _d6, _d6, _P, _P)
_tool_offset_check = _sig("hg_tool_offset_check", C.c_int, _P, C.c_double)
_offset_to_op = _sig("hg_pose_offset_to_op", None, _d6, C.c_double, _d6)
_op_to_offset = _sig("hg_pose_op_to_offset", None, _d6, C.c_double, _d6)
_guard_check = _sig("hg_guard_check", C.c_int, _P, _d6, _d6, C.c_uint, C.POINTER(GuardReport))
_guard_describe = _sig("hg_guard_describe", None, C.POINTER(GuardReport), C.c_int, C.c_char_p)
_loop_default = _sig("hg_loop_config_default", None, C.POINTER(LoopConfig))
_loop_init = _sig("hg_loop_init", C.c_int, _P, C.POINTER(LoopConfig), _P)
_loop_step = _sig("hg_loop_step", C.c_int, _P, _dc, _P)
_loop_check = _sig("hg_loop_config_check", C.c_int, C.POINTER(LoopConfig), C.POINTER(LoopCheckReport))
_plant_channels = _sig("hg_plant_channels_at", C.c_int, C.c_int, C.c_int)
_dp = np.ctypeslib.ndpointer(dtype=np.float64, flags="C_CONTIGUOUS")
_loop_run = _sig("hg_loop_run", C.c_int, _P, _dp, C.c_long, C.c_long, _P, _P, C.POINTER(LoopSummary))
_pid_inputs_check = _sig("hg_pid_inputs_check", C.c_long, _dp, C.c_long, C.POINTER(C.c_int))
_biquad_notch = _sig("hg_biquad_notch", None, C.POINTER(Biquad), C.c_double, C.c_double)
_biquad_response = _sig("hg_biquad_response", C.c_int, C.POINTER(Biquad), C.c_long, C.c_double,
                        C.POINTER(C.c_double), C.POINTER(C.c_double))
_batch_cores = _sig("hg_batch_cores", C.c_int)


class ParamInfo(_Record):
    """hg_param_info: one row of the parameter table (src/hg_params.h)."""
    _fields_ = [("name", C.c_char_p), ("unit", C.c_char_p), ("what", C.c_char_p), ("offset", C.c_ulong),
                ("hal_name", C.c_char_p), ("hal_unit", C.c_char_p), ("hal_scale", C.c_double),
                ("ini_key", C.c_char_p)]


_plant_nparams = _sig("hg_plant_nparams_at", C.c_int, C.c_int, C.c_int)
_plant_param = _sig("hg_plant_param_at", C.c_int, C.c_int, C.c_int, C.c_int, C.POINTER(ParamInfo))
_plant_defaults = _sig("hg_plant_defaults_at", C.c_int, C.c_int, C.c_int, _P)
_plant_name_at = _sig("hg_plant_name_at", C.c_char_p, C.c_int)
_plant_ini_section = _sig("hg_plant_ini_section_at", C.c_char_p, C.c_int)


def plant_names():
    """The registry's plants, by index: ["hexaglide", "serial"]."""
    out = []
    while _plant_name_at(len(out)):
        out.append(_plant_name_at(len(out)).decode())
    return out


def params_table(plant=0, variant=None):
    """A plant's parameter table (default the Hexaglide's): [ParamInfo] (spec name, SI unit, HAL name,
    HAL unit, HAL scale, INI key), units as the model variant (default the plant's) has them."""
    if variant is None:
        variant = _plant_variant_named(plant, None)
    out = []
    for i in range(_plant_nparams(plant, variant)):
        e = ParamInfo()
        _plant_param(plant, variant, i, C.byref(e))
        out.append(e)
    return out


def _unknown(name, names):
    """The message for a parameter name not in names: the closest one a typo explains (difflib)."""
    close = difflib.get_close_matches(str(name), names, 1, 0.8)
    return "%s: not a parameter of this plant and model%s (params_table lists them)" % (
        name, "; did you mean %r?" % close[0] if close else "")


BOARD_BIT_SUBSTEPS = PLANT_PARAMS_MAX           # HG_BOARD_BIT_SUBSTEPS: substeps' bit of a refused-field set
BOARD_BIT_INTEGRATOR = PLANT_PARAMS_MAX + 1     # HG_BOARD_BIT_INTEGRATOR: integrator's (src/hg_board.h)
_check_boards = {}                              # (plant, variant) -> a board of the plant's defaults


def _board_refusals(plant, variant, bp):
    """{bit: why} of every field of bp (a BoardParams) that hg_board_params_check refuses for a
    board of the plant and model: bit i below the plant's table length is parameter i, then
    BOARD_BIT_SUBSTEPS and BOARD_BIT_INTEGRATOR; {} when it takes them all."""
    if (plant, variant) not in _check_boards:            # (the check reads the board, never writes it)
        buf = C.create_string_buffer(_sizeof(8))
        if _board_init(buf, plant, variant, None):      # the plant's defaults: its checks
            raise ValueError("plant %s: cannot build its board" % plant_names()[plant])
        _check_boards[plant, variant] = buf
    bad = (C.c_ulonglong * 5)()                          # hg_bitset (HG_BITSET_BITS 320)
    why = (C.c_char_p * (PLANT_PARAMS_MAX + 2))()        # HG_BOARD_WHY_LEN
    if not _board_params_check(_check_boards[plant, variant], C.byref(bp), bad, why):
        return {}
    return {i: (why[i] or b"refused").decode() for i in range(PLANT_PARAMS_MAX + 2) if bad[i // 64] >> (i % 64) & 1}


def _board_setting(plant, variant, name, value):
    """substeps or integrator (name) as hg_board_params_check takes it for a board of the plant
    and model, else TypeError (not an int) or ValueError naming it, its value and its range."""
    bit = {"substeps": BOARD_BIT_SUBSTEPS, "integrator": BOARD_BIT_INTEGRATOR}[name]

    def why_refused(v):
        bp = BoardParams()
        _board_params_default(plant, variant, C.byref(bp))
        setattr(bp, name, v)
        return _board_refusals(plant, variant, bp).get(bit)
    return _whole_checked(name, value, C.c_uint, why_refused)


SUBSTEPS_MAX = 64                               # HG_SUBSTEPS_MAX: the most substeps the board runs a period
_BOARD_TEXT_LEN = 240                           # HG_BOARD_TEXT_LEN (src/hg_board.h)
_board_integrable = _sig("hg_board_integrable", C.c_int, _P, C.POINTER(BoardInputs), C.c_int, C.c_int,
                         C.POINTER(BoardParams), C.c_long, C.POINTER(BoardOutputs))
_enc_scale_fits = _sig("hg_board_enc_scale_fits", C.c_int, _P, C.c_int, C.c_double)
_describe_enc_scale = _sig("hg_board_describe_enc_scale", None, _P, C.c_int, C.c_double, C.c_char_p)
_describe_stiffness = _sig("hg_board_describe_stiffness", None, _P, C.POINTER(BoardOutputs), C.c_long, C.c_int,
                           C.c_char_p)
_stiff_remedy = _sig("hg_board_stiff_remedy", None, C.POINTER(BoardOutputs), C.c_char_p, C.c_char_p, C.c_char_p)
_board_params_verdicts = {}                     # (plant, variant, period_ns, bytes of bp) -> _board_params_refusal


def _refused_field(table, bp, bit, why):
    """"name = value unit: why" of the field of bp (a BoardParams) at bit (as _board_refusals
    numbers them) that the board refuses; table: the plant's params_table."""
    if bit < len(table):
        unit = table[bit].unit.decode()
        return "%s = %r%s: %s" % (table[bit].name.decode(), bp.plant[bit], " " + unit if unit else "", why)
    name = {BOARD_BIT_SUBSTEPS: "substeps", BOARD_BIT_INTEGRATOR: "integrator"}.get(bit)
    return _refusal(name, getattr(bp, name), why) if name else "plant[%d] = %r: %s" % (bit, bp.plant[bit], why)


def _stiffness(plant, variant, bp, period_ns):
    """None when a board of the plant and model built with the block bp (a BoardParams the
    board takes) integrates it at period_ns, else (code, why): HG_ERR_STIFF with the sentence of
    the board's stability check (hg_board_describe_stiffness: the parameter, its value, the
    scheme's longest stable step, the period) and what to change. The check is the core's
    hg_board_integrable, the one `hexaglide sim --set` makes before it runs."""
    buf = C.create_string_buffer(_sizeof(8))
    inputs, out = BoardInputs(), BoardOutputs()
    rc = _board_integrable(buf, C.byref(inputs), plant, variant, C.byref(bp), period_ns, C.byref(out))
    if rc == 0:
        return None
    if rc != _ERR_STIFF:
        return rc, "a board of these parameters cannot be built"
    text, remedy = C.create_string_buffer(_BOARD_TEXT_LEN), C.create_string_buffer(_BOARD_TEXT_LEN)
    _describe_stiffness(buf, C.byref(out), period_ns, 0, text)
    _stiff_remedy(C.byref(out), b"integrator", b"period_ns", remedy)
    return out.fault_code, "%s, even with %d substeps a period; give %s" % (
        text.value.decode(), SUBSTEPS_MAX, remedy.value.decode())


def _board_params_refusal(plant, variant, bp, period_ns):
    """None when a board of the plant and model takes the block bp (a BoardParams) and can
    integrate it at period_ns, else (code, why): HG_ERR_BAD_PARAM with each field
    hg_board_params_check refuses (name = value unit: rule), or _stiffness's. Cached per
    block, period and plant (a Job of a block already checked costs a lookup)."""
    key = (plant, variant, period_ns, bytes(bp))
    if key not in _board_params_verdicts:
        bad = _board_refusals(plant, variant, bp)
        if bad:
            table = params_table(plant, variant)
            verdict = _ERR_BAD_PARAM, "; ".join(_refused_field(table, bp, i, why) for i, why in sorted(bad.items()))
        else:
            verdict = _stiffness(plant, variant, bp, period_ns)
        if len(_board_params_verdicts) >= 1024:  # (a fit may try many blocks: keep the cache bounded)
            _board_params_verdicts.clear()
        _board_params_verdicts[key] = verdict
    return _board_params_verdicts[key]


@functools.lru_cache(maxsize=None)
def _table_of(plant, variant):
    """The plant's parameter table under the model variant, (name, unit) per entry: what the
    entries of a block of it mean."""
    return tuple((e.name.decode(), e.unit.decode()) for e in params_table(plant, variant))


def _check_block_plant(what, plant, variant, bp):
    """ValueError unless bp (a BoardParams) holds the parameters of the plant and model, entry
    for entry, as board_params() recorded in bp.origin (a block built otherwise is taken: its
    plant is unknown). The board would read one plant's values as the other's entries and
    refuse dozens that were never set."""
    if bp.origin is None:
        return
    p, v, call = bp.origin
    if (p, v) == (plant, variant) or (p == plant and _table_of(p, v) == _table_of(plant, variant)):
        return

    def maker(pi):
        return ("Params().board_params() with loop_config(gains)" if pi == 0 else
                "PlantParams(%r, model).board_params() with loop_config(gains, plant=PlantParams(%r, model))"
                % ((plant_names()[pi],) * 2))
    theirs = "the %s plant's parameters (%s: %d channels)" % (plant_names()[p], call, _plant_channels(p, v))
    cfgs = "the %s plant's (%d channels)" % (plant_names()[plant], _plant_channels(plant, variant))
    if p != plant:
        raise ValueError("%s: board_params are %s, but cfg is %s: give a block and a cfg of one plant: %s, or %s"
                         % (what, theirs, cfgs, maker(plant), maker(p)))
    raise ValueError("%s: board_params are %s, of another model than cfg, %s: build both from one PlantParams pp: "
                     "loop_config(gains, plant=pp) and pp.board_params()" % (what, theirs, cfgs))


def _check_board_params(what, plant, variant, bp, period_ns):
    """HexaglideError (what, then the code and why of _board_params_refusal) unless a board of
    the plant and model takes bp and integrates it at period_ns: what Board, Loop and Job
    refuse at construction, before a board faults on its first period."""
    refusal = _board_params_refusal(plant, variant, bp, period_ns)
    if refusal:
        raise HexaglideError(what, *refusal)


class _ByName:
    """A parameter set is set by name, p["c_visc"] = value. An attribute set, p.c_visc = value,
    would be kept by Python beside the parameters and never reach the machine: it raises
    (only the class's own attributes, _own, are set as attributes)."""
    _own = ()

    def __setattr__(self, name, value):
        if name not in self._own:
            raise AttributeError("%s has no attribute %r: a parameter is set by name, p[%r] = %r (an attribute "
                                 "would never reach the machine)" % (type(self).__name__, name, name, value))
        object.__setattr__(self, name, value)


class Params(_ByName):
    """hg_params: the machine's parameter set, by spec name (SI), e.g. p["c_visc"]."""
    _own = ("buf",)

    def __init__(self, **values):
        self.buf = C.create_string_buffer(_sizeof(6))
        _params_default(self.buf)
        for k, v in values.items():
            self[k] = v

    def __getitem__(self, name):
        f = _params_field(self.buf, _param_name(name).encode())
        if not f:
            raise KeyError(_unknown(name, [e.name.decode() for e in params_table()]))
        return f[0]

    def __setitem__(self, name, value):
        """KeyError for a name not in the table, TypeError for a value that is not a number,
        ValueError for one hg_params_set refuses (not finite: _param_value); the whole set's
        rules are checked where it is used (Model, Board, ik, fk)."""
        if not _params_field(self.buf, _param_name(name).encode()):
            raise KeyError(_unknown(name, [e.name.decode() for e in params_table()]))
        rc = _params_set(self.buf, name.encode(), _param_value(name, value, "SI units, params_table"))
        if rc:                                  # (a known name and a finite value: never)
            raise HexaglideError("params: %s" % name, rc)

    def board_params(self, substeps=1, integrator=DEFAULT_INTEGRATOR):
        """hg_board_params: these model parameters (by table entry) + the board's substeps and
        integrator, those two checked by hg_board_params_check (TypeError, or ValueError naming
        the argument, its value and its range)."""
        variant = _plant_variant_named(0, None)
        bp = BoardParams()
        for i, info in enumerate(params_table()):
            bp.plant[i] = self[info.name.decode()]
        bp.substeps = _board_setting(0, variant, "substeps", substeps)
        bp.integrator = _board_setting(0, variant, "integrator", integrator)
        bp.origin = 0, variant, "Params.board_params()"
        return bp


class PlantParams(_ByName):
    """Any plant's parameter block by spec name (SI), from its defaults:
    PlantParams("serial", "XYZ", mass_0=60)["lead_0"]. Unknown plants,
    models and names raise, naming what there is; a value that is not a number TypeError, one
    that is not finite ValueError (as Params)."""
    _own = ("plant", "variant", "model", "names", "v")

    def __init__(self, plant="hexaglide", model=None, **values):
        self.plant = _plant_find(_name("plant", plant, plant_names()))
        if self.plant < 0:
            raise ValueError("unknown plant %r; one of %s" % (plant, plant_names()))
        self.variant = _plant_variant_named(self.plant, None if model is None else _name("model", model, "its models"))
        if self.variant < 0:
            raise ValueError("unknown model %r of plant %s" % (model, plant))
        self.model = model                     # (as given: None for the plant's default)
        self.names = [e.name.decode() for e in params_table(self.plant, self.variant)]
        self.v = (C.c_double * PLANT_PARAMS_MAX)()
        _plant_defaults(self.plant, self.variant, C.byref(self.v))
        for k, x in values.items():
            self[k] = x

    def _index(self, name):
        try:
            return self.names.index(_param_name(name))
        except ValueError:
            raise KeyError(_unknown(name, self.names))

    def __getitem__(self, name):
        return self.v[self._index(name)]

    def __setitem__(self, name, value):
        """KeyError for a name not in the plant's table, TypeError for a value that is not a number,
        ValueError for one not finite (_param_value, as Params); the values' other rules are
        checked where the block is used (Board, Loop, batch)."""
        self.v[self._index(name)] = _param_value(name, value, "SI units, the plant's params_table")

    @property
    def channels(self):
        """The board channels this plant and model use (one servo loop each)."""
        bp = self.board_params()
        buf = C.create_string_buffer(_sizeof(8))
        if _board_init(buf, self.plant, self.variant, C.byref(bp)):
            raise ValueError("these parameters are refused by plant %s" % plant_names()[self.plant])
        out = BoardOutputs()
        _board_peek(buf, C.byref(out))
        return out.channels

    def refused(self):
        """[(name, value, why)] of every parameter the plant refuses (hg_board_params_check); [] if none."""
        bad = _board_refusals(self.plant, self.variant, self.board_params())
        return [(name, self.v[i], bad[i]) for i, name in enumerate(self.names) if i in bad]

    def board_params(self, substeps=1, integrator=DEFAULT_INTEGRATOR):
        """hg_board_params: these parameters + substeps and integrator, checked as Params.board_params."""
        bp = BoardParams()
        for i in range(len(self.names)):
            bp.plant[i] = self.v[i]
        bp.substeps = _board_setting(self.plant, self.variant, "substeps", substeps)
        bp.integrator = _board_setting(self.plant, self.variant, "integrator", integrator)
        bp.origin = self.plant, self.variant, "PlantParams(%r, %r).board_params()" % (
            plant_names()[self.plant], self.model)
        return bp


def _plant_and_model(kind, params, plant=None, kind_arg="kind", params_arg="params"):
    """(plant index, model variant, parameters) of a board of the plant named plant (None:
    params') with the model kind (None: params' model, or for the Hexaglide of Params the
    board's default, reduced-cartesian) and params (for the Hexaglide a Params, else a
    PlantParams of the plant; None: its defaults). TypeError or ValueError naming the argument
    (kind_arg, params_arg) for a kind that is no model of the plant or not params' model (Loop
    and loop_config ignored it), or params of another plant: what Board, Loop and loop_config
    check."""
    if plant is None:
        plant = plant_names()[params.plant] if isinstance(params, PlantParams) else "hexaglide"
    _name("plant", plant, plant_names())
    if plant == "hexaglide" and not isinstance(params, PlantParams):
        _geometry(params)                      # a Params or None, else TypeError
        k = _plant_variant_named(0, None if kind is None else _name(kind_arg, kind, MODELS))
        if k < 0:
            raise ValueError("unknown %s %r; one of %s" % (kind_arg, kind, MODELS))
        return 0, k, params or Params()
    if kind is not None:
        _name(kind_arg, kind, "the plant's models")
    params = params or PlantParams(plant, kind)
    if not isinstance(params, PlantParams) or plant_names()[params.plant] != plant:
        raise ValueError("%s of plant %s: give PlantParams(%r, model)" % (params_arg, plant, plant))
    kv = params.variant if kind is None else _plant_variant_named(params.plant, kind.encode())
    if kv < 0:
        raise ValueError("unknown %s %r of plant %s" % (kind_arg, kind, plant))
    if kv != params.variant:
        raise ValueError("%s %r is not the model of %s, PlantParams(%r, %r): give %s=None, or %s of model %r"
                         % (kind_arg, kind, params_arg, plant, params.model, kind_arg, params_arg, kind))
    return params.plant, params.variant, params


def _geometry(params):
    """The hg_geometry of params (a Params; None: the defaults), else TypeError."""
    if params is None:
        params = Params()
    if not isinstance(params, Params):
        raise TypeError("params must be a hexaglide.Params (the Hexaglide's parameter set) or None, got %r"
                        % (params,))
    return params.buf  # hg_geometry is the first member of hg_params


def _checked_geometry(what, params):
    """_geometry(params), the set checked first as the kinematics check it (hexaglidekins,
    `hexaglide ik --set`: hg_params_check_kinematics, the geometry and any field given another
    value than its default): ValueError naming each refused parameter, its value and its rule,
    so that the kinematics never run on a machine that cannot be built (a negative bar length
    gave a message about the tool offset, an e beyond lb zeros)."""
    params = Params() if params is None else params
    geo = _geometry(params)
    bad = (C.c_ulonglong * 5)()                          # hg_bitset (HG_BITSET_BITS 320)
    why = (C.c_char_p * PLANT_PARAMS_MAX)()              # (room for HG_PARAMS_MAX reasons)
    if _params_check_kinematics(geo, bad, why):
        table = params_table()
        said = ["%s = %r%s: %s" % (e.name.decode(), params[e.name.decode()], " " + e.unit.decode() if e.unit else "",
                                   (why[i] or b"refused").decode())
                for i, e in enumerate(table) if bad[i // 64] >> (i % 64) & 1]
        raise ValueError("%s: params: %s (hg_params_check_kinematics; `hexaglide ik --set` refuses the set too)"
                         % (what, "; ".join(said)))
    return geo


POSE = "X Y Z (mm) A B C (deg)"
JOINTS_MM = "J0..J5 (mm)"


def _pose_si(name, pose_user):
    """A pose (mm, deg) of six numbers as the core's (m, rad)."""
    v = _vector(name, pose_user, 6, what=POSE)
    return _d6(*(v[:3] / 1000.0), *np.radians(v[3:]))


def _joints_si(name, joints_mm):
    """Six joint positions (mm) as the core's (m)."""
    return _d6(*(_vector(name, joints_mm, 6, what=JOINTS_MM) / 1000.0))


def _guard_text(rep):
    text = C.create_string_buffer(200)
    _guard_describe(C.byref(rep), 0, text)
    return text.value.decode()


def _tool_offset_m(geo, tool_offset):
    """tool_offset (mm) in m, else TypeError (not a number) or ValueError (not finite, or
    beyond 100 bar lengths: hg_tool_offset_check)."""
    d = _real("tool_offset", tool_offset, "mm")
    if _tool_offset_check(geo, d / 1000.0):
        raise ValueError("tool_offset = %r mm is not a tool length: finite, at most 100 bar lengths either way"
                         % (d,))
    return d / 1000.0


def ik(pose_user, params=None, tool_offset=0.0):
    """Joints (mm) of a pose (X Y Z mm, A B C deg) the machine can take: the closed-form
    inverse and the mechanical guard, as `hexaglide ik` (hg_inverse_kinematics_guarded).
    tool_offset (mm): G43's tool length, added to Z in pose_user as LinuxCNC does; the tool's
    tip on the head's axis then follows the pose at any tilt (RTCP, hexaglidekins.tool-offset).
    HexaglideError (code and, for a guard, the bar, value and limit) otherwise; ValueError
    naming each parameter of params the kinematics refuse (hg_params_check_kinematics: the
    geometry, and any field given another value than its default), before any solve."""
    geo = _checked_geometry("ik", params)
    commanded = _pose_si("pose", pose_user)
    pose = _d6()
    _offset_to_op(commanded, _tool_offset_m(geo, tool_offset), pose)
    z = _d6()
    rep = GuardReport()
    rc = _ik(geo, pose, z, C.byref(rep))
    if rc:
        raise HexaglideError("ik", rc, _guard_text(rep))
    return np.array(z[:]) * 1000.0


def fk(joints_mm, guess_user=(0, 0, 0, 0, 0, 0), params=None, tool_offset=0.0):
    """Pose (mm, deg) of six joint positions (mm), Newton from guess (a pose); with
    tool_offset (mm) the pose of the tool's tip plus tool_offset in Z, as ik takes it; params
    checked as ik checks them."""
    geo = _checked_geometry("fk", params)
    z = _joints_si("joints", joints_mm)
    d = _tool_offset_m(geo, tool_offset)
    guess, pose = _pose_si("guess", guess_user), _d6()
    _offset_to_op(guess, d, pose)
    rc = _fk(geo, z, pose, None, None)
    if rc:
        raise HexaglideError("fk", rc)
    _op_to_offset(pose, d, guess)
    return np.concatenate([np.array(guess[:3]) * 1000.0, np.degrees(guess[3:])])


def guard(joints_mm, pose_user, params=None):
    """The mechanical limits at a state (src/hg_guard.h): (0, "") inside
    them, else (code, sentence naming the bar(s), value and limit); params checked as ik
    checks them."""
    z = _joints_si("joints", joints_mm)
    pose = _pose_si("pose", pose_user)
    rep = GuardReport()
    rc = _guard_check(_checked_geometry("guard", params), z, pose, 0, C.byref(rep))
    return rc, _guard_text(rep)


class Model:
    """hg_model + hg_data: the machine's dynamics (SI units, src/hg_dynamics.h)."""

    def __init__(self, kind="reduced-cartesian", params=None):
        k = _model_from_name(_name("kind", kind, MODELS))
        if k < 0:
            raise ValueError("unknown model %r; one of %s" % (kind, MODELS))
        _geometry(params)                      # a Params or None, else TypeError
        self.params = params or Params()
        self._dt_checked = None                # the last step length the stability check passed
        self.m = C.create_string_buffer(_sizeof(4))
        self.d = Data()
        bad, why = C.c_char_p(), C.c_char_p()
        rc = _model_init(self.m, self.params.buf, k, C.byref(bad), C.byref(why))
        if rc:
            raise HexaglideError("model: %s %s" % ((bad.value or b"").decode(), (why.value or b"").decode()), rc)
        self.reset()

    def reset(self):
        """HOME at rest."""
        rc = _data_reset(self.m, C.byref(self.d))
        if rc:
            raise HexaglideError("reset", rc)

    def step(self, volts, dt_s):
        """One integration step of dt_s seconds with six DAC volts (finite: hg_step would take
        NaN or inf as 0 V, as the DAC does; Board.step reports that in out.dac_nan); returns
        self.d. A dt_s hg_step refuses (not finite, <= 0, above STEP_DT_MAX_S) raises
        HexaglideError code -10 naming dt_s and the limit; a dt_s longer than Heun can integrate
        on these parameters (hg_stability_check, the board's own check: the board substeps
        instead) raises HexaglideError code -16 naming the parameter and the longest step."""
        dt_s = _real("dt_s", dt_s, "s")
        v = _d6(*_vector("volts", volts, JOINTS, finite=True, what="DAC volts"))
        if dt_s != self._dt_checked:
            self._check_dt(dt_s)
        rc = _step(self.m, C.byref(self.d), v, dt_s)
        if rc == _ERR_BAD_DT:                  # hg_step's own check, its limit HG_DT_MAX_S
            raise HexaglideError("step", rc, "dt_s = %r s: must be finite, > 0 and at most %r s; split a longer "
                                 "time into steps of at most that" % (dt_s, STEP_DT_MAX_S))
        if rc:
            raise HexaglideError("step", rc)
        return self.d

    def _heun_refusal(self, dt_s):
        """None when hg_stability_check (the board's own check) finds Heun, hg_model_init's
        scheme, stable on these parameters in steps of dt_s, else its _Stability (the limiting
        parameter and its longest stable step, 0 when none is)."""
        st = _Stability()
        # (self.m is an hg_model, whose first member is the hg_params it was built from)
        rc = _stability_check(self.m, integrator_id("heun"), dt_s, 1, 1, C.byref(st))
        return st if rc == _ERR_STIFF else None

    def _check_dt(self, dt_s):
        """HexaglideError code -16 when Heun cannot integrate these parameters in steps of dt_s
        (_heun_refusal; a dt_s hg_step refuses is left to hg_step's message). The check judges a
        step by the increments it makes, which vanish in rounding far below the machine's
        fastest mode: it refused 1e-18 s on the defaults and 1e-10 s on rigid trains, naming a
        bound of 0 s or below 1e-18 s. Heun's stable steps on a damped linear mode run from 0
        up to its bound, so a step it refuses while it takes a longer one is stable: taken (a
        refusal by the impact test of a train with backlash, not linear, stands)."""
        if not 0 < dt_s <= STEP_DT_MAX_S:
            return
        st = last = self._heun_refusal(dt_s)
        longer = dt_s
        while last and (last.param or b"") != b"backlash" and longer < STEP_DT_MAX_S:
            longer = min(2.0 * longer, STEP_DT_MAX_S)
            last = self._heun_refusal(longer)
        if last and st.dt_max_s > 0:           # (the bound rounded down: what it prints is stable)
            bound = decimal.Context(prec=4, rounding=decimal.ROUND_DOWN).create_decimal(st.dt_max_s)
            raise HexaglideError("step", _ERR_STIFF, "dt_s = %r s: heun cannot integrate these parameters in "
                                 "steps that long: %s limits it to %s s; call step with dt_s of at most that "
                                 "(n steps of dt / n), or use Board, which substeps" % (
                                     dt_s, (st.param or b"?").decode(), "{:g}".format(bound)))
        if last:
            raise HexaglideError("step", _ERR_STIFF, "dt_s = %r s: heun is unstable on these parameters at every "
                                 "step from %r s to %r s, the board's check says, naming %s: give its mode "
                                 "damping, or use Board with another integrator" % (
                                     dt_s, dt_s, longer, (last.param or b"?").decode()))
        self._dt_checked = dt_s

    def energy(self):
        """(kinetic, potential) J."""
        k, p = C.c_double(), C.c_double()
        _energy(self.m, C.byref(self.d), C.byref(k), C.byref(p))
        return k.value, p.value

    @property
    def z_m(self):
        return np.array(self.d.z_m[:])

    @property
    def zdd_mps2(self):
        return np.array(self.d.zdd_mps2[:])


class Board:
    """hg_board: the virtual MOTENC-100 with the machine behind it (src/hg_board.h),
    the very function LinuxCNC's motenc.0.dynamics runs. SI inside, as the core.

        b = Board()                      # power-up: HOME at rest, E-STOP loop closed here
        out = b.step([0.3] * 6)          # DAC volts of joints 0..5 for one 1 ms period
        out.pos[:6], out.position[:6], out.count[:6], out.amps_on
    b.inputs is the full hg_board_inputs record (fault injection, index-enable, ...)."""

    def __init__(self, kind="reduced-cartesian", params=None, substeps=1, integrator=DEFAULT_INTEGRATOR, period_ns=1000000,
                 estop_closed=True, plant="hexaglide"):
        """plant: the machine behind the board (plant_names()); kind its model (the Hexaglide's
        MODELS, the serial plant's axes, "XYZ"; None: params' model, or the plant's default) and
        params a Params (the Hexaglide) or a PlantParams of that plant and model (None: its
        defaults); a kind not params' model raises ValueError (_plant_and_model). Refused here, not
        at the first step: a period_ns hg_board_step would fault on (the loop's check, the same
        (0, HG_PERIOD_MAX_NS]), substeps and integrator hg_board_params_check refuses
        (ValueError naming the argument, its value and range), an estop_closed not a bool
        (TypeError), parameters the plant refuses (HexaglideError code -7 naming each) or that
        the board cannot integrate at period_ns even with SUBSTEPS_MAX substeps (code -16 naming
        the bound: _check_board_params)."""
        _name("plant", plant, plant_names())
        period_ns = _loop_period(period_ns)
        if not isinstance(estop_closed, (bool, np.bool_)):
            raise TypeError("estop_closed must be True (the E-STOP loop closed: amplifiers on) or False, got %r"
                            % (estop_closed,))
        pi, k, self.params = _plant_and_model(kind, params, plant)
        self.plant, self.variant = pi, k
        self.buf = C.create_string_buffer(_sizeof(8))
        self.board_params = self.params.board_params(substeps, integrator)
        _check_board_params("board init", pi, k, self.board_params, period_ns)
        rc = _board_init(self.buf, pi, k, C.byref(self.board_params))
        if rc:
            raise HexaglideError("board init", rc)
        self.inputs = BoardInputs()
        _board_inputs_default(self.buf, C.byref(self.inputs))
        if estop_closed:
            self.inputs.dout_values |= 1 << 7   # out-07 closes the E-STOP loop: amplifiers on
        self.inputs.dac_written = 1
        self.outputs = BoardOutputs()
        _board_peek(self.buf, C.byref(self.outputs))
        self.period_ns = period_ns

    @property
    def channels(self):
        """The channels the plant uses (the Hexaglide's six, a serial machine's axes)."""
        return self.outputs.channels

    def enc_scale_notes(self, scales):
        """[(channel, why)] for each scales[k] (INPUT_SCALE: encoder counts per machine unit) that is
        not this board's encoder's counts per mm or per inch (per deg on a rotary axis), nor 1
        (hg_board_enc_scale_fits): why says what the encoder gives and how counts / scale read the
        travel (hg_board_describe_enc_scale). A config of such a scale runs, as LinuxCNC would."""
        notes = []
        for k, s in enumerate(scales):
            if not _enc_scale_fits(self.buf, k, float(s)):
                text = C.create_string_buffer(_BOARD_TEXT_LEN)
                _describe_enc_scale(self.buf, k, float(s), text)
                notes.append((k, "%.9g %s" % (s, text.value.decode())))
        return notes

    def step(self, dac_volts=None):
        """One servo period; dac_volts (one per channel: self.channels) replaces inputs.dac_v
        of those channels (NaN gives 0 V and sets out.dac_nan, as the board's dac-nan pin).
        Returns self.outputs."""
        if dac_volts is not None:
            for i, v in enumerate(_vector("dac_volts", dac_volts, self.channels, what="DAC volts, one per channel")):
                self.inputs.dac_v[i] = v
        _board_step(self.buf, C.byref(self.inputs), C.byref(self.outputs), self.period_ns)
        return self.outputs


def substeps_run(params=None, integrator=DEFAULT_INTEGRATOR, substeps=1, period_ns=1000000):
    """The steps a servo period the board runs for the Hexaglide of params (None: the defaults)
    with this scheme: the substeps asked, raised as its stability check needs
    (src/hg_board.c), read after one period at HOME; 0 when no count up to the board's
    maximum integrates those parameters (the board refuses them). Arguments as Board takes them
    (a substeps, integrator or period_ns it refuses raises)."""
    try:
        out = Board(params=params, substeps=substeps, integrator=integrator, period_ns=period_ns).step()
    except HexaglideError:
        return 0
    return 0 if out.fault or out.param_error else int(out.substeps_run)


class RunResult:
    """What Loop.run and batch return: per-period f-errors, pid outputs and load (carriage)
    positions (n, 6) when kept, and the summary; stop_bound: the bound that stopped a batch
    job's run (its Stop), None if none did (then the run is whole or ended by a trip or fault)."""

    def __init__(self, ferror, output, summ, rc, load=None, joints=JOINTS, stop_bound=None):
        self.ferror_mm, self.output_v, self.load_mm, self.rc = ferror, output, load, rc
        self.stop_bound = stop_bound
        self.peak_ferror_mm = np.array(summ.peak_ferror_mm[:joints])
        self.peak_output_v = np.array(summ.peak_output_v[:joints])
        self.rms_ferror_mm = np.array(summ.rms_ferror_mm[:joints])
        self.peak_tool_error_mm = summ.peak_tool_error_mm
        self.periods = summ.periods
        self.tripped_at = summ.tripped_at

    @property
    def ok(self):
        return self.rc == 0 and self.tripped_at < 0


def read_ini(path=DEFAULT_INI, n_joints=JOINTS):
    """[JOINT_0..n_joints-1] and [AXIS_X..C] of a LinuxCNC INI as ([{KEY: float}] per joint,
    {axis: {KEY: float}}); ValueError naming the file, section and key when something is
    missing or not a number."""
    if not os.path.isfile(path):
        raise ValueError("no such INI file: %s" % path)
    cp = configparser.ConfigParser(strict=False, interpolation=None, comment_prefixes=("#", ";"))
    cp.optionxform = str.upper
    try:
        with open(path) as f:
            cp.read_string("".join(l for l in f if not l.startswith("#INCLUDE")))
    except configparser.Error as ex:
        raise ValueError("%s does not parse as an INI file: %s" % (path, ex))

    def numbers(sec):
        out = {}
        for k, v in cp.items(sec):
            try:
                out[k] = float(v)
            except ValueError:
                pass                     # words (TYPE = LINEAR, HOME_USE_INDEX = YES)
        return out
    joints = []
    for j in range(n_joints):
        if not cp.has_section("JOINT_%d" % j):
            raise ValueError("%s has no [JOINT_%d] section" % (path, j))
        joints.append(numbers("JOINT_%d" % j))
        for k in ("P", "I", "D", "FF0", "FF1", "FF2", "FF3", "BIAS"):
            if cp.has_option("JOINT_%d" % j, k) and k not in joints[-1]:
                raise ValueError("%s [JOINT_%d] %s = %r is not a number" % (path, j, k, cp.get("JOINT_%d" % j, k)))
    axes = {a: numbers("AXIS_" + a) if cp.has_section("AXIS_" + a) else {} for a in "XYZABC"}
    return joints, axes


_pid_setting_at = _sig("hg_pid_setting_at", C.POINTER(PidSetting), C.c_int)
_pid_gains_check = _sig("hg_pid_gains_check", C.c_int, C.POINTER(PidGains), C.POINTER(C.POINTER(PidSetting)),
                        C.POINTER(C.c_char_p))


def _pid_settings():
    out, i = [], 0
    while _pid_setting_at(i):
        out.append(_pid_setting_at(i).contents)
        i += 1
    return out


_PID_MEMBER = {getattr(PidGains, n).offset: n for n, _ in PidGains._fields_}
# the pid settings a config's [JOINT_N] sets, INI key -> PidGains field (src/hg_pid.c's table)
GAIN_KEYS = {e.ini_key.decode(): _PID_MEMBER[e.offset] for e in _pid_settings() if e.ini_key}
# the same keys -> pid.N's pin names ("P" -> "Pgain"), for a setp
GAIN_PINS = {e.ini_key.decode(): e.pin.decode() for e in _pid_settings() if e.ini_key}
SCALE_KEYS = {"INPUT_SCALE": "input_scale", "OUTPUT_SCALE": "output_scale", "OUTPUT_OFFSET": "output_offset"}
LOOP_KEYS = set(GAIN_KEYS) | set(SCALE_KEYS)     # what a gains dict of Loop / loop_config sets
# LinuxCNC's own [JOINT_N] keys (motion's limits and homing, src/emc/ini/inijoint.cc): taken in a
# gains dict (read_ini's) and ignored, the loop does not model them; any other key is refused
MOTION_JOINT_KEYS = {"TYPE", "HOME", "MIN_LIMIT", "MAX_LIMIT", "MAX_VELOCITY", "MAX_ACCELERATION", "MAX_JERK",
                     "BACKLASH", "COMP_FILE", "COMP_FILE_TYPE", "FERROR", "MIN_FERROR", "HOME_OFFSET",
                     "HOME_SEARCH_VEL", "HOME_LATCH_VEL", "HOME_FINAL_VEL", "HOME_USE_INDEX",
                     "HOME_INDEX_NO_ENCODER_RESET", "HOME_IGNORE_LIMITS", "HOME_IS_SHARED",
                     "HOME_ABSOLUTE_ENCODER", "HOME_SEQUENCE", "VOLATILE_HOME", "LOCKING_INDEXER_JOINT"}


def _gain_dict(name, g):
    """g (a dict of INI keys) checked: TypeError if not a dict, ValueError naming an unknown key
    (neither the loop's nor one of LinuxCNC's motion keys), TypeError naming a value that is not a number."""
    if not isinstance(g, dict):
        raise TypeError("%s must be a dict of INI keys (P, I, D, ...), got %r" % (name, g))
    for k, v in g.items():
        if k not in LOOP_KEYS and k not in MOTION_JOINT_KEYS:
            raise ValueError("%s: unknown key %r: the loop takes %s (LinuxCNC's motion keys, FERROR, "
                             "MAX_VELOCITY, HOME..., are ignored); filter another INI's keys of its own "
                             "HAL file out, {k: v for k, v in g.items() if k in hg.LOOP_KEYS}"
                             % (name, k, ", ".join(sorted(LOOP_KEYS))))
        if k in LOOP_KEYS:
            _real("%s[%r]" % (name, k), v)
    return g


def read_gains(path, joints=JOINTS):
    """Gains of a tune output or INI: ([{KEY: value}] of joints 0..joints-1 (the Hexaglide's six),
    {joint: predicted peak mm} or {}).
    [JOINT_N] sections with KEY = value (only pid keys kept, other sections skipped) and
    tune's "# joint N: peak |f-error| X mm" lines; ValueError naming file and line. Read as
    LinuxCNC reads an INI: '#' and ';' comment lines; what LinuxCNC would resolve silently (a
    key given twice: it takes the first; a second [JOINT_N]: it reads the first) refused, as
    the CLI's reader (src/cli/cli_ini.c) refuses it."""
    gains = [dict() for _ in range(joints)]
    pred = {}
    sec = None
    seen, heads = {}, {}                       # (joint, key) -> line; joint -> line of its header
    with open(path) as f:
        for no, line in enumerate(f, 1):
            s = line.strip()
            m = re.match(r"#\s*joint (\d): peak \|f-error\| ([0-9.eE+-]+) mm", s)
            if m:
                pred[int(m.group(1))] = float(m.group(2))
                continue
            if not s or s.startswith("#") or s.startswith(";"):
                continue
            m = re.match(r"\[JOINT_(\d+)\]$", s)
            if m:
                sec = int(m.group(1))
                if sec >= joints:
                    raise ValueError("%s line %d: [JOINT_%d]: the machine has joints 0..%d" % (path, no, sec, joints - 1))
                if sec in heads:
                    raise ValueError("%s line %d: a second [JOINT_%d] section (the first on line %d); LinuxCNC "
                                     "reads only the first one: merge them" % (path, no, sec, heads[sec]))
                heads[sec] = no
                continue
            if s.startswith("["):
                sec = None
                continue
            if sec is None:
                continue                       # other sections of an INI
            k, eq, v = s.partition("=")
            k = k.strip()
            if not eq:
                raise ValueError("%s line %d: not KEY = value: %r" % (path, no, s))
            if k in GAIN_KEYS:
                try:
                    val = hg_csv.number(v)
                except ValueError:
                    raise ValueError("%s line %d: %s = %r is not a number" % (path, no, k, v.strip()))
                if not np.isfinite(val):
                    raise ValueError("%s line %d: %s is not finite" % (path, no, k))
                if (sec, k) in seen:
                    raise ValueError("%s: [JOINT_%d]%s is given twice (lines %d and %d); LinuxCNC would use the "
                                     "first: remove one" % (path, sec, k, seen[sec, k], no))
                seen[sec, k] = no
                gains[sec][k] = val
    if not all(gains):
        raise ValueError("%s: needs [JOINT_0]..[JOINT_%d] with gains" % (path, joints - 1))
    return gains, pred


def loop_config(gains=None, ferror_limit_mm=0.0, period_ns=1000000, model=None, notch=None,
                plant=None):
    """hg_loop_config of the plant's joints: gains a list of one dict per joint (six for the
    Hexaglide, plant.channels for another) of INI keys (LOOP_KEYS: P, I, D, FF0, FF1, FF2, FF3,
    BIAS, DEADBAND, MAX_OUTPUT, MAX_ERROR_I, INPUT_SCALE, OUTPUT_SCALE, OUTPUT_OFFSET; LinuxCNC's
    motion keys, MOTION_JOINT_KEYS, ignored; any other key ValueError); keys not given keep
    pid.c's load-time values: Pgain 1, the rest 0; None: configs/hexaglide.ini's, the Hexaglide's);
    notch: per joint None or (f0 Hz, Q), a biquad.N notch between pid.N.output and the DAC;
    model: the Hexaglide's model (MODELS; None: reduced-cartesian), or plant's (None: its own; another
    ValueError); plant: a PlantParams of any plant (its plant and model; None: the Hexaglide). The loop's
    units are the config's: INPUT_SCALE counts per unit, the commands in that unit (inches for an
    inch config), as LinuxCNC's HAL file sets enc-NN-scale and dac-NN-gain. The config is
    checked (check_loop_config): ValueError naming the joint and the field that fails."""
    cfg = LoopConfig()
    _loop_default(C.byref(cfg))
    try:
        cfg.ferror_limit_mm = ferror_limit_mm
    except TypeError:
        raise TypeError("ferror_limit_mm must be a number (mm; 0: no trip), got %r" % (ferror_limit_mm,))
    cfg.period_ns = _loop_period(period_ns)
    if plant is not None and not isinstance(plant, PlantParams):
        raise TypeError("plant must be a PlantParams or None, got %r" % (plant,))
    cfg.plant, cfg.variant, _ = _plant_and_model(model, plant, None, "model", "plant")
    n = _plant_channels(cfg.plant, cfg.variant)
    if gains is None:
        if cfg.plant != 0:
            raise ValueError("gains: give one dict per channel (%d) for plant %s: the default is "
                             "configs/hexaglide.ini's, the Hexaglide's" % (n, plant_names()[cfg.plant]))
        gains = read_ini()[0]
    if isinstance(gains, dict) or not hasattr(gains, "__len__"):
        raise TypeError("gains must be a list of %d dicts (one per joint), got %r" % (n, gains))
    if len(gains) != n:
        raise ValueError("gains needs %d dicts (one per joint of plant %s), got %d"
                         % (n, plant_names()[cfg.plant], len(gains)))
    for j, g in enumerate(gains):
        for key, v in _gain_dict("gains[%d]" % j, g).items():
            if key in GAIN_KEYS:
                setattr(cfg.pid[j], GAIN_KEYS[key], float(v))
            elif key in SCALE_KEYS:
                getattr(cfg, SCALE_KEYS[key])[j] = float(v)
    if notch is not None:
        if len(notch) != n:
            raise ValueError("notch needs %d entries (None or (f0 Hz, Q) per joint), got %d" % (n, len(notch)))
        for j, nf in enumerate(notch):
            if nf is not None:
                f0, q = _vector("notch[%d]" % j, nf, 2, what="f0 Hz, Q")
                _biquad_notch(C.byref(cfg.biquad[j]), float(f0), float(q))
    check_loop_config(cfg)
    return cfg


class LoopConfigError(ValueError):
    """What hg_loop_config_check refuses: joint (-1: none), ini_key (its [JOINT_N] key, or ""),
    value and why (what it must be), as soak names them; str() the whole message."""

    def __init__(self, msg, joint, ini_key, value, why):
        super().__init__(msg)
        self.joint, self.ini_key, self.value, self.why = joint, ini_key, value, why

    def in_ini(self, path):
        """The refusal of the INI at path whose [JOINT_N] gave the loop, as soak words it."""
        if self.ini_key and self.joint >= 0:
            return "%s: [JOINT_%d]%s = %.17g: %s" % (path, self.joint, self.ini_key, self.value, self.why)
        return "%s: %s" % (path, self)


def check_loop_config(cfg):
    """LoopConfigError (a ValueError) naming the joint and the field (its INI key, its pid.N pin)
    hg_loop_config_check refuses in cfg (a LoopConfig, else TypeError), with what it must be;
    a whole-number field's value printed as the int it is."""
    if not isinstance(cfg, LoopConfig):
        raise TypeError("cfg must be a LoopConfig (hexaglide.loop_config(...)), got %r" % (cfg,))
    r = LoopCheckReport()
    rc = _loop_check(C.byref(cfg), C.byref(r))
    if not rc:
        return
    comp, field = r.component.decode(), r.field.decode()
    value = r.value                            # (the report's value is a double, whatever the field's type)
    if comp == "pid":
        name = "pid.%d.%s" % (r.joint, field)
    elif comp == "biquad":
        name = "notch biquad.%d.%s" % (r.joint, field)
    else:
        name = field
        if isinstance(getattr(cfg, field, None), int):
            value = getattr(cfg, field)        # period_ns = 0, not 0.0
    if r.ini_key:
        name = "%s (%s)" % (r.ini_key.decode(), name)
    where = "joint %d: " % r.joint if r.joint >= 0 else ""
    raise LoopConfigError("loop config: %s%s = %r: %s" % (where, name, value, r.why.decode()), r.joint,
                          r.ini_key.decode() if r.ini_key else "", r.value, r.why.decode())


def _loop_period(period_ns):
    """period_ns as an int the closed loop and the board take, else TypeError (not an int) or
    LoopConfigError (a ValueError) naming it, its value as given and the range of
    hg_loop_config_check, (0, HG_PERIOD_MAX_NS]: hg_board_step faults on a period outside it.
    A value too large for a C long is refused too (ctypes would wrap 2**64 + 1000000 to 1 ms)."""
    def why_refused(v):
        cfg = LoopConfig()
        _loop_default(C.byref(cfg))            # (the defaults pass: only the period can be refused)
        cfg.period_ns = v
        r = LoopCheckReport()
        return r.why.decode() if _loop_check(C.byref(cfg), C.byref(r)) else None
    v, why = _whole_why("period_ns", period_ns, C.c_long, why_refused, "ns")
    if why:
        raise LoopConfigError(_refusal("period_ns", v, why, "ns"), -1, "", float(v), why)
    return v


def notch_response(f0, q, freqs, period_ns=1000000):
    """LinuxCNC's biquad notch (f0 Hz, Q) in a thread of period_ns: its complex response at
    freqs (src/hg_biquad.c, the coefficients the enable edge computes), and whether
    biquad.comp accepts f0 and Q (its valid pin). ValueError for what the loop refuses
    whatever biquad.comp says (loop_config): f0 not finite and > 0 Hz, Q not finite, a period outside
    (0, 10 ms]; and for a frequency in freqs that is not finite (TypeError for one not a number). A
    discrete filter's response repeats every sampling rate, 1e9 / period_ns Hz: a frequency of at
    least that is taken exactly modulo it first (at 1e308 Hz the core's phase 2 pi f overflowed to
    NaN, and far above the rate its rounding drowned the phase)."""
    f0, q = _real("notch f0", f0, "Hz"), _real("notch Q", q)
    if not (np.isfinite(f0) and f0 > 0):
        raise ValueError("notch f0 = %r: must be finite and > 0 (Hz)" % f0)
    if not np.isfinite(q):
        raise ValueError("notch Q = %r: must be finite (biquad.comp's valid pin says whether it lies in "
                         "[0.5, 2])" % q)
    period_ns = _loop_period(period_ns)
    freqs = _vector("freqs", freqs if np.ndim(freqs) else [freqs], None, what="Hz")
    if not np.all(np.isfinite(freqs)):
        raise ValueError("freqs[%d] = %r: must be finite (Hz)" % (np.argmin(np.isfinite(freqs)),
                                                                 freqs[np.argmin(np.isfinite(freqs))]))
    b = Biquad()
    _biquad_notch(C.byref(b), f0, q)
    re, im = C.c_double(), C.c_double()
    h, valid = [], 1
    rate = fractions.Fraction(10**9, period_ns)           # (exact: Hz = 1e9 / period_ns)
    for f in freqs:
        if abs(f) >= float(rate):                           # the same response, phase 2 pi f T in range
            f = float(fractions.Fraction(float(f)) % rate)
        valid = _biquad_response(C.byref(b), period_ns, float(f), C.byref(re), C.byref(im))
        h.append(complex(re.value, im.value))
    return np.array(h), bool(valid)


class Loop:
    """LinuxCNC pid loops (and biquad notches), one per channel of the plant (the Hexaglide's
    six), around the virtual board (src/hg_loop.h), mm and volts; gains and notch as
    loop_config takes them."""

    def __init__(self, gains=None, params=None, ferror_limit_mm=0.0, period_ns=1000000,
                 model=None, substeps=1, integrator=DEFAULT_INTEGRATOR, notch=None):
        """params: Params of the Hexaglide, or PlantParams of any plant (its channels are the loops),
        refused here as Board refuses them (HexaglideError code -7 or -16 naming the parameter);
        model: as loop_config takes it (None: params' model; one not params' raises ValueError,
        as Board's kind)."""
        _, _, self.params = _plant_and_model(model, params, None, "model", "params")   # as Board checks them
        plant = self.params if isinstance(self.params, PlantParams) else None
        self.cfg = loop_config(gains, ferror_limit_mm, period_ns, model, notch, plant)
        self.joints = _plant_channels(self.cfg.plant, self.cfg.variant)
        self.board_params = self.params.board_params(substeps, integrator)   # checked there
        _check_board_params("loop init", self.cfg.plant, self.cfg.variant, self.board_params, self.cfg.period_ns)
        self.buf = C.create_string_buffer(_sizeof(0))
        self.reset()

    def reset(self):
        """Machine at HOME at rest, PIDs reset."""
        rc = _loop_init(self.buf, C.byref(self.cfg), C.byref(self.board_params))
        if rc:
            raise HexaglideError("loop init", rc)

    def run(self, cmd_mm, start=0, keep=True):
        """Run the commands (n, joints) from the current state; summary over rows >= start.
        ValueError naming the row and joint of a command that is not finite or beyond 1e9
        (hg_pid_input_check: pid.c's derivatives would overflow into NaN); nothing run then."""
        cmd = _commands(cmd_mm, self.joints)
        start = _whole_checked("start", start, C.c_long)
        n = cmd.shape[0]
        fe = np.zeros((n, self.joints)) if keep else None
        out = np.zeros((n, self.joints)) if keep else None
        summ = LoopSummary()
        rc = _loop_run(self.buf, cmd, n, start,
                       fe.ctypes.data_as(_P) if keep else None,
                       out.ctypes.data_as(_P) if keep else None, C.byref(summ))
        if keep and summ.periods < n:
            fe, out = fe[:summ.periods], out[:summ.periods]
        return RunResult(fe, out, summ, rc, joints=self.joints)


def _pid_inputs(name, values):
    """values (a float64 array) checked by hg_pid_input_check: None, or the ValueError naming
    the flat index of the first it refuses, the value and why."""
    flat = np.ascontiguousarray(values, dtype=np.float64).reshape(-1)
    rc = C.c_int()
    i = _pid_inputs_check(flat, flat.size, C.byref(rc))
    return None if i < 0 else (int(i), float(flat[i]), rc.value)


def _commands(cmd_mm, joints=JOINTS):
    """cmd_mm as a C-contiguous (n, joints) float64 array, else ValueError (the shape, or the
    row and joint of a command the loop refuses: not finite, or beyond 1e9)."""
    try:
        cmd = np.ascontiguousarray(_real_array(cmd_mm))
    except TypeError as ex:
        raise TypeError("commands (mm): %s" % ex)
    if cmd.ndim != 2 or cmd.shape[1] != joints:
        raise ValueError("commands must be an (n, %d) array, got %s" % (joints, cmd.shape))
    bad = _pid_inputs("commands", cmd)
    if bad:
        i, v, rc = bad
        raise ValueError("commands row %d, joint %d = %r: %s%s" % (
            i // joints, i % joints, v, strerror(rc),
            "" if rc == -1 else ": a pid's command derivatives would overflow to inf, then NaN"))
    return cmd


class _Trace(_Record):
    _fields_ = [("ferror_mm", _P), ("output_v", _P), ("load_mm", _P)]


class _LoopStop(_Record):
    _fields_ = [("scored", C.POINTER(C.c_ubyte)), ("above", C.c_double), ("w_rms", C.c_double),
                ("w_volts", C.c_double), ("volts_free", C.c_double), ("peak0", C.c_double),
                ("rms0", C.c_double), ("volts0", C.c_double), ("volts_dac", C.c_int)]


class _BatchJob(_Record):
    _fields_ = [("cfg", C.POINTER(LoopConfig)), ("params", C.POINTER(BoardParams)), ("cmd_mm", _P),
                ("n", C.c_long), ("from_", C.c_long), ("trace", _Trace), ("skip_tool_error", C.c_int),
                ("stop", C.POINTER(_LoopStop))]


class _BatchResult(_Record):
    _fields_ = [("sum", LoopSummary), ("rc", C.c_int), ("stop_bound", C.c_double)]


class Stop:
    """A batch Job's early stop (src/hg_loop.h's hg_loop_stop): the run stops after the first
    scored period at which the lower bound max(peak0, peak |f-error|) + w_rms max(rms0, the
    RMS's bound so far) + w_volts max(0, max(volts0, peak |volts|) - volts_free) of the same sum
    over all its scored periods exceeds `above`; RunResult.stop_bound is that bound (None if
    the run was not stopped). scored: a boolean per period (None: every period from the job's
    start); volts: pid.N.output, or the DAC value (the summary's peak_output_v) with volts_dac."""

    def __init__(self, above, scored=None, w_rms=0.0, w_volts=0.0, volts_free=0.0,
                 peak0=0.0, rms0=0.0, volts0=0.0, volts_dac=False):
        vals = dict(above=above, w_rms=w_rms, w_volts=w_volts, volts_free=volts_free, peak0=peak0,
                    rms0=rms0, volts0=volts0)
        for k, v in vals.items():
            if not np.isfinite(v) or (k != "above" and v < 0):
                raise ValueError("Stop: %s = %r: must be finite%s" % (k, v, "" if k == "above" else " and >= 0"))
        self.scored = None if scored is None else np.ascontiguousarray(scored, dtype=np.uint8)
        self.c = _LoopStop(None, *[float(vals[k]) for k in ("above", "w_rms", "w_volts", "volts_free",
                                                             "peak0", "rms0", "volts0")], int(bool(volts_dac)))
        if self.scored is not None:
            self.c.scored = self.scored.ctypes.data_as(C.POINTER(C.c_ubyte))


_batch_sizeof = _sig("hg_batch_sizeof", C.c_ulong, C.c_int)
for _i, _s in ((0, _BatchJob), (1, _BatchResult)):
    if _batch_sizeof(_i) != C.sizeof(_s):
        raise ImportError("%s: layout differs from the library's: rebuild both" % _s.__name__)
_batch_run = _sig("hg_batch_run", C.c_int, C.POINTER(_BatchJob), C.c_long, C.c_int, C.POINTER(_BatchResult))


def _checked_stop(stop, n):
    """stop (a Stop or None) for a job of n command rows, else TypeError or ValueError."""
    if stop is not None:
        if not isinstance(stop, Stop):
            raise TypeError("stop must be a hexaglide.Stop, got %r" % (stop,))
        if stop.scored is not None and stop.scored.shape != (n,):
            raise ValueError("stop.scored: one entry per command row (%d), got shape %s" % (n, stop.scored.shape))
    return stop


class Job:
    """One closed-loop run for batch(): from HOME at rest, the commands cmd (n, 6) through the
    loop of cfg (loop_config) and board parameters board_params (Params.board_params);
    summary over rows >= start; keep: the f-error and pid-output traces, load: the load's
    (carriage's) positions; tool_error False: the board skips the tool-path error (the
    Hexaglide's forward solve, a fifth of a flexible period): the summary's
    peak_tool_error_mm is then -2 (src/hg_board.h's HG_TOOL_ERROR_SKIPPED), every other
    result the same bits. Jobs may share cfg, board_params and cmd."""

    def __init__(self, cfg, board_params, cmd, start=0, keep=False, load=False, joints=None, tool_error=True,
                 stop=None):
        """joints: the plant's channels (cfg's plant: PlantParams.channels), the columns of cmd;
        None: cfg's. cfg is checked as loop_config checks it (ValueError naming the field),
        board_params as Board checks them at cfg's period (HexaglideError code -7 or -16), after
        a block board_params() made of another plant or model than cfg's: ValueError.
        stop: a Stop (None: the run goes to its end, a trip or a fault)."""
        if not isinstance(cfg, LoopConfig):
            raise TypeError("cfg must be a LoopConfig (hexaglide.loop_config), got %r" % (cfg,))
        if not isinstance(board_params, BoardParams):
            raise TypeError("board_params must be a BoardParams (Params.board_params, PlantParams.board_params), "
                            "got %r" % (board_params,))
        check_loop_config(cfg)
        _check_block_plant("job", cfg.plant, cfg.variant, board_params)
        _check_board_params("job: board_params", cfg.plant, cfg.variant, board_params, cfg.period_ns)
        n = _plant_channels(cfg.plant, cfg.variant)
        if joints is not None and _whole("joints", joints) != n:
            raise ValueError("joints = %d, but cfg's plant %s has %d channels" % (joints, plant_names()[cfg.plant], n))
        self.cfg, self.board_params, self.cmd = cfg, board_params, _commands(cmd, n)
        self.joints = n
        self.start = _whole_checked("start", start, C.c_long)
        self.keep, self.load, self.tool_error = keep, load, tool_error
        self.stop = _checked_stop(stop, self.cmd.shape[0])

    def with_stop(self, stop):
        """This job with the early stop `stop` (a Stop, or None), the rest shared."""
        j = copy.copy(self)
        j.stop = _checked_stop(stop, self.cmd.shape[0])
        return j


def cores():
    """The online processors: batch's default thread count (hg_batch_cores)."""
    return _batch_cores()


def batch(jobs, threads=0):
    """Run the Jobs over `threads` POSIX threads (0: every core, cores(); src/hg_batch.h), no
    Python per period; [RunResult] in the jobs' order, bit for bit what Loop(...).run gives
    each. A threads that is not an int TypeError, a negative one (hg_batch_run would take it
    as 0) or one beyond a C int ValueError."""
    threads = _whole_checked("threads", threads, C.c_int, lambda v: None if v >= 0 else (
        "must be 0 (every core: %d here) or a number of threads, 0..%d" % (cores(), _c_range(C.c_int)[1])))
    jobs = list(jobs)
    for i, j in enumerate(jobs):
        if not isinstance(j, Job):
            raise TypeError("jobs[%d] must be a Job (hexaglide.Job), got %r" % (i, j))
    cj = (_BatchJob * max(1, len(jobs)))()
    traces = []
    for i, j in enumerate(jobs):
        n = j.cmd.shape[0]
        # (hg_loop_run_stop writes every period it runs; the rows past them are cut below)
        fe = np.empty((n, j.joints)) if j.keep else None
        out = np.empty((n, j.joints)) if j.keep else None
        load = np.empty((n, j.joints)) if j.load else None
        traces.append((fe, out, load))
        cj[i].cfg = C.pointer(j.cfg)
        cj[i].params = C.pointer(j.board_params)
        cj[i].cmd_mm = j.cmd.ctypes.data_as(_P)
        cj[i].n, cj[i].from_ = n, j.start
        cj[i].skip_tool_error = 0 if j.tool_error else 1
        cj[i].stop = C.pointer(j.stop.c) if j.stop is not None else None
        cj[i].trace = _Trace(*[a.ctypes.data_as(_P) if a is not None else None for a in (fe, out, load)])
    res = (_BatchResult * max(1, len(jobs)))()
    rc = _batch_run(cj, len(jobs), threads, res)
    if rc:
        raise HexaglideError("batch", rc)
    out_list = []
    for j, (fe, out, load), r in zip(jobs, traces, res):
        m = r.sum.periods
        cut = (lambda a: a[:m] if a is not None else None)
        out_list.append(RunResult(cut(fe), cut(out), r.sum, r.rc, cut(load), j.joints,
                                  r.stop_bound if r.stop_bound >= 0 else None))
    return out_list


class PidState(_Record):
    """hg_pid_state: one pid's memory and output pins."""
    _fields_ = [(n, C.c_double) for n in ("error_i", "error_d", "prev_error", "prev_cmd", "prev_fb",
                                          "limit_state", "cmd_d", "cmd_dd", "cmd_ddd", "cmd_v", "fb_v")] + \
        [("prev_ie", C.c_int), ("error", C.c_double), ("output", C.c_double), ("saturated", C.c_int),
         ("saturated_s", C.c_double), ("saturated_count", C.c_int)]


_pid_calc = _sig("hg_pid_calc", C.c_double, C.POINTER(PidGains), C.POINTER(PidState), C.c_double, C.c_double,
                 C.c_int, C.c_int, C.c_long)
_pid_defaults = _sig("hg_pid_defaults", None, C.POINTER(PidGains))


def pid_gains(gains):
    """PidGains from INI keys (pid.c's defaults for the others); ValueError naming a key
    hg_pid_gains_check refuses (or one unknown, as loop_config)."""
    g = PidGains()
    _pid_defaults(C.byref(g))
    for key, v in _gain_dict("gains", gains).items():
        if key in GAIN_KEYS:
            setattr(g, GAIN_KEYS[key], float(v))
    bad, why = C.POINTER(PidSetting)(), C.c_char_p()
    if _pid_gains_check(C.byref(g), C.byref(bad), C.byref(why)):
        e = bad.contents
        name = "%s (pid.%s)" % (e.ini_key.decode(), e.pin.decode()) if e.ini_key else "pid.%s" % e.pin.decode()
        raise ValueError("gains: %s = %r: %s" % (name, getattr(g, _PID_MEMBER[e.offset]), why.value.decode()))
    return g


def pid_outputs(gains, command, feedback, enable=None, period_ns=1000000, state=None):
    """LinuxCNC's pid (src/hg_pid.c) on recorded pins: outputs for arrays of
    command and feedback (and enable, default 1), from `state` (a dict of
    PidState fields; default the load-time state, all zero). TypeError naming
    the argument: a command, feedback, enable or state value that is not a
    real number (a string, a bool, a complex); ValueError naming it: a period
    the loop refuses (hg_loop_config_check: (0, 10 ms]), a state value that is
    not finite (or, for an int field, beyond a C int), an enable other than 0
    or 1."""
    g = pid_gains(gains)
    st = PidState()
    types = dict(PidState._fields_)
    names = list(types)
    for k, v in (state or {}).items():
        if k not in names:
            raise ValueError("state: %r is not a PidState field (%s)" % (k, ", ".join(names)))
        if types[k] is C.c_int:                # (ctypes would wrap an int beyond a C int's range)
            v = _whole_checked("state: " + k, v, C.c_int)
        else:
            v = _real("state: " + k, v)
        setattr(st, k, v)
        if not np.isfinite(getattr(st, k)):
            raise ValueError("state: %s = %r: must be finite (a pid's memory is never NaN or infinite)" % (k, v))
    period_ns = _loop_period(period_ns)
    command = _vector("command", command, None, what="one per period")
    n = len(command)
    feedback = _vector("feedback", feedback, n, what="one per command")
    en = np.ones(n, dtype=int)
    if enable is not None:
        e = _vector("enable", enable, n)
        off = np.where((e != 0) & (e != 1))[0]
        if len(off):
            raise ValueError("enable[%d] = %r: must be 0 or 1 (pid.N.enable is a bit)" % (off[0], e[off[0]]))
        en = e.astype(int)
    for name, a in (("command", command), ("feedback", feedback)):
        bad = _pid_inputs(name, a)
        if bad:
            raise ValueError("%s[%d] = %r: %s" % (name, bad[0], bad[1], strerror(bad[2])))
    return np.array([_pid_calc(C.byref(g), C.byref(st), float(command[i]), float(feedback[i]), int(en[i]), 0,
                               period_ns) for i in range(n)])


if _sizeof(11) != C.sizeof(PidState):
    raise ImportError("PidState: layout differs from the library's: rebuild both")


class _RecCtx(_Record):
    """hg_board_rec_ctx (src/hg_board_rec.h)."""
    _fields_ = [("in_", C.POINTER(BoardInputs)), ("out", C.POINTER(BoardOutputs)), ("period_ns", C.c_long),
                ("plant", C.c_int), ("variant", C.c_int), ("stream", _P)]


_REC_FIELD_BYTES = 56          # sizeof(hg_board_rec_field): name[32], 7 bytes, offset, nf_index (checked below)
_rec_fields = _sig("hg_board_rec_fields", C.c_int, _P, C.c_int, C.c_int, C.c_int, C.c_int)
_rec_stream_start = _sig("hg_board_rec_stream_start", None, _P, C.c_int, C.c_int)
_rec_stream_step = _sig("hg_board_rec_stream_step", None, _P, C.POINTER(BoardParams), C.c_int)
_rec_get = _sig("hg_board_rec_get", C.c_double, _P, C.c_int, C.c_int, C.POINTER(_RecCtx))


class Recorder:
    """A format-2 record of a Board's periods (docs/replay.md), as `hexaglide sim --record` and the HAL
    glue's rec pins write it (src/hg_board_rec.h's table and event stream):
        b = Board("XYZ", PlantParams("serial", "XYZ"), plant="serial")
        b.inputs.params = hidden.board_params()     # applied by the first period, recorded as events
        with Recorder(path, b, "test") as r:
            for v in volts: r.step(v)"""

    def __init__(self, path, board, source="tools/hexaglide.py Recorder"):
        """board: a Board of PlantParams (any plant's)."""
        if not isinstance(board, Board):
            raise TypeError("Recorder: board must be a hexaglide.Board, got %r" % (board,))
        if not isinstance(board.params, PlantParams):
            raise ValueError("Recorder: the board must be built with PlantParams (the record's parameter "
                             "events name entries of the plant's table): Board(kind, PlantParams(plant, kind), "
                             "plant=plant), e.g. Board(\"reduced-cartesian\", PlantParams(\"hexaglide\", "
                             "\"reduced-cartesian\")); this one has %s" % type(board.params).__name__)
        self.b, pi, var = board, board.params.plant, board.params.variant
        self.fields = C.create_string_buffer(_REC_FIELD_BYTES * 256)
        self.n = _rec_fields(self.fields, 256, pi, var, 2)
        if self.n < 0:
            raise ValueError("no record table for this board")
        names = [self.fields.raw[i * _REC_FIELD_BYTES:i * _REC_FIELD_BYTES + 32].split(b"\0")[0].decode()
                 for i in range(self.n)]
        if names[0] != "in.period-ns":
            raise ImportError("hg_board_rec_field: layout differs from the library's: rebuild both (%r)" % names[:2])
        self.np = len(board.params.names)
        self.stream = C.create_string_buffer(1 << 17)
        _rec_stream_start(self.stream, pi, var)
        self.f = open(path, "w")
        self.f.write("# hexaglide-record 2\n# source %s\n# board 0\n# plant %s\n# closed-loop no: %s\nsample,%s\n"
                     % (source, plant_names()[pi], source, ",".join(names)))
        self.ctx = _RecCtx(C.pointer(board.inputs), C.pointer(board.outputs), board.period_ns, pi, var,
                           C.cast(self.stream, _P))
        self.s = 0

    def step(self, dac_volts=None):
        """One Board.step, recorded; returns the outputs."""
        out = self.b.step(dac_volts)
        _rec_stream_step(self.stream, C.byref(self.b.inputs.params), self.np)
        self.f.write("%d,%s\n" % (self.s, ",".join("%.17g" % _rec_get(self.fields, self.n, k, C.byref(self.ctx))
                                                   for k in range(self.n))))
        self.s += 1
        return out

    def close(self):
        self.f.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

