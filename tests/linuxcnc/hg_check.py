"""hg_check.py - helpers of the tests/linuxcnc checks: TAP lines and the
front end's outputs (TAG.json, TAG.csv written by tools/headless/hexaglide_headless.py)."""
import json
import sys

import numpy as np


def check(ok, what):
    """Print one TAP line; return ok."""
    print(("ok - " if ok else "not ok - ") + what)
    return bool(ok)


def report(stem):
    """The front end's JSON report, or exit after a failed check."""
    try:
        with open(stem + ".json") as f:
            return json.load(f)
    except Exception as ex:
        check(False, "front end wrote its report %s.json: %s" % (stem, ex))
        sys.exit(0)


def samples(stem):
    """Sampled pins as a function name -> column, or exit after a failed check."""
    try:
        with open(stem + ".csv") as f:
            names = f.readline().strip().split(",")
        d = np.loadtxt(stem + ".csv", delimiter=",", skiprows=1, ndmin=2)
    except Exception as ex:
        check(False, "sampled data %s.csv: %s" % (stem, ex))
        sys.exit(0)
    return lambda n: d[:, names.index(n)]


def fault_checks(r, joint, says, end_pose, mdi_pose, rc):
    """Checks of a scenario-fault report (tools/headless/hexaglide_headless.py):
    LinuxCNC says "joint <joint> <says>", trips (motion and every drive off),
    aborts the program before its end pose, and after the fault is cleared
    the machine switches on, homes and does the MDI move to mdi_pose; rc is
    LinuxCNC's exit code. Returns the trip time in ms or None."""
    check(not r.get("exception"), "no exception in the front end: %s" % r.get("exception"))
    check(abs(r.get("moving_before_fault", 0)) > 0.1,
          "machine was moving when the fault came (%.3g mm/s)" % r.get("moving_before_fault", 0))
    ms = r.get("fault_to_trip_ms")
    check(ms is not None, "motion.motion-enabled fell %s ms (simulated) after the fault" % ms)
    want = "joint %d %s" % (joint, says)
    errs = r.get("trip_errors", [])
    check(any(want in e for e in errs), "LinuxCNC says '%s': %s" % (want, errs))
    check(r.get("enabled") is False and r.get("task_state") != 4,
          "machine no longer on (task_state %s, enabled %s)" % (r.get("task_state"), r.get("enabled")))
    check(r.get("amp_enable") == [False] * 6, "every joint.N.amp-enable-out off: %s" % r.get("amp_enable"))
    pose = r.get("pose_at_trip", end_pose)
    far = max(abs(a - b) for a, b in zip(pose, end_pose))
    check(r.get("interp_idle") is True and far > 1.0,
          "program stopped: interpreter idle, %.1f mm/deg short of the end pose %s" % (far, end_pose))
    check(r.get("on_again") is True, "after clearing the fault the machine switches on")
    check(r.get("rehome_wall_s") is not None, "and homes again (%s s wall)" % r.get("rehome_wall_s"))
    pm = r.get("pose_after_mdi", [99] * 6)
    check(max(abs(a - b) for a, b in zip(pm, mdi_pose)) <= 0.01 and not r.get("recovery_errors"),
          "MDI '%s' reaches %s within 0.01 (got %s; errors %s)"
          % (r.get("mdi"), mdi_pose, [round(v, 4) for v in pm], r.get("recovery_errors")))
    check(rc == 0, "LinuxCNC exited cleanly (exit %d)" % rc)
    return ms
