/* hg_step_standard.h - the Standard parametrization (bars as rigid
 * bodies, q = [z(6), a(12), c(6)], z independent) for hg_integrate: its
 * accelerations (Eq. 13 with the bar structure of Phi_d and M_dd
 * exploited) and its stabilization (one Newton-Raphson iteration on the
 * bar angles and head pose, projection d' = A z'). */
#ifndef HG_STEP_STANDARD_H
#define HG_STEP_STANDARD_H

#include "hg_integrate.h"

/* Accelerations qdd[24] at (q, qd) with carriage forces fz (N); scratch in
 * d->work.step. 0, HG_ERR_SINGULAR_JACOBIAN or HG_ERR_SINGULAR_MASS. */
int hg_standard_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                      const double fz[6], double *qdd);

/* Stabilize the predicted (q1, qd1) in place; *residual_m = largest
 * bar-length error left. 0 or HG_ERR_SINGULAR_JACOBIAN. */
int hg_standard_stabilize(const hg_model *m, hg_data *d, double *q1, double *qd1,
                          double *residual_m);

/* The two as an hg_dae. */
extern const hg_dae hg_standard_dae;

#endif
