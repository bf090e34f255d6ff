"""hg_config.py - a LinuxCNC INI as build/hexaglide reads it, for the Python tools.

tune and excite take the machine ([HEXAGLIDE] onto the model's defaults, then
--set), the servo loops ([JOINT_N] gains and scales, as soak reads them) and
the limits ([JOINT_N], [AXIS_*] MIN_LIMIT MAX_LIMIT MAX_VELOCITY
MAX_ACCELERATION) from `hexaglide config` (src/cli/cmd_config.c), the C CLI's
one INI reader (src/cli/cli_ini.c: LinuxCNC's reading; a key given twice, a
value that is not a finite number, an unknown [HEXAGLIDE] key, a missing
key the HAL file reads ([HEXAGLIDE] or [JOINT_N]), an empty limit range, and
with loop=True what soak's loop refuses (a gain pid.c cannot take, a
SERVO_PERIOD above the board's 10 ms) refused, naming key, file and line).
No second parser: what sim, soak, ik and LinuxCNC see is what the tools see.

    cfg = hg_config.read("configs/hexaglide.ini", sets=["m_head=8"], loop=True, cmd="tune")
    cfg.params       # hg.Params, SI, checked as soak checks them
    cfg.joints[0]    # {"P": 24.6726, ..., "MIN_LIMIT": -240, ...}
    cfg.axes["X"]    # {"MIN_LIMIT": -100, ...}

build/hexaglide is found as $HEXAGLIDE_CLI (set by the hexaglide that runs
the tool), else beside the library (hg.LIB_PATH: build/hexaglide).
"""
import os
import re
import subprocess

import hexaglide as hg


class ConfigError(ValueError):
    """The config (or a --set) is refused: the message is the C reader's, in the tool's name."""


def cli_path():
    """The hexaglide executable whose INI reader the tools use."""
    return os.environ.get("HEXAGLIDE_CLI") or os.path.join(os.path.dirname(os.path.abspath(hg.LIB_PATH)),
                                                           "hexaglide")


class Config:
    """What `hexaglide config` printed: params (hg.Params; another plant's: hg.PlantParams),
    joints ([{KEY: float}] of the plant's [JOINT_N], six for the Hexaglide), axes ({axis: {KEY:
    float}}), servo_period_ns (None when not given)."""

    def __init__(self, path, plant=None, model=None):
        self.path = path
        self.params = hg.Params() if plant is None else hg.PlantParams(plant, model)
        n = hg.JOINTS if plant is None else self.params.channels
        self.joints = [dict() for _ in range(n)]
        self.axes = {a: {} for a in "XYZABC"}
        self.servo_period_ns = None


def read(path, sets=(), loop=False, cmd="tune", set_option="--set", plant=None, model=None, plant_option="--plant"):
    """Config of the INI file path with the model parameters of sets ("name=value", SI) after it;
    loop: also the servo loops ([JOINT_0..5] as soak reads them, every key the HAL file sets
    required; another plant's: the keys given); plant, model: another plant than the
    Hexaglide (its section, e.g. [SERIAL], and its model's joints). ConfigError with the C reader's messages, one a line, every line after the first
    starting "hexaglide CMD: " (the caller prints the first with its prefix), naming
    set_option where the C side says --set; plant_option None: the command has no option that
    chooses the plant (a config of another plant is then not its to take, whatever the option)."""
    exe = cli_path()
    if not os.access(exe, os.X_OK):
        raise ConfigError("%s is not there: the INI is read by build/hexaglide; build it with make host "
                          "(or set HEXAGLIDE_CLI)" % exe)
    args = [exe, "config", "--ini", path] + [x for s in sets for x in ("--set", s)] + (["--loop"] if loop else [])
    if plant is not None:
        args += ["--plant", plant] + (["--model", model] if model else [])
    try:
        r = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    except OSError as ex:
        raise ConfigError("cannot run %s: %s" % (exe, ex))
    if r.returncode != 0:
        lines = [x[len("hexaglide config: "):] if x.startswith("hexaglide config: ") else x
                 for x in r.stderr.strip().splitlines()] or ["hexaglide config: exit %d" % r.returncode]
        text = ("\nhexaglide %s: " % cmd).join(lines)
        if set_option != "--set":
            text = text.replace("(--set ", "(%s " % set_option).replace("--set: ", "%s: " % set_option) \
                .replace("with what --set changed", "with what %s changed" % set_option) \
                .replace("give --set ", "give %s " % set_option)
        if plant_option is None:
            text = re.sub(r": give --plant (\w+)", r": hexaglide %s has no --plant: give a config of the Hexaglide "
                          r"(a [HEXAGLIDE] section)" % cmd, text)
        raise ConfigError(text)
    cfg = Config(path, plant, model)
    for line in r.stdout.splitlines():
        w = line.split()
        if w[0] == "param":
            cfg.params[w[1]] = float(w[2])
        elif w[0] == "joint":
            cfg.joints[int(w[1])][w[2]] = float(w[3])
        elif w[0] == "axis":
            cfg.axes[w[1]][w[2]] = float(w[3])
        elif w[0] == "servo_period_ns":
            cfg.servo_period_ns = float(w[1])
    return cfg


DAC_V = 10.0      # the board's DAC: +-10 V
GAIN_FORMAT = "%.6g"   # how a tune suggestion's INI text prints a gain


def as_printed(gains, keys):
    """Gains (one dict per joint) with the entries named in keys as GAIN_FORMAT prints them, read
    back: a suggestion is predicted for the numbers the user gets (`tune --gains` of the output
    repeats the prediction number for number)."""
    return [dict(g, **{k: float(GAIN_FORMAT % g[k]) for k in keys if k in g}) for g in gains]


def output_limit(g):
    """pid.N.output's reach for joint g ([JOINT_N] keys as read(loop=True) gives them): MAX_OUTPUT,
    or where it is 0 (pid.c: no limit) the DAC's 10 V."""
    return g.get("MAX_OUTPUT", 0.0) or DAC_V


def drive_limit(g):
    """The DAC volts joint g can drive either way: pid.N.output within output_limit, on the DAC as
    (output - OUTPUT_OFFSET) x OUTPUT_SCALE (configs/hexaglide.hal's dac gain and offset), inside
    the DAC's 10 V."""
    if not g.get("MAX_OUTPUT", 0.0):
        return DAC_V
    return min(DAC_V, max(0.0, (g["MAX_OUTPUT"] - abs(g.get("OUTPUT_OFFSET", 0.0))) * abs(g.get("OUTPUT_SCALE", 1.0))))


def check_period(cfg, cmd, period_s, why):
    """ConfigError when cfg's [EMCMOT]SERVO_PERIOD is given and is not period_s (s): cmd
    ("tune") works at that period only; why: what would go wrong at another."""
    ns = int(round(period_s * 1e9))
    if cfg.servo_period_ns is not None and cfg.servo_period_ns != ns:
        raise ConfigError("%s: [EMCMOT]SERVO_PERIOD = %.0f (ns): %s works at a %g ms servo period only "
                          "(SERVO_PERIOD = %d): %s; give an INI with SERVO_PERIOD = %d"
                          % (cfg.path, cfg.servo_period_ns, cmd, period_s * 1e3, ns, why, ns))


def plant_params(path, plant="serial", model=None):
    """hg.PlantParams of `plant` and `model` from the INI's plant section ([SERIAL]: keys in the HAL
    unit, as the CLI's --ini and the HAL file's setp lines read them; the rest the defaults), by
    read(): ValueError (ConfigError) with the C reader's message naming the file, line, section and
    key for a missing section, an unknown key, a key in lower case or given twice, a value that is
    not a finite number, a refused parameter."""
    hg.PlantParams(plant, model)       # an unknown plant or model: ValueError naming it
    return read(path, cmd="plant_params", plant=plant, model=model).params
