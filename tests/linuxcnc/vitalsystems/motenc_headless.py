#!/usr/bin/python3
"""motenc_headless.py - scripted front end of the stock MOTENC config on the
virtual board with a serial-axis machine (motenc_headless.ini). It does what
an operator does in tklinuxcnc and writes what happened to
$HG_OUT/$HG_TAG.json (and the program's samples to $HG_OUT/$HG_TAG.csv):

 1. estop reset, machine on (the stock wiring: iocontrol's user-enable-out
    on out-07 closes the board's E-STOP loop, estop-in-not feeds
    emc-enable-in);
 2. unhomed, jog joint 0 + at 0.1 in/s into its limit+ switch (in-01);
    what LinuxCNC says and does; machine on, override limits, jog back off;
 3. home joints 2, 0, 1 (then 3.. in ../vitalsystems6) one by one (the stock INI has no HOME_SEQUENCE):
    home switch, back off at the latch speed, the encoder index;
 4. run HG_PROGRAM, sampling joint.N.f-error and vel-cmd every servo period,
    with the stock gains, then again with velocity feed-forward FF1 from the
    INI's OUTPUT_SCALE and the amplifiers' V_RATED ($HG_TAG_ff1.csv);
 5. E-STOP from LinuxCNC (the board's loop opens, its amplifiers go off),
    reset and on; then the board's E-STOP button during an MDI move
    (LinuxCNC sees emc-enable-in drop and goes to ESTOP), release, reset, on.
The test (tests/linuxcnc/test_motenc_stock) judges the JSON.

HG_SCENARIO=program (tests/linuxcnc/test_serial_identify, test_serial_tune):
only HG_SETP ("pin value;pin value...", set before estop reset: a hidden
machine, gains under test), steps 1, 3 and one run of HG_PROGRAM, sampled
unless the board's recorder runs (HG_RECORD: it takes `sampler`).
"""
import json
import os
import subprocess
import sys
import time

import hal
import linuxcnc

B, X = "motenc.0", "motenc-hexaglide.0"
OUT = os.environ.get("HG_OUT", "../out")
TAG = os.environ.get("HG_TAG", "motenc_stock")
PROGRAM = os.environ.get("HG_PROGRAM", "serial_mill.ngc")
# the joints: 3 in the stock config, 6 in ../vitalsystems6 (its continuation)
NJ = int(linuxcnc.ini(os.environ["INI_FILE_NAME"]).find("KINS", "JOINTS"))
# LinuxCNC's sampler takes at most 21 pins: the machine's positions only when they fit
SAMPLED = ["joint.%d.f-error" % j for j in range(NJ)] + ["joint.%d.vel-cmd" % j for j in range(NJ)] + \
          (["%s.joint-%d.pos" % (X, j) for j in range(NJ)] if 4 * NJ <= 21 else []) + \
          ["joint.%d.motor-pos-cmd" % j for j in range(NJ)]

s = linuxcnc.stat()
c = linuxcnc.command()
e = linuxcnc.error_channel()
messages = []
result = {"messages": messages}


def log(*a):
    print("motenc_headless:", *a, file=sys.stderr, flush=True)


def halcmd(*args):
    r = subprocess.run(["halcmd"] + list(args), capture_output=True, text=True)
    if r.returncode:
        raise RuntimeError("halcmd %s: %s" % (" ".join(args), r.stderr.strip()))
    return r.stdout


def g(name):
    return hal.get_value(name)


def drain():
    while True:
        m = e.poll()
        if not m:
            return
        messages.append(m[1])
        log("message:", m[1])


def wait(cond, timeout):
    t0 = time.time()
    while time.time() - t0 < timeout:
        s.poll()
        drain()
        if cond():
            return True
        time.sleep(0.01)
    s.poll()
    return cond()


def board():
    return {"pos_mm": [g("%s.joint-%d.pos" % (X, j)) for j in range(NJ)],
            "motor_pos_mm": [g("%s.joint-%d.motor-pos" % (X, j)) for j in range(NJ)],
            "amps_on": bool(g(X + ".amps-on")), "estop_in": bool(g(B + ".estop-in")),
            "fault": bool(g(X + ".fault")), "param_error": bool(g(X + ".param-error"))}


def machine_on():
    c.state(linuxcnc.STATE_ESTOP_RESET)
    ok = wait(lambda: s.task_state == linuxcnc.STATE_ESTOP_RESET, 5)
    c.state(linuxcnc.STATE_ON)
    return ok and wait(lambda: s.task_state == linuxcnc.STATE_ON and s.enabled, 5)


def manual():
    c.mode(linuxcnc.MODE_MANUAL)
    wait(lambda: s.task_mode == linuxcnc.MODE_MANUAL, 5)


def step_estop_start():
    wait(lambda: s.task_state == linuxcnc.STATE_ESTOP, 10)   # task's first status
    result["start"] = {"task_state": s.task_state, "board": board(),
                       "params": {k: g("%s.joint-%s" % (X, k)) for k in
                                  ("0.mass", "1.mass", "2.mass", "2.counterbalance", "0.lead", "1.counts-per-rev",
                                   "0.home-switch", "0.limit-max", "0.kp-vel")},
                       "substeps_run": g(X + ".substeps-run")}
    result["machine_on"] = machine_on()
    result["on"] = {"board": board(), "out07": bool(g(B + ".out-07")),
                    "emc_enable_in": bool(g("iocontrol.0.emc-enable-in"))}


def step_limit():
    manual()
    c.teleop_enable(0)
    t0 = time.time()
    c.jog(linuxcnc.JOG_CONTINUOUS, True, 0, 0.1)
    hit = wait(lambda: g(B + ".in-01"), 10)
    at = board()["pos_mm"][0]
    time.sleep(0.5)
    drain()
    s.poll()
    r = {"switch_seen": hit, "seconds": time.time() - t0, "pos_at_switch_mm": at, "board_after": board(),
         "enabled_after": bool(s.enabled), "task_state_after": s.task_state,
         "amp_enable_out": bool(g("joint.0.amp-enable-out")), "pos_lim_sw_in": bool(g("joint.0.pos-lim-sw-in")),
         "messages": list(messages)}
    c.jog(linuxcnc.JOG_STOP, True, 0)
    r["machine_on_on_the_switch"] = machine_on()      # refused while the switch is on, unless overridden
    c.override_limits()
    time.sleep(0.1)
    r["machine_on_overridden"] = machine_on()
    manual()
    c.teleop_enable(0)
    c.override_limits()
    time.sleep(0.1)
    c.jog(linuxcnc.JOG_CONTINUOUS, True, 0, -0.1)
    r["released"] = wait(lambda: not g(B + ".in-01"), 10)
    time.sleep(0.5)
    c.jog(linuxcnc.JOG_STOP, True, 0)
    time.sleep(0.3)
    r["pos_backed_off_mm"] = board()["pos_mm"][0]
    drain()
    s.poll()
    r["enabled_end"] = bool(s.enabled)
    result["limit"] = r


def step_home():
    manual()
    c.teleop_enable(0)
    homes = {}
    for j in (2, 0, 1) + tuple(range(3, NJ)):    # Z first, as an operator would
        t0 = time.time()
        c.home(j)
        ok = wait(lambda: s.homed[j], 30)
        time.sleep(0.3)
        s.poll()
        b = board()
        homes[j] = {"homed": bool(ok), "seconds": round(time.time() - t0, 2), "plant_pos_mm": b["pos_mm"][j],
                    "plant_motor_pos_mm": b["motor_pos_mm"][j],
                    "joint_pos_fb_in": g("joint.%d.motor-pos-fb" % j),
                    "joint_pos_cmd_in": g("joint.%d.motor-pos-cmd" % j)}
        log("joint", j, homes[j])
    result["home"] = homes


class Sampler:
    """sampler on the servo thread (SAMPLED, enabled by a signal); start(path) .. finish()
    writes one CSV of a run."""

    def __init__(self):
        pins = {}
        for line in halcmd("-s", "show", "pin").splitlines():
            f = line.split()
            if len(f) >= 5:
                pins[f[4]] = f[5:7] if len(f) >= 7 and f[5] in ("==>", "<==", "<=>") else None
        halcmd("loadrt", "sampler", "depth=60000", "cfg=" + "f" * len(SAMPLED))
        halcmd("newsig", "hgs-enable", "bit")
        for i, p in enumerate(SAMPLED):
            sig = pins[p][1] if pins.get(p) else "hgs-" + p
            if not pins.get(p):
                halcmd("net", sig, p)
            halcmd("net", sig, "sampler.0.pin.%d" % i)
        halcmd("net", "hgs-enable", "sampler.0.enable")
        halcmd("addf", "sampler.0", "servo-thread")

    def enable(self, on):
        halcmd("sets", "hgs-enable", "1" if on else "0")

    def start(self, path):
        self.path = path
        self.raw = open(path + ".raw", "w")
        self.proc = subprocess.Popen(["halsampler", "-c", "0"], stdout=self.raw)
        self.enable(True)

    def finish(self):
        self.enable(False)
        for _ in range(100):
            if int(float(g("sampler.0.curr-depth"))) == 0:
                break
            time.sleep(0.05)
        time.sleep(0.2)
        self.proc.terminate()
        self.proc.wait(5)
        self.raw.close()
        with open(self.path, "w") as out, open(self.path + ".raw") as src:
            out.write(",".join(SAMPLED) + "\n")
            for line in src:
                f = line.split()
                if len(f) == len(SAMPLED):
                    out.write(",".join(f) + "\n")
        os.remove(self.path + ".raw")


SAMPLER = []


def run_program(path):
    if path is None:                       # unsampled (the recorder has sampler)
        sm = None
    else:
        if not SAMPLER:
            SAMPLER.append(Sampler())
        sm = SAMPLER[0]
    c.mode(linuxcnc.MODE_AUTO)
    wait(lambda: s.task_mode == linuxcnc.MODE_AUTO, 5)
    n0 = len(messages)
    c.program_open(PROGRAM)
    if sm:
        sm.start(path)
    t0 = time.time()
    c.auto(linuxcnc.AUTO_RUN, 0)
    wait(lambda: s.interp_state != linuxcnc.INTERP_IDLE, 5)
    done = wait(lambda: s.interp_state == linuxcnc.INTERP_IDLE, 120)
    secs = time.time() - t0
    time.sleep(0.3)
    if sm:
        sm.finish()
    s.poll()
    drain()
    return {"done": done, "seconds": round(secs, 2), "axis_pos_in": list(s.actual_position[:NJ]),
            "board": board(), "enabled": bool(s.enabled), "messages_during": messages[n0:]}


def step_program():
    """The program with the stock gains."""
    result["program"] = run_program(os.path.join(OUT, TAG + ".csv"))


def step_program_only():
    """HG_SCENARIO=program: the program once, sampled unless the recorder runs."""
    result["program"] = run_program(None if os.environ.get("HG_RECORD") else os.path.join(OUT, TAG + ".csv"))


def step_program_ff1():
    """Again with velocity feed-forward FF1 = 1 / (OUTPUT_SCALE V_RATED / 10 V): the
    velocity-mode amplifier's speed per PID output unit, from the INI."""
    ini = linuxcnc.ini(os.environ["INI_FILE_NAME"])
    ff1 = []
    for j in range(NJ):
        v_rated_in = float(ini.find("SERIAL", "V_RATED_%d" % j)) / 25.4
        ff1.append(10.0 / (float(ini.find("JOINT_%d" % j, "OUTPUT_SCALE")) * v_rated_in))
        halcmd("setp", "pid.%d.FF1" % j, repr(ff1[-1]))
    r = run_program(os.path.join(OUT, TAG + "_ff1.csv"))
    r["ff1"] = ff1
    for j in range(NJ):
        halcmd("setp", "pid.%d.FF1" % j, ini.find("JOINT_%d" % j, "FF1"))
    result["program_ff1"] = r


def step_estop():
    r = {}
    c.state(linuxcnc.STATE_ESTOP)
    wait(lambda: s.task_state == linuxcnc.STATE_ESTOP, 5)
    time.sleep(0.2)
    r["lcnc"] = {"task_state": s.task_state, "user_enable_out": bool(g("iocontrol.0.user-enable-out")),
                 "out07": bool(g(B + ".out-07")), "board": board()}
    r["on_after_lcnc"] = machine_on()
    r["amps_on_after_lcnc"] = board()["amps_on"]
    c.mode(linuxcnc.MODE_MDI)
    wait(lambda: s.task_mode == linuxcnc.MODE_MDI, 5)
    c.mdi("G20 G90 G1 X-3 Y-1 Z-0.5 F45")
    wait(lambda: s.interp_state != linuxcnc.INTERP_IDLE, 5)
    time.sleep(1.0)
    moving_at = board()["pos_mm"]
    hal.set_p(X + ".estop-button", "1")
    t0 = time.time()
    seen = wait(lambda: s.task_state == linuxcnc.STATE_ESTOP, 5)
    dt = time.time() - t0
    at = board()
    time.sleep(1.0)
    s.poll()
    drain()
    later = board()
    r["button"] = {"moving_at_mm": moving_at, "estop_seen": seen, "seconds": round(dt, 3), "board_at": at,
                   "board_1s_later": later, "emc_enable_in": bool(g("iocontrol.0.emc-enable-in")),
                   "estop_in_not": bool(g(B + ".estop-in-not")), "interp_idle": s.interp_state == linuxcnc.INTERP_IDLE,
                   "amp_enable_out": [bool(g("joint.%d.amp-enable-out" % j)) for j in range(NJ)]}
    r["on_while_pressed"] = machine_on()
    hal.set_p(X + ".estop-button", "0")
    time.sleep(0.1)
    r["on_after_release"] = machine_on()
    r["amps_on_end"] = board()["amps_on"]
    result["estop"] = r


def main():
    rc = 1
    comp = hal.component("motenc_headless")    # hal.get_value needs a component
    comp.ready()
    try:
        steps = (step_estop_start, step_limit, step_home, step_program, step_program_ff1, step_estop)
        if os.environ.get("HG_SCENARIO") == "program":
            for item in filter(None, os.environ.get("HG_SETP", "").split(";")):
                halcmd("setp", *item.split())
            steps = (step_estop_start, step_home, step_program_only)
        for step in steps:
            log(step.__name__)
            step()
        rc = 0
    except Exception as ex:  # reported, the test fails on it
        import traceback
        result["exception"] = traceback.format_exc()
        log(result["exception"])
    drain()
    result["messages"] = messages
    with open(os.path.join(OUT, TAG + ".json"), "w") as f:
        json.dump(result, f, indent=1, default=str)
    try:
        c.state(linuxcnc.STATE_ESTOP)
    except Exception:
        pass
    return rc


if __name__ == "__main__":
    sys.exit(main())
