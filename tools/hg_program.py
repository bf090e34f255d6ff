"""hg_program.py - a program's rows in a sampled run and the rest-to-rest
moves tune generates, shared by tune's two plants (tools/hexaglide_tune.py,
tools/hexaglide_tune_serial.py), identify and verify_gains: one servo period,
one lead-in, one way to find where a program ran, one check of a trajectory
against the joints' limits and of its time column."""
import numpy as np

PERIOD_S = 0.001          # tune's servo period: an INI with another [EMCMOT]SERVO_PERIOD is refused
PERIOD_WHY = ("its closed-loop runs, the plant's response and a trajectory's lines are one per 1 ms period, "
              "and the gains it finds hold at that period only")
LEAD_IN = 300              # rows kept before the program starts (recorded runs)


def program_rows(running, cmd):
    """Rows (start, end) of the program in a sampled run: from the last rest
    before its first move to the last row halui.program.is-running is set.
    is-running can rise a few periods after the commands start moving (halui
    lags motion on a loaded machine), so the start is found from the commands:
    back from the rise while any joint's command changes. None when it never ran."""
    if not running.any():
        return None
    s = int(np.argmax(running))
    while s > 0 and np.any(cmd[s] != cmd[s - 1]):
        s -= 1
    return s, len(running) - int(np.argmax(running[::-1]))


def beyond_limits(source, cmd, joints, unit):
    """A message naming the first command of cmd (rows, joints) outside its joint's
    [JOINT_N]MIN_LIMIT..MAX_LIMIT (joints: the INI's [JOINT_N] dicts; unit(j): joint j's
    unit), or None: the machine cannot go there."""
    for j, g in enumerate(joints):
        lo, hi = g.get("MIN_LIMIT", -np.inf), g.get("MAX_LIMIT", np.inf)
        out = np.where((cmd[:, j] < lo) | (cmd[:, j] > hi))[0]
        if len(out):
            return ("%s: joint %d is commanded to %.4g %s at sample %d, outside [JOINT_%d]MIN_LIMIT..MAX_LIMIT "
                    "(%g..%g %s): the machine cannot go there (another machine's trajectory, or not in the joint's unit, %s?)"
                    % (source, j, cmd[out[0], j], unit(j), out[0] + 1, j, lo, hi, unit(j), unit(j)))
    return None


def uneven_times(source, t, lines):
    """A message when a recorded time column t (s, the headless runners' t_s) is not one servo
    period a line: samples missing (a gap), or lines closer than a period (a faster servo
    thread, or time going back: under 0.6 of a period); None when it is. lines[i]: the file line of
    sample i."""
    d = np.diff(t)
    bad = np.where((d > 1.5 * PERIOD_S) | (d < 0.6 * PERIOD_S))[0]
    if not len(bad):
        return None
    i = bad[0]
    if d[i] > 1.5 * PERIOD_S:
        return ("%s line %d: samples missing after t = %.3f s (a gap in the recording); record again"
                % (source, lines[i + 1], t[i]))
    return ("%s line %d: t = %.4g s, %.4g s after the line before: tune takes one line per %g s servo period; "
            "record with [EMCMOT]SERVO_PERIOD = %d (ns)" % (source, lines[i + 1], t[i + 1], d[i], PERIOD_S,
                                                           round(PERIOD_S * 1e9)))


def s_curve(dist, vmax, amax, jerk_time=0.02):
    """Positions (per period) of a rest-to-rest move of dist with velocity
    vmax and acceleration amax, the acceleration ramped over jerk_time."""
    dist = abs(dist)
    ta = vmax / amax
    if amax * ta * ta > dist:                  # no cruise: triangle
        ta = np.sqrt(dist / amax)
        vmax = amax * ta
    tc = max(0.0, (dist - amax * ta * ta) / vmax)
    T = 2 * ta + tc + jerk_time
    t = np.arange(0, T + 0.2, PERIOD_S)
    acc = np.where(t < ta, amax, 0.0) - np.where((t >= ta + tc) & (t < 2 * ta + tc), amax, 0.0)
    n = max(1, int(jerk_time / PERIOD_S))
    acc = np.convolve(acc, np.ones(n) / n)[:len(t)]   # jerk-limited (S-curve)
    pos = np.cumsum(np.cumsum(acc) * PERIOD_S) * PERIOD_S
    return pos * (dist / pos[-1]) if pos[-1] > 0 else pos
