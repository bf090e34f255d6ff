"""hg_program.py - a program's rows in a sampled run and the rest-to-rest
moves tune generates, shared by tune's two plants (tools/hexaglide_tune.py,
tools/hexaglide_tune_serial.py), identify and verify_gains: one servo period,
one lead-in, one way to find where a program ran."""
import numpy as np

PERIOD_S = 0.001
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
