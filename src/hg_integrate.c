/* hg_integrate.c - improved Euler, Heun and RK4 on the state of any
 * parametrization, followed by its constraint stabilization. */
#include "hg_integrate.h"
#include "hg_system.h"
#include "hg_forces.h"
#include "hg_errors.h"

/* Stage vectors laid over hg_work.stage. */
typedef struct {
    double qs[HG_NQ_MAX], vs[HG_NQ_MAX]; /* stage state */
    double a[HG_NQ_MAX];                 /* stage accelerations */
    double sq[HG_NQ_MAX], sv[HG_NQ_MAX]; /* weighted sums of the stages' q' and q'' */
    double fz[6];                        /* stage carriage forces */
} stage_ws;
typedef char hg_stage_ws_fits[sizeof(stage_ws) <= sizeof(((hg_work *)0)->stage) ? 1 : -1];

/* The paper's step: q1 = q0 + q0' dt + q0'' dt^2/2, q1' = q0' + q0'' dt
 * (the five vectors must not overlap: restrict lets the compiler pack them). */
static inline __attribute__((always_inline)) void
improved_euler(const int n, const double *restrict q0, const double *restrict qd0,
               const double *restrict qdd, double dt, double *restrict q1, double *restrict qd1)
{
    const double h2 = 0.5 * dt * dt;
    int i;
    for (i = 0; i < n; i++) {
        q1[i] = q0[i] + qd0[i] * dt + qdd[i] * h2;
        qd1[i] = qd0[i] + qdd[i] * dt;
    }
}

/* Accelerations at the stage state (qs, vs) of w, forces from volts. */
static int stage_accel(const hg_model *m, const hg_dae *f, hg_data *ctx, stage_ws *w,
                       const double volts[6])
{
    hg_carriage_forces(m, w->qs, w->vs, volts, w->fz, 0);
    return f->accel(m, ctx, w->qs, w->vs, w->fz, w->a);
}

int hg_integrate(const hg_model *m, hg_integrator scheme, const hg_dae *f, hg_data *ctx,
                 const double *q0, const double *qd0, const double volts[6],
                 const double fz0[6], double dt, double *q1, double *qd1, double *qdd,
                 double *residual_m)
{
    /* RK4's stage offsets (c_i dt) and weights (b_i); Heun's are the first two */
    static const double rk4_c[4] = {0.0, 0.5, 0.5, 1.0};
    static const double rk4_b[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
    static const double heun_c[2] = {0.0, 1.0};
    static const double heun_b[2] = {0.5, 0.5};
    stage_ws *w = (stage_ws *)ctx->work.stage;
    const double *c, *b;
    int n = f->n, i, s, ns, rc;
    switch (scheme) {
    case HG_INTEGRATOR_IMPROVED_EULER:
        rc = f->accel(m, ctx, q0, qd0, fz0, qdd);
        if (rc)
            return rc;
        if (n == HG_NQ_REDUCED)        /* a constant length lets the compiler unroll */
            improved_euler(HG_NQ_REDUCED, q0, qd0, qdd, dt, q1, qd1);
        else
            improved_euler(n, q0, qd0, qdd, dt, q1, qd1);
        return f->stabilize(m, ctx, q1, qd1, residual_m);
    case HG_INTEGRATOR_HEUN:
        c = heun_c, b = heun_b, ns = 2;
        break;
    case HG_INTEGRATOR_RK4:
        c = rk4_c, b = rk4_b, ns = 4;
        break;
    default:
        return HG_ERR_BAD_PARAM;
    }
    /* explicit Runge-Kutta whose stage i starts from y0 + c_i dt k_(i-1)
     * (true of Heun's and classical RK4's tableaux) */
    for (s = 0; s < ns; s++) {
        if (s == 0) {
            rc = f->accel(m, ctx, q0, qd0, fz0, w->a);
            for (i = 0; i < n; i++) {
                w->vs[i] = qd0[i];
                w->sq[i] = 0.0;
                w->sv[i] = 0.0;
            }
        } else {
            const double h = c[s] * dt;
            double vprev;
            for (i = 0; i < n; i++) {  /* k_(s-1) = (vs, a) of the previous stage */
                vprev = w->vs[i];
                w->qs[i] = q0[i] + h * vprev;
                w->vs[i] = qd0[i] + h * w->a[i];
            }
            rc = stage_accel(m, f, ctx, w, volts);
        }
        if (rc)
            return rc;
        for (i = 0; i < n; i++) {
            w->sq[i] += b[s] * w->vs[i];
            w->sv[i] += b[s] * w->a[i];
        }
    }
    for (i = 0; i < n; i++) {
        q1[i] = q0[i] + dt * w->sq[i];
        qd1[i] = qd0[i] + dt * w->sv[i];
        qdd[i] = w->sv[i];
    }
    return f->stabilize(m, ctx, q1, qd1, residual_m);
}
