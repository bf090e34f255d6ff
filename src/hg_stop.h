/* hg_stop.h - a mechanical hard stop at each end of an axis's stroke: a
 * stiff spring-damper that acts only in contact and only pushes. Shared
 * by every plant (the Hexaglide's carriages, hg_forces.h; a serial
 * machine's axes). Units SI (m, N; rad, N m for a rotary axis). */
#ifndef HG_STOP_H
#define HG_STOP_H

/* A hard stop is a spring: a load this far beyond it (m) has gone through
 * what the model represents (a crash, or a stop moved beneath the load),
 * and the step fails with HG_ERR_THROUGH_STOP. A chosen bound, far beyond
 * the millimetre or less a stop yields under any drive's force. */
#define HG_THROUGH_STOP_M 0.005

/* Force (+ toward +x) of the stops at lo and hi (lo < hi) on a load at x
 * moving at v: k times the penetration plus c v, never pulling it in. */
static inline double hg_stop_force(double x, double v, double lo, double hi, double k, double c)
{
    double f = 0.0;
    if (x > hi) {
        f = -k * (x - hi) - c * v;
        if (f > 0.0)
            f = 0.0;
    } else if (x < lo) {
        f = k * (lo - x) - c * v;
        if (f < 0.0)
            f = 0.0;
    }
    return f;
}

#endif
