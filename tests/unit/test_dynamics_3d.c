/* test_dynamics_3d.c - the dynamics away from pure vertical motion: tilted
 * head poses, rotating and translating, where the velocity-product terms and
 * the bars' rotation matter (at HOME in pure vertical motion both vanish).
 *
 * The reference is written here from docs/model.md alone, in the head pose
 * c = X Y Z A B C: the closed-form inverse kinematics gives every joint
 * point, the kinetic energy T(c, c') sums the carriages with their reflected
 * rotor inertia, the bars by Koenig's theorem (COM at l/2, inertia
 * i_bar - m_bar l^2/4 about it, spin neglected) and the head (COM
 * head_com below Op, inertia diag(i_head) in head axes), the potential
 * V(c) is gravity on every mass. Velocities come by complex-step
 * differentiation (the geometry evaluated at c + i eps c': exact to
 * rounding, no subtraction), so T is exact to rounding.
 *
 * (b) Lagrange's equations by central finite differences (Richardson):
 *     M(c) c'' = J^T fz - (dp/dc) c' + dT/dc - dV/dc, p = dT/dc' = M c',
 *     M by polarization of the quadratic T, dT/dc, dV/dc, (dp/dc) c' by
 *     central differences. Each kind's accelerations (hg_dae's accel, the
 *     paper's Eq. 13) at random tilted, rotating states with random carriage
 *     forces must equal c''_ref, and z'' (and the Standard model's bar-angle
 *     accelerations) the second time derivative of the geometry along it.
 *     The bound is ten times the finite differences' own error estimate
 *     (the result at step 2 delta against delta) plus a rounding floor
 *     (machine epsilon times the condition number of M); the check prints
 *     how many bounds the velocity-product terms and the bars' rotation are.
 * (a) Energy conservation: frictionless, undriven 3D motion (c_visc,
 *     f_coulomb, c_stop and any static friction set to 0 by name) from
 *     tilted poses with head translational and angular velocities, for
 *     every kind and scheme, energy from the reference above: the drift
 *     must shrink at the scheme's order (1 improved Euler, 2 Heun, 4 RK4)
 *     as dt halves. A wrong velocity term leaves a drift that does not
 *     shrink. */
#include <complex.h>
#include <float.h>
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_integrate.h"
#include "hg_system.h"
#include "hg_step_standard.h"
#include "hg_step_joints.h"
#include "hg_step_cartesian.h"
#include "hg_errors.h"

#define PI 3.14159265358979323846
#define CS_EPS 1e-30          /* complex step */
#define FD_DELTA 2e-3         /* finite-difference step (m, rad; s for the path) */

typedef double complex cx;

/* ---- the spec (docs/model.md), read by name through the parameter table ---- */

typedef struct {
    double l, lb, e, lp, h;               /* geometry; h from HOME at pose 0 */
    double m_head, head_com, ih[3];       /* head */
    double m_bar, i_bar_com;              /* bar: COM at l/2, inertia about the COM */
    double m_carriage, rotor;             /* carriage and j_rotor (2 pi / lead)^2 */
    double g;
} spec;

/* Value of parameter name (the test stops with a failed check if it is missing). */
static double par(hg_params *p, const char *name)
{
    double *f = hg_params_field(p, name);
    if (!f)
        CHECK(0, "parameter %s exists in hg_params_table", name);
    return f ? *f : NAN;
}

/* The spec's numbers from p. */
static void spec_of(hg_params *p, spec *s)
{
    double screw = 2 * PI / par(p, "lead");
    s->l = par(p, "l");
    s->lb = par(p, "lb");
    s->e = par(p, "e");
    s->lp = par(p, "lp");
    s->h = sqrt(s->l * s->l - (s->lb - s->lp) * (s->lb - s->lp));
    s->m_head = par(p, "m_head");
    s->head_com = par(p, "head_com");
    s->ih[0] = par(p, "i_head_xx");
    s->ih[1] = par(p, "i_head_yy");
    s->ih[2] = par(p, "i_head_zz");
    s->m_bar = par(p, "m_bar");
    s->i_bar_com = par(p, "i_bar") - s->m_bar * s->l * s->l / 4;
    s->m_carriage = par(p, "m_carriage");
    s->rotor = par(p, "j_rotor") * screw * screw;
    s->g = par(p, "g");
}

/* ---- the geometry at a complex head pose ---- */

typedef struct {
    cx z[6];         /* carriage heights relative to HOME */
    cx B[6][3], A[6][3];
    cx ang[12];      /* Standard model bar angles phi_k, theta_k: u = (A - B)/l = Rx(phi) Ry(theta) (0,0,-1) */
    cx R[9];         /* head orientation, row-major */
    cx G[3];         /* head COM */
} config;

/* Everything's position at head pose c (docs/model.md, "Frames and coordinates"). */
static void configure(const spec *s, const cx c[6], config *x)
{
    static const double alpha[3] = {0, 2 * PI / 3, -2 * PI / 3};
    cx sa = csin(c[3]), ca = ccos(c[3]), sb = csin(c[4]), cb = ccos(c[4]);
    cx sc = csin(c[5]), cc = ccos(c[5]);
    int k, r;
    /* R = Rz(C) Ry(B) Rx(A) */
    x->R[0] = cc * cb; x->R[1] = cc * sb * sa - sc * ca; x->R[2] = cc * sb * ca + sc * sa;
    x->R[3] = sc * cb; x->R[4] = sc * sb * sa + cc * ca; x->R[5] = sc * sb * ca - cc * sa;
    x->R[6] = -sb;     x->R[7] = cb * sa;                x->R[8] = cb * ca;
    for (r = 0; r < 3; r++)
        x->G[r] = c[r] - x->R[3 * r + 2] * s->head_com;
    for (k = 0; k < 6; k++) {
        double al = alpha[k / 2], sj = (k % 2) ? -1.0 : 1.0;
        double hp[3] = {cos(al) * s->lp - sin(al) * sj * s->e, sin(al) * s->lp + cos(al) * sj * s->e, 0};
        cx dx, dy;
        for (r = 0; r < 3; r++)
            x->A[k][r] = c[r] + x->R[3 * r] * hp[0] + x->R[3 * r + 1] * hp[1];
        x->B[k][0] = cos(al) * s->lb - sin(al) * sj * s->e;
        x->B[k][1] = sin(al) * s->lb + cos(al) * sj * s->e;
        dx = x->B[k][0] - x->A[k][0];
        dy = x->B[k][1] - x->A[k][1];
        x->B[k][2] = x->A[k][2] + csqrt(s->l * s->l - dx * dx - dy * dy); /* the + root: carriage above */
        x->z[k] = x->B[k][2] - s->h;
        {
            cx u[3];
            for (r = 0; r < 3; r++)
                u[r] = (x->A[k][r] - x->B[k][r]) / s->l;
            x->ang[2 * k] = catan(u[1] / -u[2]);   /* -u_z > 0: the bar hangs down */
            x->ang[2 * k + 1] = casin(-u[0]);
        }
    }
}

/* The configuration at c + i CS_EPS cd: real parts are the positions at c,
 * imaginary parts / CS_EPS the velocities along cd. */
static void configure_cs(const spec *s, const double c[6], const double cd[6], config *x)
{
    cx cc[6];
    int i;
    for (i = 0; i < 6; i++)
        cc[i] = c[i] + I * CS_EPS * cd[i];
    configure(s, cc, x);
}

#define VEL(v) (cimag(v) / CS_EPS)

/* Kinetic energy T(c, cd) (J). */
static double kinetic(const spec *s, const double c[6], const double cd[6])
{
    config x;
    double t = 0, W[9], w[3];
    int k, r, j, i;
    configure_cs(s, c, cd, &x);
    for (k = 0; k < 6; k++) {
        double vz = VEL(x.z[k]), vc2 = 0, ud2 = 0;
        t += 0.5 * (s->m_carriage + s->rotor) * vz * vz;
        for (r = 0; r < 3; r++) {
            double vc = VEL(x.A[k][r] + x.B[k][r]) / 2, ud = VEL(x.A[k][r] - x.B[k][r]) / s->l;
            vc2 += vc * vc;
            ud2 += ud * ud;
        }
        t += 0.5 * s->m_bar * vc2 + 0.5 * s->i_bar_com * ud2;
    }
    for (r = 0; r < 3; r++) {
        double vg = VEL(x.G[r]);
        t += 0.5 * s->m_head * vg * vg;
    }
    for (r = 0; r < 3; r++)            /* W = R^T R': the body angular velocity, skew */
        for (j = 0; j < 3; j++) {
            W[3 * r + j] = 0;
            for (i = 0; i < 3; i++)
                W[3 * r + j] += creal(x.R[3 * i + r]) * VEL(x.R[3 * i + j]);
        }
    w[0] = W[7]; w[1] = W[2]; w[2] = W[3];
    for (r = 0; r < 3; r++)
        t += 0.5 * s->ih[r] * w[r] * w[r];
    return t;
}

/* Gravity potential V(c) (J, up to a constant). */
static double potential(const spec *s, const double c[6])
{
    static const double zero[6] = {0, 0, 0, 0, 0, 0};
    config x;
    double v;
    int k;
    configure_cs(s, c, zero, &x);
    v = s->m_head * creal(x.G[2]);
    for (k = 0; k < 6; k++)
        v += s->m_carriage * creal(x.z[k]) + s->m_bar * creal(x.A[k][2] + x.B[k][2]) / 2;
    return s->g * v;
}

/* ---- Lagrange's equations by finite differences ---- */

/* M(c) from the quadratic T by polarization: M_ii = 2 T(e_i), M_ij = T(e_i + e_j) - T(e_i) - T(e_j). */
static void mass_matrix(const spec *s, const double c[6], double M[36])
{
    double ti[6];
    int i, j;
    for (i = 0; i < 6; i++) {
        double e[6] = {0, 0, 0, 0, 0, 0};
        e[i] = 1;
        ti[i] = kinetic(s, c, e);
        M[7 * i] = 2 * ti[i];
    }
    for (i = 0; i < 6; i++)
        for (j = 0; j < i; j++) {
            double e[6] = {0, 0, 0, 0, 0, 0};
            e[i] = e[j] = 1;
            M[6 * i + j] = M[6 * j + i] = kinetic(s, c, e) - ti[i] - ti[j];
        }
}

/* 1-norm condition number of M. */
static double condition(const double M[36])
{
    double inv_norm = 0, norm = 0;
    int i, j;
    for (j = 0; j < 6; j++) {
        double a[36], col[6] = {0, 0, 0, 0, 0, 0}, s1 = 0, s2 = 0;
        memcpy(a, M, sizeof a);
        col[j] = 1;
        hg_test_solve(6, a, col);
        for (i = 0; i < 6; i++) {
            s1 += fabs(col[i]);
            s2 += fabs(M[6 * i + j]);
        }
        inv_norm = fmax(inv_norm, s1);
        norm = fmax(norm, s2);
    }
    return norm * inv_norm;
}

/* The generalized forces of Lagrange's equations at (c, cd) with step d:
 * out = J^T fz - (dp/dc) cd + dT/dc - dV/dc, each derivative a central
 * difference (one level of Richardson extrapolation, error O(d^4)). With
 * vel_terms 0 the velocity-dependent parts are left out. */
static void lagrange_rhs(const spec *s, const double c[6], const double cd[6], const double fz[6],
                         double d, int vel_terms, double out[6])
{
    int j, k, lev;
    double part[2][6];
    for (lev = 0; lev < 2; lev++) {
        double h = lev ? d / 2 : d, Mp[36], Mm[36], cp[6], cm[6];
        for (j = 0; j < 6; j++) {
            double a[6], b[6], tt = 0;
            memcpy(a, c, sizeof a);
            memcpy(b, c, sizeof b);
            a[j] += h;
            b[j] -= h;
            if (vel_terms)
                tt = (kinetic(s, a, cd) - kinetic(s, b, cd)) / (2 * h);
            part[lev][j] = tt - (potential(s, a) - potential(s, b)) / (2 * h);
        }
        if (vel_terms) {               /* (dp/dc) cd = d/dtau M(c + tau cd) cd */
            for (j = 0; j < 6; j++) {
                cp[j] = c[j] + h * cd[j];
                cm[j] = c[j] - h * cd[j];
            }
            mass_matrix(s, cp, Mp);
            mass_matrix(s, cm, Mm);
            for (j = 0; j < 6; j++)
                for (k = 0; k < 6; k++)
                    part[lev][j] -= (Mp[6 * j + k] - Mm[6 * j + k]) * cd[k] / (2 * h);
        }
    }
    for (j = 0; j < 6; j++) {          /* + J^T fz, column j of J = dz/dc by complex step */
        double e[6] = {0, 0, 0, 0, 0, 0}, qj = 0;
        config x;
        e[j] = 1;
        configure_cs(s, c, e, &x);
        for (k = 0; k < 6; k++)
            qj += fz[k] * VEL(x.z[k]);
        out[j] = qj + (4 * part[1][j] - part[0][j]) / 3;
    }
}

/* c''_ref at (c, cd) with step d: solve M c'' = lagrange_rhs. */
static void reference_accel(const spec *s, const double c[6], const double cd[6], const double fz[6],
                            double d, int vel_terms, double cdd[6])
{
    double M[36];
    mass_matrix(s, c, M);
    lagrange_rhs(s, c, cd, fz, d, vel_terms, cdd);
    hg_test_solve(6, M, cdd);
}

/* Second time derivative of z (6) and the bar angles (12) along the path
 * c(t) = c + cd t + cdd t^2/2: central differences (Richardson, step d)
 * of the complex-step velocities. out[0..5] z'', out[6..17] angles''. */
static void geometry_accel(const spec *s, const double c[6], const double cd[6], const double cdd[6],
                           double d, double out[18])
{
    double v[2][2][18];
    int lev, sg, i, k;
    for (lev = 0; lev < 2; lev++)
        for (sg = 0; sg < 2; sg++) {
            double t = (sg ? -1 : 1) * (lev ? d / 2 : d), ct[6], cdt[6];
            config x;
            for (i = 0; i < 6; i++) {
                ct[i] = c[i] + cd[i] * t + 0.5 * cdd[i] * t * t;
                cdt[i] = cd[i] + cdd[i] * t;
            }
            configure_cs(s, ct, cdt, &x);
            for (k = 0; k < 6; k++)
                v[lev][sg][k] = VEL(x.z[k]);
            for (k = 0; k < 12; k++)
                v[lev][sg][6 + k] = VEL(x.ang[k]);
        }
    for (k = 0; k < 18; k++) {
        double d0 = (v[0][0][k] - v[0][1][k]) / (2 * d), d1 = (v[1][0][k] - v[1][1][k]) / d;
        out[k] = (4 * d1 - d0) / 3;
    }
}

/* J[18 x 6]: d(z, bar angles)/dc at c (complex step, column by column). */
static void jacobian(const spec *s, const double c[6], double J[108])
{
    int i, k;
    for (i = 0; i < 6; i++) {
        double e[6] = {0, 0, 0, 0, 0, 0};
        config x;
        e[i] = 1;
        configure_cs(s, c, e, &x);
        for (k = 0; k < 6; k++)
            J[6 * k + i] = VEL(x.z[k]);
        for (k = 0; k < 12; k++)
            J[6 * (6 + k) + i] = VEL(x.ang[k]);
    }
}

/* ---- the model's side ---- */

/* The parametrization hg_step integrates for kind (as hg_dynamics.c picks it). */
static const hg_dae *dae_of(hg_model_kind kind)
{
    switch (kind) {
    case HG_MODEL_STANDARD: return &hg_standard_dae;
    case HG_MODEL_REDUCED_JOINTS: return &hg_joints_dae;
    case HG_MODEL_REDUCED_CARTESIAN: return &hg_cartesian_dae;
    default: return &hg_fused_dae;
    }
}

/* hg_data of the state (c, cd): positions and velocities of z, the bar
 * angles (Standard) and the head from the reference geometry. */
static void state_of(const spec *s, const double c[6], const double cd[6], hg_data *d)
{
    config x;
    int k;
    memset(d, 0, sizeof *d);
    configure_cs(s, c, cd, &x);
    for (k = 0; k < 6; k++) {
        d->z_m[k] = creal(x.z[k]);
        d->zd_mps[k] = VEL(x.z[k]);
        d->pose[k] = c[k];
        d->posed[k] = cd[k];
    }
    for (k = 0; k < 12; k++) {
        d->bar_rad[k] = creal(x.ang[k]);
        d->bar_radps[k] = VEL(x.ang[k]);
    }
}

/* The model's accelerations at d's state with carriage forces fz: qdd of
 * its layout ([z, c] or [z, a, c]); 0 or the accel function's code. */
static int model_accel(const hg_model *m, hg_data *d, const double fz[6], double *qdd)
{
    double q[HG_NQ_STANDARD], qd[HG_NQ_STANDARD];
    int off = m->kind == HG_MODEL_STANDARD ? 18 : 6;
    memcpy(q, d->z_m, sizeof d->z_m);
    memcpy(qd, d->zd_mps, sizeof d->zd_mps);
    if (m->kind == HG_MODEL_STANDARD) {
        memcpy(q + 6, d->bar_rad, sizeof d->bar_rad);
        memcpy(qd + 6, d->bar_radps, sizeof d->bar_radps);
    }
    memcpy(q + off, d->pose, sizeof d->pose);
    memcpy(qd + off, d->posed, sizeof d->posed);
    d->trig_valid = 0;
    return dae_of(m->kind)->accel(m, d, q, qd, fz, qdd);
}

/* A random tilted, rotating state: |X|, |Y| <= 40 mm, |Z| <= 80 mm, |A|, |B|
 * <= 9 deg, |C| <= 11 deg; up to 0.4 m/s and 1.5 rad/s; forces up to 400 N. */
static void random_state(double c[6], double cd[6], double fz[6])
{
    int i;
    for (i = 0; i < 3; i++) {
        c[i] = hg_test_uniform(-0.04, 0.04);
        c[3 + i] = hg_test_uniform(-0.15, 0.15);
        cd[i] = hg_test_uniform(-0.4, 0.4);
        cd[3 + i] = hg_test_uniform(-1.5, 1.5);
    }
    c[2] = hg_test_uniform(-0.08, 0.08);
    c[5] = hg_test_uniform(-0.2, 0.2);
    for (i = 0; i < 6; i++)
        fz[i] = hg_test_uniform(-400, 400);
}

/* ---- (b) accelerations against Lagrange's equations ---- */

#define NSTATES 12

/* (b): every kind's accelerations against Lagrange's equations of the reference. */
static void test_lagrange(hg_params *p, const spec *s)
{
    static hg_model m[HG_MODEL_COUNT];
    static hg_data d;
    double worst[HG_MODEL_COUNT][3], ratio_vel = INFINITY, ratio_bar = INFINITY, worst_setup = 0;
    double angle_conv = 0, tol_max = 0, acc_max = 0;
    int kind, n, i, rc_all = 0;
    for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
        if (hg_model_init(&m[kind], p, (hg_model_kind)kind, 0, 0))
            rc_all = -1;
        worst[kind][0] = worst[kind][1] = worst[kind][2] = 0;
    }
    CHECK(rc_all == 0, "every model kind initializes with the default parameters");
    for (n = 0; n < NSTATES; n++) {
        double c[6], cd[6], fz[6], ref[6], ref2[6], tol[6], M[36], kappa, scale = 0;
        double geo[18], geo2[18], gtol[18], nov[6], nobar[6], J[108];
        spec sb = *s;
        random_state(c, cd, fz);
        reference_accel(s, c, cd, fz, FD_DELTA, 1, ref);
        reference_accel(s, c, cd, fz, 2 * FD_DELTA, 1, ref2);
        mass_matrix(s, c, M);
        kappa = condition(M);
        for (i = 0; i < 6; i++)
            scale = fmax(scale, fabs(ref[i]));
        /* the bound: 10 x the finite-difference error estimate (the O(d^4)
         * result at 2d is 16 times further off than at d, so d's error is
         * |ref(2d) - ref(d)| / 15), plus rounding in either solve:
         * 100 eps kappa(M) of the largest acceleration (the largest system,
         * the Standard model's KKT, has 42 unknowns) */
        for (i = 0; i < 6; i++)
            tol[i] = 10 * fabs(ref2[i] - ref[i]) / 15 + 100 * DBL_EPSILON * kappa * scale;
        geometry_accel(s, c, cd, ref, FD_DELTA, geo);
        geometry_accel(s, c, cd, ref2, 2 * FD_DELTA, geo2);
        jacobian(s, c, J);
        for (i = 0; i < 18; i++) {     /* the c'' bound carried through z'' = J c'' + ... */
            int j;
            gtol[i] = 10 * fabs(geo2[i] - geo[i]) / 15;
            for (j = 0; j < 6; j++)
                gtol[i] += fabs(J[6 * i + j]) * tol[j];
        }
        /* what the bound can see: c'' without the velocity-product terms,
         * and with the bars' rotational inertia about their COM left out */
        reference_accel(s, c, cd, fz, FD_DELTA, 0, nov);
        sb.i_bar_com = 0;
        reference_accel(&sb, c, cd, fz, FD_DELTA, 1, nobar);
        {
            double dv = 0, db = 0, tmax = 0;
            for (i = 0; i < 6; i++) {
                dv = fmax(dv, fabs(nov[i] - ref[i]));
                db = fmax(db, fabs(nobar[i] - ref[i]));
                tmax = fmax(tmax, tol[i]);
            }
            tol_max = fmax(tol_max, tmax);
            acc_max = fmax(acc_max, scale);
            ratio_vel = fmin(ratio_vel, dv / tmax);
            ratio_bar = fmin(ratio_bar, db / tmax);
        }
        for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
            double qdd[HG_NQ_STANDARD], ha[12];
            int off = kind == HG_MODEL_STANDARD ? 18 : 6, rc, k;
            state_of(s, c, cd, &d);
            worst_setup = fmax(worst_setup, hg_bar_length_error(&m[kind].p.geo, d.z_m, d.pose));
            if (kind == HG_MODEL_STANDARD) {   /* the bar-angle convention is the model's */
                hg_bar_angles(&m[kind].p, d.z_m, d.pose, ha);
                for (k = 0; k < 12; k++)
                    angle_conv = fmax(angle_conv, fabs(ha[k] - d.bar_rad[k]));
            }
            rc = model_accel(&m[kind], &d, fz, qdd);
            if (rc) {
                worst[kind][0] = INFINITY;
                continue;
            }
            for (i = 0; i < 6; i++) {   /* head c'' and carriage z'', in bounds */
                worst[kind][0] = fmax(worst[kind][0], fabs(qdd[off + i] - ref[i]) / tol[i]);
                worst[kind][1] = fmax(worst[kind][1], fabs(qdd[i] - geo[i]) / gtol[i]);
            }
            if (kind == HG_MODEL_STANDARD)
                for (i = 0; i < 12; i++)
                    worst[kind][2] = fmax(worst[kind][2], fabs(qdd[6 + i] - geo[6 + i]) / gtol[6 + i]);
        }
    }
    CHECK(worst_setup < 1e-12 && angle_conv < 1e-12,
          "the reference geometry closes the model's loops (bar-length error %.1e m) and has its bar "
          "angles (max diff %.1e rad)", worst_setup, angle_conv);
    CHECK(ratio_vel > 100 && ratio_bar > 100,
          "what the bound sees: at these %d tilted, rotating states the velocity-product terms change c'' "
          "by at least %.1e bounds, the bars' rotational inertia by at least %.1e bounds (want > 100)", NSTATES, ratio_vel,
          ratio_bar);
    for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
        char bars[64] = "";
        if (kind == HG_MODEL_STANDARD)
            snprintf(bars, sizeof bars, ", bar angles'' %.2g", worst[kind][2]);
        CHECK(worst[kind][0] <= 1 && worst[kind][1] <= 1 && worst[kind][2] <= 1,
              "%s: head c'', carriage z''%s = Lagrange's equations by finite differences at %d tilted, "
              "rotating states with carriage forces (worst: c'' %.2g, z'' %.2g%s of the bound; c'' bound up "
              "to %.1e on accelerations up to %.0f m/s^2 or rad/s^2)",
              hg_model_name((hg_model_kind)kind), kind == HG_MODEL_STANDARD ? ", bar angles''" : "",
              NSTATES, worst[kind][0], worst[kind][1], bars, tol_max, acc_max);
    }
}

/* ---- (a) energy conservation of frictionless, undriven 3D motion ---- */

/* Starting states: tilted head poses with translational and angular velocity. */
static const double start_c[][6] = {
    {0.03, -0.02, 0.02, 0.10, -0.06, 0.08},
    {-0.04, 0.01, -0.03, -0.08, 0.12, -0.10},
    {0.01, 0.04, 0.05, 0.05, 0.09, 0.15},
};
static const double start_cd[][6] = {
    {0.15, -0.10, 0.20, 0.6, -0.4, 0.5},
    {-0.10, 0.20, 0.10, -0.5, 0.7, -0.3},
    {0.05, -0.15, 0.25, 0.4, 0.5, -0.6},
};
#define NSTARTS (int)(sizeof start_c / sizeof start_c[0])
#define T_RUN_S 0.2

/* Max |E(t) - E(0)| (J) over T_RUN_S of undriven motion from start st, the
 * energy T + V of the reference at the model's (pose, posed); *e0 the
 * kinetic energy at the start, *zmax the largest |z|; NAN on a failed step. */
static double energy_drift(const hg_model *m, const spec *s, int st, double dt, double *t0, double *zmax)
{
    static hg_data d;
    static const double off[6] = {0, 0, 0, 0, 0, 0};
    long n = lround(T_RUN_S / dt), i;
    double e0, worst = 0;
    int k;
    state_of(s, start_c[st], start_cd[st], &d);
    *t0 = kinetic(s, d.pose, d.posed);
    e0 = *t0 + potential(s, d.pose);
    *zmax = 0;
    for (i = 0; i < n; i++) {
        if (hg_step(m, &d, off, dt))
            return NAN;
        worst = fmax(worst, fabs(kinetic(s, d.pose, d.posed) + potential(s, d.pose) - e0));
        for (k = 0; k < 6; k++)
            *zmax = fmax(*zmax, fabs(d.z_m[k]));
    }
    return worst;
}

/* The observed order log2(e_coarse / e_fine) of a pair of drifts, or NAN
 * when the finer drift is within 30 times the rounding floor (rounding
 * would move the order by more than log2(1 + 1/30) = 0.05). */
static double observed_order(double coarse, double fine, double floor_j)
{
    return fine > 30 * floor_j ? log2(coarse / fine) : NAN;
}

/* Energy drift of every kind and scheme at dt0, dt0/2, dt0/4 from every
 * start: the observed orders must be the scheme's, within ORDER_TOL. The
 * dt0 per scheme puts the drifts above rounding and in the asymptotic
 * range, where the O(dt) correction to an observed order halves as dt
 * halves: at these dt0 it is at most 0.16 (RK4 at 10 ms, z-independent
 * kinds: 4.16 then 4.05; Heun at 2 ms 2.09 then 2.05). A velocity-product
 * term that is off leaves a drift that does not shrink: the observed order
 * falls towards 0. */
#define ORDER_TOL 0.25

/* (a): energy drift orders of every kind and scheme. */
static void test_energy(void)
{
    static hg_model m;
    static const int order[HG_INTEGRATOR_COUNT] = {1, 2, 4};
    static const double dt0[HG_INTEGRATOR_COUNT] = {1e-3, 2e-3, 1e-2};
    hg_params p;
    spec s;
    double zmax_all = 0, stop;
    int kind, sch, st, lev, rc;
    hg_test_rigid_defaults(&p);
    CHECK(hg_test_frictionless(&p) == 0, "c_visc, f_coulomb and c_stop set to 0 by name (and f_static where it exists)");
    spec_of(&p, &s);
    stop = fmin(par(&p, "stop_max"), -par(&p, "stop_min"));
    for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
        rc = hg_model_init(&m, &p, (hg_model_kind)kind, 0, 0);
        for (sch = 0; sch < HG_INTEGRATOR_COUNT; sch++) {
            double pmin = INFINITY, pmax = -INFINITY, drift_max = 0, tmin = INFINITY, tmax = 0;
            int npairs = 0, nstart_ok = 0;
            rc = rc ? rc : hg_model_set_integrator(&m, sch);
            for (st = 0; st < NSTARTS && rc == 0; st++) {
                double e[3], t0 = 0, zmax, floor_j;
                int seen = 0;
                for (lev = 0; lev < 3; lev++) {
                    e[lev] = energy_drift(&m, &s, st, dt0[sch] / (1 << lev), &t0, &zmax);
                    zmax_all = fmax(zmax_all, zmax);
                }
                /* rounding of T + V: a few eps of its magnitude per evaluation, the max over
                 * the run's steps (measured: 0.5 to 1.5e-13 J, RK4 at 1 ms) */
                floor_j = 8 * DBL_EPSILON * (t0 + fabs(potential(&s, start_c[st])));
                for (lev = 0; lev < 2; lev++) {
                    double po = observed_order(e[lev], e[lev + 1], floor_j);
                    if (isnan(po) && !isnan(e[lev + 1]))
                        continue;
                    pmin = fmin(pmin, isnan(po) ? -INFINITY : po);
                    pmax = fmax(pmax, isnan(po) ? INFINITY : po);
                    npairs++;
                    seen = 1;
                }
                nstart_ok += seen;
                drift_max = fmax(drift_max, e[0]);
                tmin = fmin(tmin, t0);
                tmax = fmax(tmax, t0);
            }
            CHECK(rc == 0 && nstart_ok == NSTARTS && fabs(pmin - order[sch]) <= ORDER_TOL &&
                      fabs(pmax - order[sch]) <= ORDER_TOL,
                  "%s, %s: frictionless, undriven 3D motion from %d tilted, rotating starts (T0 %.1f..%.1f J), "
                  "%.1f s: energy drift %.2e J at dt %g ms, observed order %.2f..%.2f as dt halves twice "
                  "(%d pairs above rounding; want %d +- %.2f)",
                  hg_model_name((hg_model_kind)kind), hg_integrator_name((hg_integrator)sch), NSTARTS, tmin, tmax,
                  T_RUN_S, drift_max, dt0[sch] * 1e3, pmin, pmax, npairs, order[sch], ORDER_TOL);
        }
    }
    CHECK(zmax_all < stop - 0.1, "the motions stay clear of the hard stops: |z| <= %.0f mm (stops at %.0f mm)",
          zmax_all * 1e3, stop * 1e3);
}

int main(void)
{
    hg_params p;
    spec s;
    hg_test_rigid_defaults(&p);
    spec_of(&p, &s);
    test_lagrange(&p, &s);
    test_energy();
    return hg_test_exit();
}
