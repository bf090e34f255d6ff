/* hg_friction.c - stick and slip of the carriages at the velocity level
 * (hg_friction.h). */
#include "hg_math.h"
#include "hg_friction.h"
#include "hg_linalg.h"
#include "hg_errors.h"

#define SLIDE_PASSES 3   /* fixed-point passes of the sliding force over the step's speed range */
#define STRIBECK_FLAT 6.0 /* beyond 6 v_stribeck exp(-(v/v_s)^2) < 2.4e-16: the curve is f_coulomb */

int hg_friction_on(const hg_params *p)
{
    return p->f_static_n > 0.0 || p->f_coulomb_n > 0.0;
}

double hg_friction_stribeck(const hg_params *p, double v)
{
    double x = v / p->v_stribeck_mps;
    if (!(fabs(x) <= STRIBECK_FLAT))
        return 0.0;
    return exp(-x * x);
}

double hg_friction_sliding(const hg_params *p, double v)
{
    return p->f_coulomb_n + (p->f_static_n - p->f_coulomb_n) * hg_friction_stribeck(p, v);
}

/* erf(x), x >= 0, with rtapi_math's exp: Numerical Recipes' Chebyshev
 * fit of erfc (relative error below 1.2e-7). */
static double erf_pos(double x)
{
    double t = 1.0 / (1.0 + 0.5 * x);
    double y = t * exp(-x * x - 1.26551223 +
                       t * (1.00002368 + t * (0.37409196 + t * (0.09678418 + t * (-0.18628806 +
                       t * (0.27886807 + t * (-1.13520398 + t * (1.48851587 +
                       t * (-0.82215223 + t * 0.17087277)))))))));
    return 1.0 - y;
}

/* Mean of the Stribeck curve while the speed runs linearly from a to b
 * (a, b >= 0): f_c + (f_s - f_c) mean of exp(-(v/v_s)^2), in closed form
 * (v_s sqrt(pi)/2 (erf(b/v_s) - erf(a/v_s)) / (b - a)); the curve at the
 * mean speed when a and b are too close for the difference (within
 * 0.01 v_s, where both err by about 1e-5 of f_s - f_c at most). */
static double sliding_mean(const hg_params *p, double a, double b)
{
    const double vs = p->v_stribeck_mps, d = b - a;
    double g;
    if (p->f_static_n == p->f_coulomb_n || (a > STRIBECK_FLAT * vs && b > STRIBECK_FLAT * vs))
        return p->f_coulomb_n;            /* on the flat of the curve all step long */
    if (fabs(d) < 1e-2 * vs)          /* midpoint error (d/vs)^2/12 below erf's 1.2e-7 vs/d */
        return hg_friction_sliding(p, 0.5 * (a + b));
    g = 0.88622692545275801365 * vs * (erf_pos(b / vs) - erf_pos(a / vs)) / d;
    g = fmax(0.0, fmin(1.0, g));      /* a mean of exp(-x^2): the fit's error must not leave [0, 1] */
    return p->f_coulomb_n + (p->f_static_n - p->f_coulomb_n) * g;
}

/* Impulses of the sticking carriages (mask stuck) that make their speeds
 * exactly 0 with the sliding ones' impulses fixed: W_SS p_S = -(v*_S + W_SF p_F). */
static int solve_stuck(const double W[36], const double vstar[6], unsigned stuck, double p[6])
{
    double a[36], b[6];
    int idx[6], piv[6], n = 0, i, j, rc;
    for (i = 0; i < 6; i++)
        if ((stuck >> i) & 1u)
            idx[n++] = i;
    if (n == 0)
        return 0;
    for (i = 0; i < n; i++) {
        double r = -vstar[idx[i]];
        for (j = 0; j < 6; j++)
            if (!((stuck >> j) & 1u))
                r -= W[6 * idx[i] + j] * p[j];
        b[i] = r;
        for (j = 0; j < n; j++)
            a[n * i + j] = W[6 * idx[i] + idx[j]];
    }
    rc = hg_lu_factor(n, a, piv);
    if (rc)
        return HG_ERR_SINGULAR_MASS;
    hg_lu_solve(n, a, piv, 1, b);
    for (i = 0; i < n; i++)
        p[idx[i]] = b[i];
    return 0;
}

/* The impulses of a stick/slip set: the sliding carriages' from their
 * sliding friction (sigma, slide), the stuck ones' from solve_stuck. */
static int set_impulses(const double W[36], const double vstar[6], unsigned stuck,
                        const double sigma[6], const double slide[6], double impulse[6])
{
    int k;
    for (k = 0; k < 6; k++)
        if (!((stuck >> k) & 1u))
            impulse[k] = -sigma[k] * slide[k];
    return solve_stuck(W, vstar, stuck, impulse);
}

/* Carriage k's speed at the step's end under the impulses: v*_k + (W p)_k. */
static double end_speed(const double W[36], const double vstar[6], const double impulse[6], int k)
{
    double v = vstar[k];
    int j;
    for (j = 0; j < 6; j++)
        v += W[6 * k + j] * impulse[j];
    return v;
}

int hg_friction_solve(const hg_params *p, const double W[36], const double vstar[6],
                      const double v0[6], unsigned at_rest, double dt, hg_friction_out *o)
{
    const double ps = p->f_static_n * dt;          /* the most static friction can give */
    double slide[6], sigma[6], vrev[6];
    unsigned stuck = 0, rest = at_rest;
    int k, it, rc;
    for (k = 0; k < 6; k++) {
        if (v0[k] == 0.0)
            rest |= 1u << k;
        slide[k] = hg_friction_sliding(p, fabs(v0[k])) * dt;
        /* at rest: alone, the impulse that keeps carriage k there is -v*_k / W_kk;
         * moving: it slides in its direction of motion */
        if ((rest >> k) & 1u) {
            if (fabs(vstar[k]) <= ps * W[7 * k])
                stuck |= 1u << k;
            sigma[k] = vstar[k] < 0.0 ? -1.0 : 1.0;
        } else {
            sigma[k] = v0[k] < 0.0 ? -1.0 : 1.0;
        }
        o->impulse[k] = 0.0;
        o->stop[k] = 1.0;
        vrev[k] = 0.0;
    }
    for (it = 0; it < HG_FRICTION_MAX_ITER; it++) {
        int worst = -1, changed = 0, pass;
        double excess = 0.0;
        /* the sliding force over the step follows the speed from v0 to its
         * end value: a few passes of the Stribeck mean (it varies by at most
         * f_static - f_coulomb) */
        for (pass = 0; pass < SLIDE_PASSES; pass++) {
            int moved = 0;
            rc = set_impulses(W, vstar, stuck, sigma, slide, o->impulse);
            if (rc)
                return rc;
            for (k = 0; k < 6; k++) {
                double v1, s1;
                if ((stuck >> k) & 1u)
                    continue;
                v1 = end_speed(W, vstar, o->impulse, k);
                s1 = sliding_mean(p, sigma[k] * v0[k] > 0.0 ? fabs(v0[k]) : 0.0,
                                  sigma[k] * v1 > 0.0 ? fabs(v1) : 0.0) * dt;
                moved |= s1 != slide[k];
                slide[k] = s1;
            }
            if (!moved)
                break;                     /* a fixed point: further passes change nothing */
        }
        rc = set_impulses(W, vstar, stuck, sigma, slide, o->impulse);
        if (rc)
            return rc;
        for (k = 0; k < 6; k++)          /* a stuck carriage the load breaks away */
            if ((stuck >> k) & 1u && fabs(o->impulse[k]) - ps > excess) {
                excess = fabs(o->impulse[k]) - ps;
                worst = k;
            }
        if (worst >= 0) {
            stuck &= ~(1u << worst);
            sigma[worst] = o->impulse[worst] > 0.0 ? -1.0 : 1.0; /* it slides against the impulse */
            changed = 1;
        } else {
            double most = 0.0;
            for (k = 0; k < 6; k++) {        /* a sliding carriage that friction would reverse */
                double v;
                if ((stuck >> k) & 1u)
                    continue;
                v = end_speed(W, vstar, o->impulse, k);
                if (sigma[k] * v < most) {
                    most = sigma[k] * v;
                    worst = k;
                }
            }
            if (worst >= 0) {
                stuck |= 1u << worst;
                vrev[worst] = sigma[worst] * most;   /* its end speed had it kept sliding */
                changed = 1;
            }
        }
        if (!changed)
            break;
    }
    if (it == HG_FRICTION_MAX_ITER) {    /* no set settled: the impulses of the last one */
        rc = set_impulses(W, vstar, stuck, sigma, slide, o->impulse);
        if (rc)
            return rc;
    }
    for (k = 0; k < 6; k++)              /* moving carriages that stopped: when, at constant deceleration */
        if ((stuck >> k) & 1u && !((rest >> k) & 1u) && v0[k] != vrev[k])
            o->stop[k] = fmin(1.0, fmax(0.0, v0[k] / (v0[k] - vrev[k])));
    o->stuck = stuck;
    o->iterations = it;
    return 0;
}

int hg_friction_all_sliding(const hg_params *p, const double vpred[6], const double v0[6],
                            unsigned at_rest, const double est[6], double m_min, double dt,
                            hg_friction_out *o)
{
    const double flat = STRIBECK_FLAT * p->v_stribeck_mps;
    double e2 = 0.0, dv;
    int k;
    if (at_rest & 0x3fu)
        return 0;
    for (k = 0; k < 6; k++) {
        double sigma = v0[k] < 0.0 ? -1.0 : 1.0;
        if (!(sigma * v0[k] > flat))
            return 0;
        o->impulse[k] = -sigma * (p->f_coulomb_n * dt);
        e2 += (o->impulse[k] - est[k]) * (o->impulse[k] - est[k]);
    }
    dv = sqrt(e2) / m_min;
    for (k = 0; k < 6; k++)
        if (!((v0[k] < 0.0 ? -vpred[k] : vpred[k]) - dv > flat))
            return 0;
    for (k = 0; k < 6; k++)
        o->stop[k] = 1.0;
    o->stuck = 0;
    o->iterations = 0;
    return 1;
}
