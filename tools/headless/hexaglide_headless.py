#!/usr/bin/python3
"""hexaglide_headless.py - scripted, display-less LinuxCNC front end.

LinuxCNC starts it as the DISPLAY of hexaglide_headless.ini; its exit code
becomes LinuxCNC's. It does what an operator does in AXIS: reset estop,
machine on, home all joints (switch + index), run a G-code program, and
reports the outcome. Optionally it samples HAL pins at servo rate with
sampler/halsampler and writes them as CSV.

Settings (environment):
  HG_OUT        output directory (default ../out)
  HG_PROGRAM    G-code file to run (default nc_files/hexaglide_logo.ngc)
  HG_SCENARIO   run     home, run the program            (default)
                estop   home, run, press estop HG_ESTOP_AFTER s into the program
                refuse  home, run a program that must be refused
                home    home only
                fault   home, run, set HG_FAULT HG_FAULT_AFTER s into the program,
                        wait for LinuxCNC to trip, clear the fault, machine on,
                        home again, one MDI move (docs/reliability.md)
  HG_SAMPLE     1: sample HAL pins to HG_OUT/HG_TAG.csv (default 1; 0 when
                HG_RECORD is set: the replay recorder has `sampler`)
  HG_SAMPLE_EXTRA  more pins to sample, space separated
  HG_TAG        file name stem of outputs (default: the scenario)
  HG_TIMEOUT    seconds allowed for the program (default 300)
  (a program standing 2 s waiting for a spindle this machine cannot report,
  G33/G33.1/G76 or G95 with no spindle feedback, is aborted with a message
  naming the cause: LinuxCNC would wait forever without one)
  HG_ON_PAUSE   resume  a pause the program makes (M0, M1) is resumed as an
                        operator would (default; "pauses" lists LinuxCNC's
                        line then: that of the last move before it)
                stop    it ends the run with an error naming the line
  HG_FEED_OVERRIDE  feed override set before the program (an operator's
                slider; LinuxCNC bounds it by [DISPLAY]MAX_FEED_OVERRIDE)
  HG_SETP       "pin value;pin value..." set with halcmd before estop reset
  HG_ESTOP_AFTER  seconds (default 2); estop = the board's E-STOP button
                (motenc-hexaglide.0.estop-button), released afterwards and
                the machine switched on again
  HG_FAULT      "pin value;pin value..." set at once (hal.set_p) in scenario
                fault, e.g. "motenc-hexaglide.0.joint-1.amp-fail 1"
  HG_FAULT_AFTER  seconds into the program (default 1.5)
  HG_FAULT_UNLINK pins disconnected from their signals before the program
                and connected again for the recovery, e.g. joint.1.amp-fault-in:
                a drive whose fault output is not wired
  HG_FAULT_ON_AGAIN 1: try machine on while the fault is still there
  HG_FAULT_MDI  the recovery's MDI move (default "G90 G1 X5 Y-5 Z5 F600")
Outputs: HG_OUT/HG_TAG.json (verdict, positions, errors, the program's own
messages ((MSG,...), (DEBUG,...): "messages", not errors), timings) and,
with sampling, HG_OUT/HG_TAG.csv (one row per servo period).
"""
import json
import os
import signal
import subprocess
import sys
import time

import hal
import linuxcnc

JOINTS = ["z11", "z12", "z21", "z22", "z31", "z32"]
AXES = "xyzabc"
SERVO_PERIOD_S = 0.001
CLOCK_PIN = "motenc-hexaglide.0.sim-time"  # the virtual board's simulated time (s)
# hexaglidekins' message when its geometry and the board's differ (src/hexaglidekins.c): a run that
# saw it drove another machine than the one simulated, and is not ok
GEOMETRY_MISMATCH = "hexaglidekins: the geometry differs from the board's"


def log(*a):
    print("hexaglide_headless:", *a, file=sys.stderr, flush=True)


def halcmd(*args, check=True):
    """Run one halcmd command; return its stdout."""
    r = subprocess.run(["halcmd"] + list(args), capture_output=True, text=True)
    if check and r.returncode != 0:
        raise RuntimeError("halcmd %s: %s" % (" ".join(args), r.stderr.strip()))
    return r.stdout


def setp_items(text):
    """'pin value;pin value...' -> [(pin, value)]."""
    return [tuple(item.split()) for item in filter(None, text.split(";"))]


def fk_fault():
    """hexaglidekins.fk-fault (its forward kinematics failing: LinuxCNC shows the last solved
    pose), or None when the config has no such pin (other kinematics)."""
    try:
        return bool(hal.get_value("hexaglidekins.fk-fault"))
    except Exception:          # (hal's error for a name it does not find)
        return None


def sim_time():
    """The virtual board's simulated time, s."""
    return float(hal.get_value(CLOCK_PIN))


def wait_pin(pin, value, timeout):
    """Poll a bit pin every 0.5 ms until it reads value; the simulated time
    then, or None. Resolution: about one servo period."""
    t0 = time.time()
    while time.time() - t0 < timeout:
        if bool(hal.get_value(pin)) == value:
            return sim_time()
        time.sleep(0.0005)
    return None


def pin_table():
    """{pin name: (type, signal or None)} for every HAL pin."""
    pins = {}
    for line in halcmd("-s", "show", "pin").splitlines():
        f = line.split()
        if len(f) < 5:
            continue
        sig = None
        if len(f) >= 7 and f[5] in ("==>", "<==", "<=>"):
            sig = f[6]
        pins[f[4]] = (f[1], sig)
    return pins


def sampled_pins():
    """Pins recorded during a run, in CSV column order; missing ones are skipped."""
    want = []
    for j in range(6):
        want.append("joint.%d.motor-pos-cmd" % j)
    for j in range(6):
        want.append("joint.%d.motor-pos-fb" % j)
    for j in range(6):
        want.append("joint.%d.f-error" % j)
    for j in range(6):
        want.append("pid.%d.output" % j)
    for a in AXES:
        want.append("axis.%s.pos-cmd" % a)
    # the virtual board's view of the machine (docs/driver.md)
    for a in AXES:
        want.append("motenc-hexaglide.0.head-%s" % a)
    want += ["motenc-hexaglide.0.step-time-ns", "motenc-hexaglide.0.fault",
             "motenc-hexaglide.0.amps-on", "motenc-hexaglide.0.residual",
             "motenc-hexaglide.0.tool-error",
             "hexaglidekins.fk-iterations", "hexaglidekins.fk-error",
             "hexaglidekins.fk-fault", "hexaglidekins.fk-fail-count",
             "hexaglidekins.fk-residual",
             "motion.motion-enabled", "halui.program.is-running"]
    want += os.environ.get("HG_SAMPLE_EXTRA", "").split()   # more pins a test asks for
    return want


class Sampler:
    """sampler + halsampler on the servo thread, written out as CSV.

    One sampler FIFO holds at most 20 pins, so the columns are spread over
    several FIFOs that share one enable signal and are joined by sample
    number."""
    TYPE_CHAR = {"float": "f", "bit": "b", "s32": "s", "u32": "u"}
    PER_FIFO = 20

    def __init__(self, raw_stem):
        table = pin_table()
        self.cols = [p for p in sampled_pins() if p in table]
        missing = [p for p in sampled_pins() if p not in table]
        if missing:
            log("not sampled (no such pin):", " ".join(missing))
        # every FIFO also records the simulated time, the key that joins them
        self.key = CLOCK_PIN if CLOCK_PIN in table else None
        per = self.PER_FIFO - (1 if self.key else 0)
        groups = [self.cols[i:i + per] for i in range(0, len(self.cols), per)]
        if self.key:
            groups = [[self.key] + g for g in groups]
        self.groups = groups
        cfgs = ["".join(self.TYPE_CHAR[table[p][0]] for p in g) for g in groups]
        halcmd("loadrt", "sampler", "depth=" + ",".join(["30000"] * len(groups)),
               "cfg=" + ",".join(cfgs))
        halcmd("newsig", "hg-sample-enable", "bit")
        for f, g in enumerate(groups):
            for i, p in enumerate(g):
                sig = table[p][1]
                if sig is None:
                    sig = "hg-sample-" + p
                    halcmd("net", sig, p)
                    table[p] = (table[p][0], sig)
                halcmd("net", sig, "sampler.%d.pin.%d" % (f, i))
            halcmd("net", "hg-sample-enable", "sampler.%d.enable" % f)
            halcmd("addf", "sampler.%d" % f, "servo-thread")
        self.raw_paths = ["%s.%d.raw" % (raw_stem, f) for f in range(len(groups))]
        self.raw = [open(r, "w") for r in self.raw_paths]
        self.procs = [subprocess.Popen(["halsampler", "-t", "-c", str(f)], stdout=self.raw[f])
                      for f in range(len(groups))]

    def enable(self, on):
        halcmd("sets", "hg-sample-enable", "1" if on else "0")

    def stop(self):
        self.enable(False)
        for _ in range(100):  # let halsampler drain the FIFOs
            if all(int(float(hal.get_value("sampler.%d.curr-depth" % f))) == 0
                   for f in range(len(self.groups))):
                break
            time.sleep(0.05)
        time.sleep(0.2)
        for p in self.procs:
            p.send_signal(signal.SIGINT)
        for p in self.procs:
            try:
                p.wait(5)
            except subprocess.TimeoutExpired:
                p.kill()
        for r in self.raw:
            r.close()

    def read_raw(self, path):
        """{key: [values]} of one halsampler file; the key is the simulated
        time in microseconds (or the sample number without the board)."""
        rows = {}
        with open(path) as src:
            for line in src:
                f = line.split()
                if len(f) < 2 or f[0] == "overrun":
                    continue
                if self.key:
                    rows[int(round(float(f[1]) * 1e6))] = f[2:]
                else:
                    rows[int(f[0])] = f[1:]
        return rows

    def write_csv(self, csv_path):
        """Raw halsampler text -> CSV with a time column; returns (rows, gaps,
        the largest |joint.N.f-error| per joint while halui.program.is-running,
        None without those columns or a running program)."""
        parts = [self.read_raw(p) for p in self.raw_paths]
        keys = sorted(set(parts[0]).intersection(*parts[1:]))
        step = 1000 if self.key else 1
        gaps = sum(1 for a, b in zip(keys, keys[1:]) if b - a > step)
        fcols = ["joint.%d.f-error" % j for j in range(6)]
        watch = None
        if all(c in self.cols for c in fcols + ["halui.program.is-running"]):
            watch = [self.cols.index(c) for c in fcols], self.cols.index("halui.program.is-running")
        fmax = None
        with open(csv_path, "w") as dst:
            dst.write("t_s," + ",".join(self.cols) + "\n")
            first = keys[0] if keys else 0
            for n in keys:
                vals = []
                for part in parts:
                    vals += part[n]
                dst.write("%.3f,%s\n" % ((n - first) * (1e-6 if self.key else SERVO_PERIOD_S),
                                          ",".join(vals)))
                if watch and int(float(vals[watch[1]])):
                    fe = [abs(float(vals[i])) for i in watch[0]]
                    fmax = fe if fmax is None else [max(a, b) for a, b in zip(fmax, fe)]
        for p in self.raw_paths:
            os.unlink(p)
        return len(keys), gaps, fmax


# LinuxCNC's error channel carries errors and the program's own messages
# ((MSG,...), (DEBUG,...), M-code texts): only these kinds are errors
ERROR_KINDS = (linuxcnc.NML_ERROR, linuxcnc.OPERATOR_ERROR)


COMMAND_S = 30.0  # wall seconds task may take to answer a command (wait_complete; LinuxCNC's default is 5)
STALL_S = 2.0   # simulated seconds a program may stand on the spindle before it is aborted


def spindle_wait(s):
    """What the running program stands still waiting for: "index", "speed"
    or None. LinuxCNC starts a spindle-synchronized move (G33, G33.1, G76)
    at the spindle's index (spindle.0.index-enable, cleared by its encoder)
    and feeds a G95 move by the measured speed (spindle.0.speed-in): with
    neither connected (a config without configs/hexaglide.hal's virtual
    spindle), it waits forever and says nothing."""
    if s.queue == 0:
        return None
    if hal.get_value("spindle.0.index-enable"):
        return "index"
    if 950 in s.gcodes and float(hal.get_value("spindle.0.speed-in")) == 0.0:
        return "speed"
    return None


def spindle_wait_text(kind, s):
    """The message for spindle_wait's kind, naming the line and the pin."""
    pin = "spindle.0.index-enable" if kind == "index" else "spindle.0.speed-in"
    wired = pin_table().get(pin, (None, None))[1] is not None
    if kind == "index":
        return ("the program waits for the spindle's index pulse to start a spindle-synchronized move "
                "(G33, G33.1, G76) after line %d: %s is %s" % (
                    s.motion_line, pin, "never answered by the encoder" if wired
                    else "not connected, this machine has no spindle encoder"))
    return ("the move of line %d has no feed: feed per revolution (G95) with the measured spindle speed "
            "%s at 0 (%s)" % (s.motion_line, pin, "the spindle stands" if wired
                              else "not connected, this machine has no spindle encoder"))


def not_taken(what, timeout):
    """The error for a command LinuxCNC's task did not take within timeout s."""
    return RuntimeError("%s: LinuxCNC's task did not take the command within %.0f s (a host too loaded for "
                        "LinuxCNC? its log may say 'USRMOT: ERROR: command timeout'): this run proves nothing; "
                        "run it again on a quieter host" % (what, timeout))


class Machine:
    def __init__(self):
        self.s = linuxcnc.stat()
        self.c = linuxcnc.command()
        self.e = linuxcnc.error_channel()
        self.errors = []
        self.messages = []     # what the program displays: not errors

    def poll(self):
        self.s.poll()
        while True:
            m = self.e.poll()
            if not m:
                break
            kind, text = m
            if kind in ERROR_KINDS:
                self.errors.append(text)
                log("LinuxCNC says:", text)
            else:
                self.messages.append(text)
                log("LinuxCNC displays:", text)
        return self.s

    def wait(self, cond, timeout, what, fail_on_error=False):
        t0 = time.time()
        n_err = len(self.errors)
        while time.time() - t0 < timeout:
            self.poll()
            if cond(self.s):
                return True
            if fail_on_error and len(self.errors) > n_err:
                raise RuntimeError("%s: LinuxCNC reported: %s" % (what, self.errors[n_err]))
            if fail_on_error and self.s.task_state != linuxcnc.STATE_ON:
                raise RuntimeError("%s: machine is no longer on (task_state %d; errors %s)"
                                   % (what, self.s.task_state, self.errors))
            time.sleep(0.05)
        raise TimeoutError("%s: not reached within %.0f s" % (what, timeout))

    def done(self, what, timeout=COMMAND_S):
        """Wait until LinuxCNC's task has taken the command just sent (what: what it was, for
        the message). A command task does not answer is raised, not passed over: under a host
        too loaded for LinuxCNC (its log then says "USRMOT: ERROR: command timeout") a lost
        mode change or program start would otherwise end in a verdict of ok for a program that
        never moved the machine. A command task refuses (RCS_ERROR) is said on the error
        channel, which poll() reads, as before."""
        if self.c.wait_complete(timeout) == -1:
            raise not_taken(what, timeout)

    def taken(self, what, before, timeout=None):
        """Wait until task has received the command sent after its echo serial number was
        `before` (AUTO_RUN: wait_complete would wait for the program's end, the command runs
        as long as the program); raised as done() raises when it does not."""
        t0, timeout = time.time(), COMMAND_S if timeout is None else timeout
        while self.poll().echo_serial_number == before:
            if time.time() - t0 > timeout:
                raise not_taken(what, timeout)
            time.sleep(0.01)

    def on(self):
        self.c.state(linuxcnc.STATE_ESTOP_RESET)
        self.wait(lambda s: s.task_state == linuxcnc.STATE_ESTOP_RESET, 10, "estop reset")
        self.c.state(linuxcnc.STATE_ON)
        self.wait(lambda s: s.task_state == linuxcnc.STATE_ON, 10, "machine on")

    def home(self, timeout=120):
        self.c.mode(linuxcnc.MODE_MANUAL)
        self.done("manual mode")
        self.c.teleop_enable(0)
        self.done("joint mode (teleop off)")
        self.poll()
        if any(self.s.homed[j] for j in range(6)):  # homing again: forget the old home
            self.c.unhome(-1)
            self.wait(lambda s: not any(s.homed[j] for j in range(6)), 10, "unhome")
        self.c.home(-1)
        self.wait(lambda s: all(s.homed[j] for j in range(6)), timeout, "homing",
                  fail_on_error=True)

    def run_program(self, path):
        self.c.mode(linuxcnc.MODE_AUTO)
        self.done("auto mode")
        if os.environ.get("HG_FEED_OVERRIDE"):
            self.c.feedrate(float(os.environ["HG_FEED_OVERRIDE"]))
            self.done("feed override")
        self.c.program_open(path)
        self.done("open " + path)
        before = self.poll().echo_serial_number
        self.c.auto(linuxcnc.AUTO_RUN, 0)
        self.taken("run " + path, before)

    def run_to_end(self, timeout, on_pause="resume"):
        """Wait until the program has ended (or was refused or aborted).
        A pause the program makes itself (M0, M1 with optional stop on) is
        met as an operator meets it: resumed (cycle start), or with
        on_pause "stop" a RuntimeError naming the line. Returns, for each
        pause, LinuxCNC's current line then: that of the last move before
        the M0/M1."""
        t0 = time.time()
        pauses = []
        stall = None               # simulated time since which the program stands on a spindle
        while True:
            s = self.poll()
            if s.interp_state == linuxcnc.INTERP_IDLE and s.queue == 0 and s.state != linuxcnc.RCS_EXEC:
                return pauses
            why = None if s.paused or s.current_vel != 0.0 else spindle_wait(s)
            if why is None:
                stall = None
            elif stall is None:
                stall = sim_time()
            elif sim_time() - stall >= STALL_S:
                text = spindle_wait_text(why, s)
                self.c.abort()
                self.wait(lambda st: st.interp_state == linuxcnc.INTERP_IDLE, 10, "abort")
                raise RuntimeError("%s; LinuxCNC waits for it with no message: the program was aborted after "
                                   "%.0f s standing still" % (text, STALL_S))
            if s.paused and s.interp_state == linuxcnc.INTERP_PAUSED:
                line = s.current_line      # LinuxCNC's: the line of the last move, before the M0/M1
                if on_pause != "resume":
                    raise RuntimeError("the program paused (M0, M1 or a pause) after line %d and waits for "
                                       "cycle start; HG_ON_PAUSE=resume resumes it as an operator would"
                                       % line)
                log("the program paused (M0, M1) after line %d; resuming as an operator would "
                    "(HG_ON_PAUSE=stop stops instead)" % line)
                pauses.append(line)
                self.c.auto(linuxcnc.AUTO_RESUME)
                self.wait(lambda st: not st.paused, 10, "resume after the pause at line %d" % line)
            if time.time() - t0 > timeout:
                raise TimeoutError("program end: not reached within %.0f s (interpreter state %d, at line %d)"
                                   % (timeout, s.interp_state, s.current_line))
            time.sleep(0.05)

    def mdi(self, line, timeout=30):
        self.c.mode(linuxcnc.MODE_MDI)
        self.done("MDI mode")
        self.c.mdi(line)
        time.sleep(0.3)
        self.wait(lambda s: s.interp_state == linuxcnc.INTERP_IDLE and s.queue == 0
                  and s.state != linuxcnc.RCS_EXEC, timeout, "MDI " + line, fail_on_error=True)

    def joints(self):
        return [self.s.joint[j]["output"] for j in range(6)]

    def joints_fb(self):
        return [self.s.joint[j]["input"] for j in range(6)]


def fault_scenario(m, program, res):
    """Inject HG_FAULT mid-program; record how LinuxCNC trips; recover."""
    faults = setp_items(os.environ.get("HG_FAULT", ""))
    after = float(os.environ.get("HG_FAULT_AFTER", "1.5"))
    table = pin_table()
    relink = [(p, table[p][1]) for p in os.environ.get("HG_FAULT_UNLINK", "").split()]
    for pin, sig in relink:
        halcmd("unlinkp", pin)
    res["unlinked"] = relink
    with open(program) as f:
        res["program_lines"] = len(f.read().splitlines())
    m.run_program(program)
    m.wait(lambda s: s.interp_state != linuxcnc.INTERP_IDLE, 10, "program start")
    time.sleep(after)
    m.poll()
    res["moving_before_fault"] = m.s.current_vel
    res["pose_before_fault"] = list(m.s.actual_position[:6])
    n_err = len(m.errors)
    t_before = sim_time()
    for pin, val in faults:
        hal.set_p(pin, val)
    t_after = sim_time()
    t_trip = wait_pin("motion.motion-enabled", False, 10)
    res["fault_sim_s"] = [t_before, t_after]
    res["trip_sim_s"] = t_trip
    if t_trip is not None:
        res["fault_to_trip_ms"] = [round((t_trip - t_after) * 1e3, 1),
                                   round((t_trip - t_before) * 1e3, 1)]
    m.wait(lambda s: s.task_state != linuxcnc.STATE_ON and s.interp_state == linuxcnc.INTERP_IDLE,
           10, "machine off, interpreter idle")
    time.sleep(0.5)
    m.poll()
    res["trip_errors"] = m.errors[n_err:]
    res["task_state"] = m.s.task_state
    res["enabled"] = bool(m.s.enabled)
    res["interp_idle"] = m.s.interp_state == linuxcnc.INTERP_IDLE
    res["motion_line"] = m.s.motion_line
    res["pose_at_trip"] = list(m.s.actual_position[:6])
    res["ferror_highmark"] = [m.s.joint[j]["ferror_highmark"] for j in range(6)]
    res["amp_enable"] = [bool(hal.get_value("joint.%d.amp-enable-out" % j)) for j in range(6)]
    if os.environ.get("HG_FAULT_ON_AGAIN") == "1":
        # the operator presses machine on with the fault still there
        n_err = len(m.errors)
        m.c.state(linuxcnc.STATE_ESTOP_RESET)
        m.done("E-STOP reset")
        m.c.state(linuxcnc.STATE_ON)
        m.done("machine on")
        time.sleep(1.0)
        m.poll()
        res["on_with_fault_errors"] = m.errors[n_err:]
        res["on_with_fault_stays_on"] = m.s.task_state == linuxcnc.STATE_ON and bool(m.s.enabled)
    # recovery: the fault goes away (amplifier replaced, switch freed)
    for pin, val in faults:
        hal.set_p(pin, "0")
    for pin, sig in relink:
        halcmd("net", sig, pin)
    time.sleep(0.2)
    n_err = len(m.errors)
    m.on()
    res["on_again"] = True
    t0 = time.time()
    m.home()
    res["rehome_wall_s"] = round(time.time() - t0, 2)
    mdi = os.environ.get("HG_FAULT_MDI", "G90 G1 X5 Y-5 Z5 F600")
    m.mdi(mdi)
    time.sleep(0.3)
    m.poll()
    res["mdi"] = mdi
    res["pose_after_mdi"] = list(m.s.actual_position[:6])
    res["recovery_errors"] = m.errors[n_err:]
    res["ok"] = (t_trip is not None and bool(res["trip_errors"]) and not res["enabled"]
                 and res["interp_idle"] and not res["recovery_errors"]
                 and m.s.task_state == linuxcnc.STATE_ON)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = os.path.abspath(os.environ.get("HG_OUT", os.path.join(here, "..", "out")))
    os.makedirs(out, exist_ok=True)
    scenario = os.environ.get("HG_SCENARIO", "run")
    tag = os.environ.get("HG_TAG", scenario)
    program = os.path.abspath(os.environ.get(
        "HG_PROGRAM", os.path.join(here, "nc_files", "hexaglide_logo.ngc")))
    timeout = float(os.environ.get("HG_TIMEOUT", "300"))
    # sampler loads once per HAL session: with the replay recorder
    # (HG_RECORD, tools/hg_record.tcl) it is taken, so no sampling by default
    sample = os.environ.get("HG_SAMPLE", "0" if os.environ.get("HG_RECORD") else "1") == "1"

    def on_term(signum, frame):
        raise KeyboardInterrupt("signal %d" % signum)
    signal.signal(signal.SIGTERM, on_term)

    comp = hal.component("hexaglide_headless")
    comp.ready()
    m = Machine()
    res = {"scenario": scenario, "program": program, "ok": False, "errors": m.errors,
           "messages": m.messages}
    sampler = None
    t_start = time.time()
    try:
        if sample:
            sampler = Sampler(os.path.join(out, tag))
            sampler.enable(True)
        for item in filter(None, os.environ.get("HG_SETP", "").split(";")):
            halcmd("setp", *item.split())  # e.g. gains under test (tools/tune_pid.sh)
        m.poll()
        res["joints_at_start"] = m.joints_fb()
        m.on()
        t0 = time.time()
        m.home()
        res["home_wall_s"] = round(time.time() - t0, 2)
        m.poll()
        res["joints_after_home"] = m.joints_fb()
        res["pose_after_home"] = list(m.s.actual_position[:6])
        log("homed in %.1f s (wall), joints %s" % (res["home_wall_s"], res["joints_after_home"]))
        if scenario == "home":
            res["ok"] = True
        elif scenario in ("run", "estop", "refuse"):
            n_err = len(m.errors)
            m.run_program(program)
            t0 = time.time()
            if scenario == "estop":
                after = float(os.environ.get("HG_ESTOP_AFTER", "2"))
                m.wait(lambda s: s.interp_state != linuxcnc.INTERP_IDLE, 10, "program start")
                time.sleep(after)
                m.poll()
                res["moving_before_estop"] = m.s.current_vel
                res["joints_before_estop"] = m.joints_fb()
                # the operator hits the machine's E-STOP button: the board opens
                # its estop loop (estop-in-not -> iocontrol.0.emc-enable-in)
                halcmd("setp", "motenc-hexaglide.0.estop-button", "1")
                m.wait(lambda s: s.task_state == linuxcnc.STATE_ESTOP, 10, "estop")
                time.sleep(0.5)
                m.poll()
                res["task_state"] = m.s.task_state
                res["estop"] = bool(m.s.estop)
                res["enabled"] = bool(m.s.enabled)
                res["interp_idle"] = m.s.interp_state == linuxcnc.INTERP_IDLE
                res["amp_enable"] = [bool(hal.get_value("joint.%d.amp-enable-out" % j)) for j in range(6)]
                res["pid_output"] = [float(hal.get_value("pid.%d.output" % j)) for j in range(6)]
                res["drive_volts"] = [float(hal.get_value("motenc-hexaglide.0.joint-%d.volts" % j))
                                      for j in range(6)]
                res["board_amps_on"] = bool(hal.get_value("motenc-hexaglide.0.amps-on"))
                # the simulation keeps running: with the drives off the machine sinks
                z0 = float(hal.get_value("motenc-hexaglide.0.joint-0.pos"))
                time.sleep(0.5)
                res["joint0_sank_mm"] = z0 - float(hal.get_value("motenc-hexaglide.0.joint-0.pos"))
                # release the button: the machine can be switched on again
                halcmd("setp", "motenc-hexaglide.0.estop-button", "0")
                time.sleep(0.2)
                m.on()
                m.poll()
                res["on_again"] = m.s.task_state == linuxcnc.STATE_ON
                res["ok"] = (res["estop"] and not res["enabled"] and not any(res["amp_enable"])
                             and all(v == 0.0 for v in res["pid_output"])
                             and all(v == 0.0 for v in res["drive_volts"])
                             and not res["board_amps_on"] and res["on_again"])
            else:
                # wait for the program to start and to finish (or to be refused)
                time.sleep(0.5)
                res["pauses"] = m.run_to_end(timeout, os.environ.get("HG_ON_PAUSE", "resume"))
                res["program_wall_s"] = round(time.time() - t0, 2)
                time.sleep(0.3)
                m.poll()
                res["program_errors"] = m.errors[n_err:]
                res["joints_cmd_end"] = m.joints()
                res["joints_end"] = m.joints_fb()
                res["pose_end"] = list(m.s.actual_position[:6])
                res["task_state"] = m.s.task_state
                # LinuxCNC's own high mark counts from its start: it holds how far
                # the unpowered machine sank before motion took each joint on
                # (0.3-0.9 mm), not the program's following error (ferror_max_program)
                res["ferror_highmark_since_start"] = [m.s.joint[j]["ferror_highmark"] for j in range(6)]
                # the kinematics still failing at the end: the pose LinuxCNC shows is stale (an error
                # said before the program, during homing, is not in program_errors)
                res["fk_fault_end"] = fk_fault()
                # kinematics of another machine than the board simulates (a geometry the board refused,
                # or a setp on one component), said at any time, homing and startup included
                res["geometry_mismatch"] = any(GEOMETRY_MISMATCH in e for e in m.errors)
                if scenario == "run":
                    res["ok"] = (not res["program_errors"] and m.s.task_state == linuxcnc.STATE_ON
                                 and not res["fk_fault_end"] and not res["geometry_mismatch"])
                else:
                    moved = max(abs(a - b) for a, b in zip(res["joints_end"], res["joints_after_home"]))
                    res["moved_mm"] = moved
                    res["ok"] = bool(res["program_errors"]) and m.s.task_state == linuxcnc.STATE_ON
        elif scenario == "fault":
            fault_scenario(m, program, res)
        else:
            res["errors"].append("unknown HG_SCENARIO %r" % scenario)
    except BaseException as ex:  # report, do not hang (SIGTERM from timeout too)
        res["exception"] = "%s: %s" % (type(ex).__name__, ex)
        log(res["exception"])
    finally:
        try:
            m.poll()
            res["fk"] = {k: hal.get_value("hexaglidekins." + k)
                         for k in ("fk-iterations", "fk-fail-count", "fk-fault", "fk-error",
                                   "fk-residual")}
            res["board"] = {k: hal.get_value("motenc-hexaglide.0." + k)
                            for k in ("fault", "fault-code", "steps", "step-time-max-ns",
                                      "sim-time")}
            res["task_state_end"] = m.s.task_state
            res["interp_idle_end"] = m.s.interp_state == linuxcnc.INTERP_IDLE
            # where the simulated head is (beside pose_end, where LinuxCNC says it is)
            res["head_end"] = [hal.get_value("motenc-hexaglide.0.head-" + a) for a in AXES]
        except Exception as ex:
            res["fk"] = "unavailable: %s" % ex
        if sampler:
            sampler.stop()
            rows, gaps, fmax = sampler.write_csv(os.path.join(out, tag + ".csv"))
            res["samples"] = rows
            res["sample_gaps"] = gaps
            res["ferror_max_program"] = fmax   # mm per joint, while the program ran
            res["columns"] = sampler.cols
        res["wall_s"] = round(time.time() - t_start, 2)
        with open(os.path.join(out, tag + ".json"), "w") as f:
            json.dump(res, f, indent=1, default=str)
        try:
            m.c.state(linuxcnc.STATE_ESTOP)
        except Exception:
            pass
    log("verdict:", "ok" if res["ok"] else "FAILED")
    return 0 if res["ok"] else 1


if __name__ == "__main__":
    sys.exit(main())
