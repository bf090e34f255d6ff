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


def serial_joint(ini, j):
    """The stock MOTENC config's joint j on the serial plant (tests/linuxcnc/vitalsystems,
    vitalsystems6), from its INI (a ConfigParser): unit (mm, or deg, per joint unit),
    rev (a motor revolution in mm or deg: LEAD, or 360 / RATIO), the index the homing
    latches (the last one below the home switch: one per motor revolution from where
    the machine stood at power-up), home (the machine's position after homing: the
    index is HOME_OFFSET, then the joint goes to HOME), count (one encoder count),
    Kv (P OUTPUT_SCALE V_RATED / 10 V, 1/s) and the DEADBAND."""
    def f(sec, key):
        return float(ini[sec][key])
    jn = "JOINT_%d" % j
    rotary = ini[jn]["TYPE"].strip().upper() == "ANGULAR"
    unit = 1.0 if rotary else 25.4
    rev = 360.0 / f("SERIAL", "RATIO_%d" % j) if rotary else f("SERIAL", "LEAD_%d" % j)
    index = np.floor(f("SERIAL", "HOME_SWITCH_%d" % j) / rev) * rev
    return {"rotary": rotary, "unit": unit, "rev": rev, "index": index,
            "home": index + (f(jn, "HOME") - f(jn, "HOME_OFFSET")) * unit,
            "count": 1.0 / abs(f(jn, "INPUT_SCALE")),
            "kv": f(jn, "P") * f(jn, "OUTPUT_SCALE") * f("SERIAL", "V_RATED_%d" % j) / unit / 10.0,
            "deadband": f(jn, "DEADBAND")}


def serial_home_checks(r, ini, joints):
    """motenc_headless.py's homing of each joint: the machine at serial_joint's home
    within 8 counts (its motor) and 16 (the load behind a flexible train), the encoder
    zeroed at the index (motor-pos-fb is the motor's way from it, within 2 counts)."""
    for j in joints:
        sj = serial_joint(ini, j)
        h = r.get("home", {}).get(str(j), {})
        u = "deg" if sj["rotary"] else "mm"
        tol = sj["count"] * sj["unit"]
        check(h.get("homed") and abs(h.get("plant_motor_pos_mm", 99) - sj["home"]) < 8 * tol
              and abs(h.get("plant_pos_mm", 99) - sj["home"]) < 16 * tol,
              "joint %d homed in %.1f s (switch, latch, index): the machine at %.5f %s (motor %.5f), index %.3f %s, "
              "home %.4f %s" % (j, h.get("seconds", 0), h.get("plant_pos_mm", 99), u, h.get("plant_motor_pos_mm", 99),
                                sj["index"], u, sj["home"], u))
        fb = h.get("joint_pos_fb_in", 99) * sj["unit"]
        check(abs(fb - (h.get("plant_motor_pos_mm", 99) - sj["index"])) <= 2 * tol,
              "joint %d: motor-pos-fb %.5f %s = the motor's %.5f %s from the index (2 counts, %.2g %s each): the "
              "encoder zeroed at the index" % (j, fb, u, h.get("plant_motor_pos_mm", 99) - sj["index"], u, tol, u))


def serial_ferror_checks(col, ini, joints, vmin):
    """Steady following error of a P-only loop on a velocity-mode amplifier:
    |f-error| = |v| / Kv + DEADBAND where the commanded speed is steady (above
    vmin[j] in joint units/s, acceleration under 0.01): the median of measured /
    predicted within 2 % with the sign of v; the largest |f-error| within 5 % of
    vmax / Kv + DEADBAND. Returns the largest |f-error| of each joint."""
    peaks = []
    for j in joints:
        sj = serial_joint(ini, j)
        fe, v = col("joint.%d.f-error" % j), col("joint.%d.vel-cmd" % j)
        acc = np.gradient(v) / 0.001
        steady = (np.abs(v) > vmin[j]) & (np.abs(acc) < 0.01)
        ratio = float(np.median(np.abs(fe[steady]) / (np.abs(v[steady]) / sj["kv"] + sj["deadband"]))) if steady.any() else 0
        vmax = float(np.abs(v).max())
        peaks.append(float(np.abs(fe).max()))
        check(steady.sum() > 50 and abs(ratio - 1) < 0.02 and np.all(np.sign(fe[steady]) == np.sign(v[steady])),
              "joint %d: steady f-error = v / Kv + DEADBAND, Kv = P OUTPUT_SCALE V_RATED/10 V = %.0f 1/s: "
              "measured/predicted %.4f over %d periods" % (j, sj["kv"], ratio, steady.sum()))
        check(peaks[-1] <= 1.05 * (vmax / sj["kv"] + sj["deadband"]),
              "joint %d: max |f-error| %.6f within 5%% of vmax/Kv + DEADBAND = %.6f at %.2f a second"
              % (j, peaks[-1], vmax / sj["kv"] + sj["deadband"], vmax))
    return peaks
