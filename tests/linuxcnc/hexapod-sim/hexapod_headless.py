#!/usr/bin/python3
"""hexapod_headless.py - the operator of tests/linuxcnc/test_hexapod_sim in
place of AXIS: estop reset, machine on, home all, run $HG_PROGRAM, sampling
the pose (actual_position) and the joints (pos-fb) at every poll of the
status; then the sample's kinematics switches by MDI (M429 identity, a
move, M428 back, a move home, M430); writes $HG_OUT/$HG_TAG.json and asks
LinuxCNC to shut down."""
import json
import os
import sys
import time

import hal
import linuxcnc

c, s, e = linuxcnc.command(), linuxcnc.stat(), linuxcnc.error_channel()
comp = hal.component("hexapod-headless")    # hal.get_value needs a component
comp.ready()
out = {"messages": [], "samples": []}


def drain():
    """LinuxCNC's error and text messages so far, into out["messages"]."""
    while True:
        m = e.poll()
        if not m:
            return
        out["messages"].append(m[1].strip())


def wait(cond, seconds, sample=False):
    """Poll the status until cond() or seconds; True if cond() held."""
    t0 = time.time()
    while time.time() - t0 < seconds:
        s.poll()
        drain()
        if sample:
            out["samples"].append(list(s.actual_position[:6]) + [j["input"] for j in s.joint[:6]])
        if cond():
            return True
        time.sleep(0.02)
    return False


def snapshot():
    """The pose, the joints, hexaglidekins' skgui pose and kinstype.is-* pins."""
    s.poll()
    return {"pose": list(s.actual_position[:6]), "joints": [j["input"] for j in s.joint[:6]],
            "skgui": [hal.get_value("skgui." + a) for a in "xyzabc"],
            "kinstype": [int(hal.get_value("kinstype.is-%d" % k)) for k in range(3)]}


def mdi(command):
    """One MDI command to its end; a snapshot after it and the messages it caused."""
    before = len(out["messages"])
    c.mdi(command)
    c.wait_complete(30)
    wait(lambda: s.interp_state == linuxcnc.INTERP_IDLE and s.state == linuxcnc.RCS_DONE, 30)
    time.sleep(0.3)                     # the joints settle on the commanded point
    drain()
    snap = snapshot()
    snap["command"] = command
    snap["messages"] = out["messages"][before:]
    return snap


try:
    wait(lambda: s.task_state == linuxcnc.STATE_ESTOP, 10)
    c.state(linuxcnc.STATE_ESTOP_RESET)
    c.state(linuxcnc.STATE_ON)
    out["machine_on"] = wait(lambda: s.task_state == linuxcnc.STATE_ON, 10)
    c.mode(linuxcnc.MODE_MANUAL)
    c.wait_complete()
    c.teleop_enable(0)
    c.wait_complete()
    c.home(-1)
    out["homed"] = wait(lambda: all(s.homed[:6]), 30)
    out["home"] = snapshot()
    c.mode(linuxcnc.MODE_AUTO)
    c.wait_complete()
    c.program_open(os.environ["HG_PROGRAM"])
    c.wait_complete()
    c.auto(linuxcnc.AUTO_RUN, 0)
    out["started"] = wait(lambda: s.interp_state != linuxcnc.INTERP_IDLE, 5)
    out["ended"] = wait(lambda: s.interp_state == linuxcnc.INTERP_IDLE, 120, sample=True)
    out["end"] = snapshot()
    out["task_state_end"] = s.task_state
    c.mode(linuxcnc.MODE_MDI)
    c.wait_complete()
    out["switch"] = [mdi(m) for m in ("M429", "G0 X0.5 Z-0.3 B0.4", "M428", "G0 X0 Y0 Z0 A0 B0 C0")]
    out["switch"].append(mdi("M430"))
    c.abort()
    c.wait_complete()
    c.mode(linuxcnc.MODE_MDI)
    c.wait_complete()
    out["switch"].append(mdi("G0 X0.2"))    # after the refusal: the Hexaglide's kinematics still in force
except Exception as ex:  # reported, not raised: the test reads the JSON
    out["exception"] = repr(ex)
drain()
with open(os.path.join(os.environ["HG_OUT"], os.environ["HG_TAG"] + ".json"), "w") as f:
    json.dump(out, f)
c.state(linuxcnc.STATE_OFF)
sys.exit(0)
