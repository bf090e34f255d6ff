/* hg_stability.c - linear stability of the board's step on the stiff
 * test systems of each axis, and the impact test of a train with
 * backlash (hg_stability.h). */
#include <float.h>
#include "hg_math.h"
#include "hg_stability.h"
#include "hg_errors.h"
#include "hg_drivetrain.h"
#include "hg_units.h"

#define BISECT_ITER 40        /* the largest stable step, to 1e-12 of the period */
#define STAB_NEAR 1.05        /* a bound within 5% of the shortest: the simpler system names it */
#define IMPACT_CYCLES 8.0     /* the impact test's length: crossings of the free play and contacts */
#define IMPACT_STEPS_MAX 4000 /* ... in at most this many steps (the counts found with 20 and 20,000) */
#define IMPACT_BUDGET 200000  /* steps of the test in one check, every force and count: a count not
                                 passed within them fails (the check runs in the servo thread) */

/* One carriage with one stiff part: m x'' = f - c x' - k x, f the drive's
 * force held over the step from a state variable w. */
typedef struct {
    double m, k, c;
    int drive;           /* 0 current held (w unused), 1 bus-limited winding (w = i), 2 velocity loop (w = xi) */
    double fpa;          /* force per ampere (N/A) */
    double ke_r;         /* winding: current per speed the back-EMF takes, kt (2 pi / lead) / R (A s/m) */
    double tau;          /* winding: L / R (s) */
    double kp, ki;       /* velocity loop (A s/m, A/m) */
    const char *param;   /* what limits it */
    const char *param_c; /* what names the bound when the damping c alone cannot be integrated */
} test_system;

/* The reduced mass of two bodies on one spring. */
static double reduced_mass(double a, double b)
{
    return 1.0 / (1.0 / a + 1.0 / b);
}

/* Acceleration of the test system. */
static double accel(const test_system *s, double f, double x, double v)
{
    return (f - s->c * v - s->k * x) / s->m;
}

/* One step of dt of the scheme on y = (x, v, w), in hg_step's order: the
 * drive's force from the step's start, the scheme's stages, the drive's
 * state at the end. */
static void step(const test_system *s, hg_integrator scheme, double dt, double y[3])
{
    const double *cs, *bs;
    double x0 = y[0], v0 = y[1], w0 = y[2], f = 0.0, w1 = 0.0, x1, v1, a;
    int ns = hg_scheme_tableau(scheme, &cs, &bs), i;
    if (s->drive == 1) {               /* the winding towards (u - e) / R, linearized: -ke_r v */
        double is = -s->ke_r * v0, dec = exp(-dt / s->tau);
        f = s->fpa * (is + (w0 - is) * s->tau / dt * (1.0 - dec));
        w1 = is + (w0 - is) * dec;
    } else if (s->drive == 2) {        /* xi + x is constant (xi' = -x'): xi = -x, a spring */
        f = s->fpa * (-s->kp * v0 - s->ki * x0);
    }
    a = accel(s, f, x0, v0);
    if (ns == 0) {                     /* improved Euler */
        x1 = x0 + v0 * dt + 0.5 * a * dt * dt;
        v1 = v0 + a * dt;
    } else {
        double vs = v0, sq = bs[0] * v0, sv = bs[0] * a;
        for (i = 1; i < ns; i++) {
            double h = cs[i] * dt, xs = x0 + h * vs;
            vs = v0 + h * a;
            a = accel(s, f, xs, vs);
            sq += bs[i] * vs;
            sv += bs[i] * a;
        }
        x1 = x0 + dt * sq;
        v1 = v0 + dt * sv;
    }
    y[0] = x1;
    y[1] = v1;
    y[2] = w1;
}

/* x > 0 beyond rounding: x was summed from terms whose magnitudes add to s. */
static int positive(double x, double s)
{
    return x > 64.0 * DBL_EPSILON * s;
}

/* x is 0 to rounding: neither positive nor negative beyond it. */
static int neutral(double x, double s)
{
    return !positive(x, s) && !positive(-x, s);
}

/* 1 when both eigenvalues 1 + u of a 2x2 map G = I + D lie inside the unit
 * circle, D's trace t and determinant d (ts, ds: the magnitudes they were
 * summed from): Jury's conditions on p(z) = z^2 + a1 z + a0. */
static int inside2(double t, double ts, double d, double ds)
{
    return positive(d, ds) &&                      /* p(1) = d */
           positive(4.0 + 2.0 * t + d, 4.0) &&     /* p(-1) */
           positive(-(t + d), ts + ds) &&          /* det G = 1 + t + d < 1 */
           positive(2.0 + t + d, 2.0);             /* det G > -1 */
}

/* 1 when every eigenvalue of the step's map G lies inside the unit circle,
 * or one is exactly 1 (a state the step leaves as it is, as the position
 * without a spring: a velocity loop without integral gain, or a damping
 * too weak to change a speed's last bit) and the others inside.
 * Without a spring the position is neutral (eigenvalue 1, it only
 * accumulates), so the map is taken on (v, w); with one on (x, v, w); the
 * velocity loop ties its integral to x, so its map is on (x, v). Jury's
 * conditions are written in D = G - I (trace t, second invariant m,
 * determinant d), taken from the step's increments: as dt shrinks the
 * eigenvalues approach 1, and the coefficients of G's polynomial would
 * cancel to rounding against 1 while D's invariants keep their precision. */
static int stable(const test_system *s, hg_integrator scheme, double dt)
{
    double D[3][3];
    int j, r, n = s->drive == 2 ? 2 : s->k > 0.0 ? 3 : 2, off = s->drive == 2 ? 0 : 3 - n;
    for (j = 0; j < n; j++) {          /* column j: the increment of unit vector j */
        double y[3] = {0, 0, 0};
        y[off + j] = 1.0;
        step(s, scheme, dt, y);
        y[off + j] -= 1.0;
        for (r = 0; r < n; r++)
            D[r][j] = y[off + r];
    }
    if (n == 2) {                      /* p(z) = z^2 + a1 z + a0, G = I + D */
        double t = D[0][0] + D[1][1], ts = fabs(D[0][0]) + fabs(D[1][1]);
        double d = D[0][0] * D[1][1] - D[0][1] * D[1][0];
        double ds = fabs(D[0][0] * D[1][1]) + fabs(D[0][1] * D[1][0]);
        if (neutral(d, ds))            /* an eigenvalue 1 + 0: the other, 1 + t, inside */
            return positive(-t, ts) && positive(2.0 + t, 2.0);
        return inside2(t, ts, d, ds);
    } else {                           /* p(z) = z^3 + a2 z^2 + a1 z + a0 */
        double t = D[0][0] + D[1][1] + D[2][2], ts = fabs(D[0][0]) + fabs(D[1][1]) + fabs(D[2][2]);
        double p01 = D[0][0] * D[1][1] - D[0][1] * D[1][0], p02 = D[0][0] * D[2][2] - D[0][2] * D[2][0];
        double p12 = D[1][1] * D[2][2] - D[1][2] * D[2][1];
        double m = p01 + p02 + p12;
        double ms = fabs(D[0][0] * D[1][1]) + fabs(D[0][1] * D[1][0]) + fabs(D[0][0] * D[2][2]) +
                    fabs(D[0][2] * D[2][0]) + fabs(D[1][1] * D[2][2]) + fabs(D[1][2] * D[2][1]);
        double d = D[0][0] * p12 - D[0][1] * (D[1][0] * D[2][2] - D[1][2] * D[2][0]) +
                   D[0][2] * (D[1][0] * D[2][1] - D[1][1] * D[2][0]);
        double ds = fabs(D[0][0]) * (fabs(D[1][1] * D[2][2]) + fabs(D[1][2] * D[2][1])) +
                    fabs(D[0][1]) * (fabs(D[1][0] * D[2][2]) + fabs(D[1][2] * D[2][0])) +
                    fabs(D[0][2]) * (fabs(D[1][0] * D[2][1]) + fabs(D[1][1] * D[2][0]));
        double g = t + m + d, gs = ts + ms + ds;    /* det G - 1 */
        /* Jury's last condition |a0^2 - 1| > |a0 a2 - a1| in D's invariants */
        double lhs = fabs(g * (2.0 + g));
        double rhs = fabs(2.0 * t + t * t + 2.0 * m + t * m + 3.0 * d + t * d);
        double rs = 2.0 * ts + ts * ts + 2.0 * ms + ts * ms + 3.0 * ds + ts * ds;
        if (neutral(d, ds))            /* an eigenvalue 1 + 0: the others, 1 + the roots of u^2 - t u + m */
            return inside2(t, ts, m, ms);
        return positive(-d, ds) &&                                  /* p(1) = -d */
               positive(8.0 + 4.0 * t + 2.0 * m + d, 8.0) &&        /* -p(-1) */
               positive(-g, gs) && positive(2.0 + g, 2.0) &&        /* |det G| < 1 */
               positive(lhs - rhs, gs * (2.0 + gs) + rs);
    }
}

/* The test systems of axis a; returns how many (at most
 * HG_STAB_AXIS_SYSTEMS). A rigid train moves the rotor with its load:
 * every system has their two masses (m_rigid). A flexible one (k_axial >
 * 0) parts them: the load alone (m_load, the least inertia it has) meets
 * the stop and viscous friction; the rotor alone the drive; and the
 * train's mode of the two, stiffness k_axial on their reduced mass, bounds
 * every mode of the machine on its springs. */
static int test_systems(const hg_stability_axis *a, test_system s[HG_STAB_AXIS_SYSTEMS])
{
    const double fpa = a->force_per_amp, rotor = a->m_rotor;
    const int flexible = a->k_axial > 0.0;
    const double carriage = flexible ? a->m_load : a->m_rigid;
    const test_system base = {carriage, 0.0, a->c_visc, 0, fpa, fpa / a->r_winding,
                              a->l_winding / a->r_winding, a->kp_vel, a->ki_vel, a->name[HG_STAB_C_VISC],
                              a->name[HG_STAB_C_VISC]};
    test_system stop, drive = base;
    int n = 0;
    if (flexible)                                           /* the drive turns the rotor alone */
        drive.m = rotor, drive.c = 0.0;
    if (a->c_visc > 0.0) {                                  /* viscous friction alone */
        s[n] = base;
        s[n].param = a->name[HG_STAB_C_VISC], n++;
    }
    s[n] = base;                                            /* in a hard stop (and on its train) */
    s[n].k = a->k_stop + (flexible ? a->k_axial : 0.0), s[n].c += a->c_stop;
    s[n].param = a->name[s[n].c > 0.0 ? HG_STAB_K_STOP : HG_STAB_C_STOP];
    s[n].param_c = a->name[a->c_stop > 0.0 ? HG_STAB_C_STOP : HG_STAB_C_VISC], n++;
    stop = flexible ? drive : s[n - 1];                     /* a rotor's drive does not meet the stop */
    s[n] = drive;                                           /* back-EMF of a drive at its bus voltage */
    s[n].drive = 1, s[n].param = a->name[HG_STAB_R_WINDING], n++;
    if (!flexible) {
        s[n] = stop;                                        /* ... in a hard stop */
        s[n].drive = 1, n++;
    }
    if (a->velocity_mode) {
        s[n] = drive;                                       /* the velocity loop: ki_vel its spring, kp_vel */
        s[n].drive = 2, s[n].param = a->name[HG_STAB_KI_VEL];   /* its damping (damping_limits) */
        s[n].param_c = a->name[HG_STAB_KP_VEL], n++;
        if (!flexible) {
            s[n] = stop;                                    /* ... in a hard stop */
            s[n].drive = 2, n++;
        }
    }
    if (flexible) {                                         /* the train's mode, motor against load */
        s[n] = base;
        s[n].m = reduced_mass(rotor, carriage);
        s[n].k = a->k_axial;
        s[n].c = a->c_axial;
        s[n].param = a->name[s[n].c > 0.0 ? HG_STAB_K_AXIAL : HG_STAB_C_AXIAL];
        s[n].param_c = a->name[HG_STAB_C_AXIAL], n++;
    }
    return n;
}

/* 1 when system s has a spring and a damping, and the damping alone
 * cannot be integrated at dt: then the damping, not the spring, names the
 * bound. The velocity loop's spring is ki_vel, its damping kp_vel. */
static int damping_limits(const test_system *s, hg_integrator scheme, double dt)
{
    test_system c_only = *s;
    if (s->drive == 2 && s->k == 0.0) {   /* the velocity loop alone: kp_vel alone, without ki_vel */
        c_only.ki = 0.0;
        return !stable(&c_only, scheme, dt);
    }
    c_only.k = 0.0;
    c_only.drive = 0;
    return s->k > 0.0 && s->c > 0.0 && !stable(&c_only, scheme, dt);
}

/* 1 when every test system of the n axes is stable at dt. */
static int all_stable(const hg_stability_axis *ax, int n, hg_integrator scheme, double dt)
{
    test_system s[HG_STAB_AXIS_SYSTEMS];
    int a, i, m;
    for (a = 0; a < n; a++)
        for (i = 0, m = test_systems(&ax[a], s); i < m; i++)
            if (!stable(&s[i], scheme, dt))
                return 0;
    return 1;
}

/* The impact test's state: rotor and load positions (m) and speeds (m/s). */
typedef struct {
    double xr, vr, xl, vl;
} impact_state;

/* Its accelerations: force f on the rotor, the train between rotor and load, viscous friction on the load. */
static impact_state impact_rate(const hg_stability_axis *a, const hg_drivetrain_channel *t, double f,
                                const impact_state *y)
{
    double ft = hg_drivetrain_force(t, y->xr - y->xl, y->vr - y->vl);
    impact_state r = {y->vr, (f - ft) / a->m_rotor, y->vl, (ft - a->c_visc * y->vl) / a->m_load};
    return r;
}

/* y + h r. */
static impact_state impact_add(const impact_state *y, double h, const impact_state *r)
{
    impact_state s = {y->xr + h * r->xr, y->vr + h * r->vr, y->xl + h * r->xl, y->vl + h * r->vl};
    return s;
}

/* One step of dt of the scheme on the impact test's state (stage i from y0 + c_i dt k_(i-1), as the plants' step). */
static void impact_step(const hg_stability_axis *a, const hg_drivetrain_channel *t, hg_integrator scheme,
                        double f, double dt, impact_state *y)
{
    static const impact_state zero = {0, 0, 0, 0};
    const double *cs, *bs;
    int ns = hg_scheme_tableau(scheme, &cs, &bs), i;
    impact_state k = impact_rate(a, t, f, y), sum;
    if (ns == 0) {                     /* improved Euler: q += q' dt + q'' dt^2 / 2, q' += q'' dt */
        impact_state y1 = impact_add(y, dt, &k);
        y1.xr += 0.5 * dt * dt * k.vr;
        y1.xl += 0.5 * dt * dt * k.vl;
        *y = y1;
        return;
    }
    sum = impact_add(&zero, bs[0], &k);
    for (i = 1; i < ns; i++) {
        impact_state ys = impact_add(y, cs[i] * dt, &k);
        k = impact_rate(a, t, f, &ys);
        sum = impact_add(&sum, bs[i], &k);
    }
    *y = impact_add(y, dt, &sum);
}

/* The impact test of axis a at dt with the force f (> 0) on its rotor,
 * from rest in the middle of the free play: 1 while the energy (both
 * bodies' kinetic energy and the train's spring) stays within
 * HG_STAB_IMPACT_ENERGY times the work f has done, over IMPACT_CYCLES
 * crossings of the free play and contacts (at most IMPACT_STEPS_MAX steps);
 * each step taken from *budget, 0 when it runs out. */
static int impact_passive(const hg_stability_axis *a, hg_integrator scheme, double dt, double f, long *budget)
{
    const hg_drivetrain_channel t = {a->k_axial, a->c_axial, a->backlash};
    const double m_mode = reduced_mass(a->m_rotor, a->m_load);
    const double cycle = sqrt(2.0 * a->backlash * a->m_rotor / f) + HG_PI * sqrt(m_mode / a->k_axial);
    const double want = ceil(IMPACT_CYCLES * cycle / dt);
    const long steps = want < IMPACT_STEPS_MAX ? (long)want : IMPACT_STEPS_MAX;
    impact_state y = {0, 0, 0, 0};
    double work = 0.0;
    long s;
    for (s = 0; s < steps; s++) {
        double xr0 = y.xr, e;
        if (--*budget < 0)
            return 0;
        impact_step(a, &t, scheme, f, dt, &y);
        work += f * (y.xr - xr0);
        e = 0.5 * a->m_rotor * y.vr * y.vr + 0.5 * a->m_load * y.vl * y.vl + hg_drivetrain_energy(&t, y.xr - y.xl);
        if (!(e <= HG_STAB_IMPACT_ENERGY * (work > 0.0 ? work : 0.0)) && !(e <= 0.0))
            return 0;                  /* (NaN and inf too: neither comparison holds) */
    }
    return 1;
}

/* 1 when axis a has no backlash (or no train, or no drive), or its impact test passes at dt with
 * each of HG_STAB_IMPACT_FORCES of its force (steps from *budget). */
static int impacts_pass(const hg_stability_axis *a, hg_integrator scheme, double dt, long *budget)
{
    static const double share[] = {HG_STAB_IMPACT_FORCES};
    unsigned i;
    if (!(a->backlash > 0.0 && a->k_axial > 0.0 && a->f_max > 0.0))
        return 1;
    for (i = 0; i < sizeof share / sizeof share[0]; i++)
        if (!impact_passive(a, scheme, dt, share[i] * a->f_max, budget))
            return 0;
    return 1;
}

/* 1 when every axis of the n passes its impact test at dt; else *bad is the first that does not. */
static int all_impacts_pass(const hg_stability_axis *ax, int n, hg_integrator scheme, double dt, int *bad,
                            long *budget)
{
    int a;
    for (a = 0; a < n; a++)
        if (!impacts_pass(&ax[a], scheme, dt, budget)) {
            *bad = a;
            return 0;
        }
    return 1;
}

/* From out->substeps (the linear systems' count) up to substeps_max, the
 * first count whose step passes every axis's impact test. 0 when it is
 * out->substeps; else 1 with *out rewritten: that count (0 past
 * substeps_max), the failing axis's backlash as the bound and the step of
 * the first count that passes (searched up to four times substeps_max
 * only to say it; 0 when none does). */
static int raise_for_impacts(const hg_stability_axis *ax, int n_axes, hg_integrator scheme, double period_s,
                             unsigned substeps_max, hg_stability *out)
{
    unsigned k = out->substeps, pass;
    int bad = 0;
    long budget = IMPACT_BUDGET;
    while (k <= substeps_max && !all_impacts_pass(ax, n_axes, scheme, period_s / k, &bad, &budget))
        k++;
    if (k == out->substeps)
        return 0;
    for (pass = k; pass > substeps_max && pass <= 4 * substeps_max; pass += 1 + pass / 8)
        if (impacts_pass(&ax[bad], scheme, period_s / pass, &budget))
            break;
    out->substeps = k <= substeps_max ? k : 0;
    out->param = ax[bad].name[HG_STAB_BACKLASH];
    out->dt_max_s = pass <= 4 * substeps_max ? period_s / pass : 0.0;
    return 1;
}

/* The longest stable step of system s below hi (bisection). */
static double longest_step(const test_system *s, hg_integrator scheme, double hi)
{
    double lo = 0.0;
    int k;
    for (k = 0; k < BISECT_ITER; k++) {
        double mid = 0.5 * (lo + hi);
        if (stable(s, scheme, mid))
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

int hg_stability_check_axes(const hg_stability_axis *ax, int n_axes, hg_integrator scheme, double period_s,
                            unsigned substeps_min, unsigned substeps_max, hg_stability *out)
{
    test_system s[HG_STAB_AXIS_SYSTEMS];
    double h[HG_STAB_SYSTEMS_MAX] = {0}; /* each system's longest stable step, in the axes' order */
    const char *name[HG_STAB_SYSTEMS_MAX] = {0};
    int a, i, m, n = 0, limiting = -1;
    unsigned k, last = 0;              /* last: the last count still unstable */
    if (substeps_min < 1)
        substeps_min = 1;
    if (n_axes > HG_STAB_AXES_MAX)
        n_axes = HG_STAB_AXES_MAX;
    out->substeps = 0;
    out->param = 0;
    out->dt_max_s = 0.0;
    for (k = substeps_min; k <= substeps_max; k++) {
        if (all_stable(ax, n_axes, scheme, period_s / k)) {
            out->substeps = k;
            break;
        }
        last = k;
    }
    if (out->substeps && raise_for_impacts(ax, n_axes, scheme, period_s, substeps_max, out))
        return out->substeps ? 0 : HG_ERR_STIFF;
    /* of the systems unstable at that count, the one with the shortest stable step names the
     * bound; the first listed within 5% of it when there is one (a system listed earlier is a
     * part of later ones: viscous friction alone comes before the stop that adds to it) */
    for (a = 0; last && a < n_axes; a++)
        for (i = 0, m = test_systems(&ax[a], s); i < m; i++, n++) {
            h[n] = stable(&s[i], scheme, period_s / last) ? DBL_MAX
                                                         : longest_step(&s[i], scheme, period_s / substeps_min);
            /* the damping names the bound when it limits, or when some damping but no step is stable
             * at all: the mode needs more of it (c_axial = 1e-300 named k_axial; with none, the
             * system's own name is already the damping's) */
            name[n] = (damping_limits(&s[i], scheme, period_s / last) ||
                       (h[n] == 0.0 && s[i].c > 0.0 && s[i].param_c)) ? s[i].param_c : s[i].param;
            if (h[n] < DBL_MAX && (limiting < 0 || h[n] < h[limiting]))
                limiting = n;
        }
    for (i = 0; limiting >= 0 && i < limiting; i++)
        if (h[i] <= STAB_NEAR * h[limiting]) {
            limiting = i;
            break;
        }
    if (limiting >= 0)
        out->param = name[limiting], out->dt_max_s = h[limiting];
    return out->substeps ? 0 : HG_ERR_STIFF;
}
