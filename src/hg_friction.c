/* hg_friction.c - stick and slip of a plant's axes at the velocity level
 * (hg_friction.h). */
#include "hg_math.h"
#include "hg_compiler.h"
#include "hg_friction.h"
#include "hg_linalg.h"
#include "hg_errors.h"

#define SLIDE_PASSES 3   /* fixed-point passes of the sliding force over the step's speed range */
#define STRIBECK_FLAT 6.0 /* beyond 6 v_stribeck exp(-(v/v_s)^2) < 2.4e-16: the curve is f_coulomb */

int hg_friction_any(const hg_friction_channel *c, int n)
{
    int k;
    for (k = 0; k < n && k < HG_FRICTION_MAX_N; k++)
        if (c[k].f_static_n > 0.0 || c[k].f_coulomb_n > 0.0)
            return 1;
    return 0;
}

double hg_friction_shape(const hg_friction_channel *c, double v)
{
    double x = v / c->v_stribeck_mps;
    if (!(fabs(x) <= STRIBECK_FLAT))
        return 0.0;
    return exp(-x * x);
}

double hg_friction_curve(const hg_friction_channel *c, double v)
{
    return c->f_coulomb_n + (c->f_static_n - c->f_coulomb_n) * hg_friction_shape(c, v);
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

/* What one solve works with: the channels, the step, and the erf of each
 * axis's start speed (the same in every pass: computed once, key NaN = not yet). */
typedef struct {
    const hg_friction_channel *c;
    double dt;
    double erf_key[HG_FRICTION_MAX_N], erf_val[HG_FRICTION_MAX_N];
} solve_ctx;

/* erf_pos(a / v_stribeck) of axis k, from the context when it has it. */
static double erf_start(solve_ctx *x, int k, double a)
{
    if (!(x->erf_key[k] == a)) {
        x->erf_key[k] = a;
        x->erf_val[k] = erf_pos(a / x->c[k].v_stribeck_mps);
    }
    return x->erf_val[k];
}

/* Mean of axis k's Stribeck curve while the speed runs linearly from a to
 * b (a, b >= 0): f_c + (f_s - f_c) mean of exp(-(v/v_s)^2), in closed form
 * (v_s sqrt(pi)/2 (erf(b/v_s) - erf(a/v_s)) / (b - a)); the curve at the
 * mean speed when a and b are too close for the difference (within
 * 0.01 v_s, where both err by about 1e-5 of f_s - f_c at most). */
static double sliding_mean(solve_ctx *x, int k, double a, double b)
{
    const hg_friction_channel *c = &x->c[k];
    const double vs = c->v_stribeck_mps, d = b - a;
    double g;
    if (c->f_static_n == c->f_coulomb_n || (a > STRIBECK_FLAT * vs && b > STRIBECK_FLAT * vs))
        return c->f_coulomb_n;            /* on the flat of the curve all step long */
    if (fabs(d) < 1e-2 * vs)          /* midpoint error (d/vs)^2/12 below erf's 1.2e-7 vs/d */
        return hg_friction_curve(c, 0.5 * (a + b));
    g = 0.88622692545275801365 * vs * (erf_pos(b / vs) - erf_start(x, k, a)) / d;
    /* a mean of exp(-x^2): the fit's error must not leave [0, 1] (libm's fmax(0, fmin(1, g))) */
    g = !(g <= 1.0) ? 1.0 : (g < 0.0 ? 0.0 : g);
    return c->f_coulomb_n + (c->f_static_n - c->f_coulomb_n) * g;
}

/* The LU factors of the sticking axes' block W_SS (HG_FRICTION_MAX_N at
 * most), kept while the sticking set stays: key the set, ~0u = none. */
typedef struct {
    unsigned key;
    int m, idx[HG_FRICTION_MAX_N], piv[HG_FRICTION_MAX_N];
    double lu[HG_FRICTION_MAX_N * HG_FRICTION_MAX_N];
} stuck_lu;

/* Impulses of the sticking axes (mask stuck) that make their speeds
 * exactly 0 with the sliding ones' impulses fixed: W_SS p_S = -(v*_S + W_SF p_F). */
static HG_ALWAYS_INLINE int
solve_stuck(const int n, const double *W, const double *vstar, unsigned stuck, stuck_lu *f,
            double *p)
{
    double b[HG_FRICTION_MAX_N];
    int i, j;
    if (stuck == 0)
        return 0;
    if (f->key != stuck) {            /* factor W_SS of this set */
        f->key = ~0u;
        f->m = 0;
        for (i = 0; i < n; i++)
            if ((stuck >> i) & 1u)
                f->idx[f->m++] = i;
        for (i = 0; i < f->m; i++)
            for (j = 0; j < f->m; j++)
                f->lu[f->m * i + j] = W[n * f->idx[i] + f->idx[j]];
        if (hg_lu_factor(f->m, f->lu, f->piv))
            return HG_ERR_SINGULAR_MASS;
        f->key = stuck;
    }
    for (i = 0; i < f->m; i++) {
        double r = -vstar[f->idx[i]];
        for (j = 0; j < n; j++)
            if (!((stuck >> j) & 1u))
                r -= W[n * f->idx[i] + j] * p[j];
        b[i] = r;
    }
    hg_lu_solve(f->m, f->lu, f->piv, 1, b);
    for (i = 0; i < f->m; i++)
        p[f->idx[i]] = b[i];
    return 0;
}

/* The impulses of a stick/slip set: the sliding axes' from their sliding
 * friction (sigma, slide), the stuck ones' from solve_stuck. */
static HG_ALWAYS_INLINE int
set_impulses(const int n, const double *W, const double *vstar, unsigned stuck, stuck_lu *f,
             const double *sigma, const double *slide, double *impulse)
{
    int k;
    for (k = 0; k < n; k++)
        if (!((stuck >> k) & 1u))
            impulse[k] = -sigma[k] * slide[k];
    return solve_stuck(n, W, vstar, stuck, f, impulse);
}

/* Axis k's speed at the step's end under the impulses: v*_k + (W p)_k. */
static HG_ALWAYS_INLINE double
end_speed(const int n, const double *W, const double *vstar, const double *impulse, int k)
{
    double v = vstar[k];
    int j;
    for (j = 0; j < n; j++)
        v += W[n * k + j] * impulse[j];
    return v;
}

/* hg_friction_solve with n known where it is inlined (6: the Hexaglide). */
static HG_ALWAYS_INLINE int
solve(const int n, const hg_friction_channel *c, const double *W, const double *vstar,
      const double *v0, unsigned at_rest, double dt, hg_friction_out *o)
{
    double slide[HG_FRICTION_MAX_N], sigma[HG_FRICTION_MAX_N], vrev[HG_FRICTION_MAX_N];
    double ps[HG_FRICTION_MAX_N];             /* the most static friction can give */
    unsigned stuck = 0, rest = at_rest;
    solve_ctx x;
    stuck_lu f;
    int k, it, rc;
    x.c = c;
    x.dt = dt;
    f.key = ~0u;
    for (k = 0; k < HG_FRICTION_MAX_N; k++)
        x.erf_key[k] = x.erf_val[k] = NAN;
    for (k = 0; k < n; k++) {
        ps[k] = c[k].f_static_n * dt;
        if (v0[k] == 0.0)
            rest |= 1u << k;
        slide[k] = hg_friction_curve(&c[k], fabs(v0[k])) * dt;
        /* at rest: alone, the impulse that keeps axis k there is -v*_k / W_kk;
         * moving: it slides in its direction of motion */
        if ((rest >> k) & 1u) {
            if (fabs(vstar[k]) <= ps[k] * W[(n + 1) * k])
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
        int worst = -1, changed = 0, pass, moved = 1;
        double excess = 0.0;
        /* the sliding force over the step follows the speed from v0 to its
         * end value: a few passes of the Stribeck mean (it varies by at most
         * f_static - f_coulomb) */
        for (pass = 0; pass < SLIDE_PASSES; pass++) {
            moved = 0;
            rc = set_impulses(n, W, vstar, stuck, &f, sigma, slide, o->impulse);
            if (rc)
                return rc;
            for (k = 0; k < n; k++) {
                double v1, s1;
                if ((stuck >> k) & 1u)
                    continue;
                v1 = end_speed(n, W, vstar, o->impulse, k);
                s1 = sliding_mean(&x, k, sigma[k] * v0[k] > 0.0 ? fabs(v0[k]) : 0.0,
                                  sigma[k] * v1 > 0.0 ? fabs(v1) : 0.0) * dt;
                moved |= s1 != slide[k];
                slide[k] = s1;
            }
            if (!moved)
                break;                     /* a fixed point: further passes change nothing */
        }
        if (moved) {                       /* else o->impulse is already this set's and slide's */
            rc = set_impulses(n, W, vstar, stuck, &f, sigma, slide, o->impulse);
            if (rc)
                return rc;
        }
        for (k = 0; k < n; k++)          /* a stuck axis the load breaks away */
            if ((stuck >> k) & 1u && fabs(o->impulse[k]) - ps[k] > excess) {
                excess = fabs(o->impulse[k]) - ps[k];
                worst = k;
            }
        if (worst >= 0) {
            stuck &= ~(1u << worst);
            sigma[worst] = o->impulse[worst] > 0.0 ? -1.0 : 1.0; /* it slides against the impulse */
            changed = 1;
        } else {
            double most = 0.0;
            for (k = 0; k < n; k++) {        /* a sliding axis that friction would reverse */
                double v;
                if ((stuck >> k) & 1u)
                    continue;
                v = end_speed(n, W, vstar, o->impulse, k);
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
        rc = set_impulses(n, W, vstar, stuck, &f, sigma, slide, o->impulse);
        if (rc)
            return rc;
    }
    for (k = 0; k < n; k++)              /* moving axes that stopped: when, at constant deceleration */
        if ((stuck >> k) & 1u && !((rest >> k) & 1u) && v0[k] != vrev[k]) {
            double s = v0[k] / (v0[k] - vrev[k]);
            o->stop[k] = !(s >= 0.0) ? 0.0 : (s > 1.0 ? 1.0 : s);  /* libm's fmin(1, fmax(0, s)) */
        }
    o->stuck = stuck;
    o->iterations = it;
    return 0;
}

int hg_friction_solve(const hg_friction_channel *c, int n, const double *W, const double *vstar,
                      const double *v0, unsigned at_rest, double dt, hg_friction_out *o)
{
    if (n == 6)
        return solve(6, c, W, vstar, v0, at_rest, dt, o);
    if (n < 1 || n > HG_FRICTION_MAX_N)
        return HG_ERR_BAD_PARAM;
    return solve(n, c, W, vstar, v0, at_rest, dt, o);
}

int hg_friction_all_sliding(const hg_friction_channel *c, int n, const double *vpred,
                            const double *v0, unsigned at_rest, const double *est, double m_min,
                            double dt, hg_friction_out *o)
{
    double e2 = 0.0, dv;
    int k;
    if (n < 1 || n > HG_FRICTION_MAX_N || (at_rest & ((1u << n) - 1u)))
        return 0;
    for (k = 0; k < n; k++) {
        double sigma = v0[k] < 0.0 ? -1.0 : 1.0;
        if (!(sigma * v0[k] > STRIBECK_FLAT * c[k].v_stribeck_mps))
            return 0;
        o->impulse[k] = -sigma * (c[k].f_coulomb_n * dt);
        e2 += (o->impulse[k] - est[k]) * (o->impulse[k] - est[k]);
    }
    dv = sqrt(e2) / m_min;
    for (k = 0; k < n; k++)
        if (!((v0[k] < 0.0 ? -vpred[k] : vpred[k]) - dv > STRIBECK_FLAT * c[k].v_stribeck_mps))
            return 0;
    for (k = 0; k < n; k++)
        o->stop[k] = 1.0;
    o->stuck = 0;
    o->iterations = 0;
    return 1;
}
