/* hg_step_joints.h - the Reduced Joints parametrization (bars lumped,
 * q = [z(6), c(6)], z independent) for hg_integrate: its accelerations
 * (the paper's Eq. 13 with A = -Phi_c^-1 Phi_z) and its stabilization
 * (one Newton-Raphson iteration on c and the projection c' = A z'). */
#ifndef HG_STEP_JOINTS_H
#define HG_STEP_JOINTS_H

#include "hg_integrate.h"

/* Accelerations qdd[12] at (q, qd) with carriage forces fz (N); scratch in
 * d->work.step. 0, HG_ERR_SINGULAR_JACOBIAN or HG_ERR_SINGULAR_MASS. */
int hg_joints_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                    const double fz[6], double *qdd);

/* Stabilize the predicted (q1, qd1) in place (Jacobians at q1);
 * *residual_m = largest bar-length error left. 0 or HG_ERR_SINGULAR_JACOBIAN. */
int hg_joints_stabilize(const hg_model *m, hg_data *d, double *q1, double *qd1,
                        double *residual_m);

/* The two as an hg_dae. */
extern const hg_dae hg_joints_dae;

#endif
