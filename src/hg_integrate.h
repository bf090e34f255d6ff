/* hg_integrate.h - the time integration schemes of hg_step (the
 * hg_integrator enum of hg_model.h), shared by every parametrization.
 *
 * A parametrization is seen as the ODE of its accelerations (the paper's
 * Eq. 13: q'' with the independent coordinates' dynamics and the
 * dependent coordinates' accelerations that keep the constraints) plus a
 * constraint stabilization of the predicted state. A scheme advances the
 * whole state (q, q') over dt with the volts held (zero-order hold, as a
 * DAC), re-evaluating the carriage forces (friction, stops) at each stage,
 * then applies the stabilization once:
 *   improved Euler (paper): q1 = q0 + q0' dt + q0'' dt^2/2, q1' = q0' + q0'' dt
 *                           (one evaluation; first order in q', second in q)
 *   Heun (RK2):  two evaluations, second order
 *   RK4:         four evaluations, fourth order (classical weights)
 * The stabilization (one Newton-Raphson iteration on the dependent
 * positions and the velocity projection) changes the dependent
 * coordinates by the constraint drift of one step, O(dt^(p+1)), so the
 * schemes keep their order (measured: docs/dynamics.md). */
#ifndef HG_INTEGRATE_H
#define HG_INTEGRATE_H

#include "hg_model.h"

/* One parametrization as the integrator sees it; ctx is the hg_data whose
 * scratch the functions may use (its state is not touched). */
typedef struct {
    int n; /* coordinates: 12 or 24 */
    /* accelerations qdd[n] at (q, qd) with carriage forces fz (N): 0 or a code */
    int (*accel)(const hg_model *m, hg_data *ctx, const double *q, const double *qd,
                 const double fz[6], double *qdd);
    /* stabilize the predicted (q1, qd1) in place; *residual_m the largest
     * bar-length error left (m): 0 or a code */
    int (*stabilize)(const hg_model *m, hg_data *ctx, double *q1, double *qd1,
                     double *residual_m);
} hg_dae;

/* Advance (q0, qd0) by dt with `scheme`: fz0 are the carriage forces at
 * the start (hg_carriage_forces of q0, qd0, volts), later stages compute
 * their own from volts. Writes q1, qd1 and qdd (the step's mean
 * acceleration, (q1' - q0')/dt before the stabilization). Stage vectors in
 * ctx->work.stage. 0 or the first failing function's code (HG_ERR_BAD_PARAM
 * for an unknown scheme). */
int hg_integrate(const hg_model *m, hg_integrator scheme, const hg_dae *f, hg_data *ctx,
                 const double *q0, const double *qd0, const double volts[6],
                 const double fz0[6], double dt, double *q1, double *qd1, double *qdd,
                 double *residual_m);

#endif
