/* hg_step_cartesian.h - the Reduced Cartesian parametrization (bars
 * lumped, q = [z(6), c(6)], head pose c independent, Phi_z diagonal so
 * A = -Phi_z^-1 Phi_c) for hg_integrate, and the fused variant: the whole
 * improved-Euler step as one generated function, the accelerations as
 * another for the stages of higher-order schemes. */
#ifndef HG_STEP_CARTESIAN_H
#define HG_STEP_CARTESIAN_H

#include "hg_integrate.h"

/* Accelerations qdd[12] at (q, qd) with carriage forces fz (N). The head's
 * sin/cos come from d->trig_sc when d->trig_valid and q's angles equal
 * d->trig_key_rad. Scratch in d->work.step. 0 or HG_ERR_SINGULAR_MASS. */
int hg_cartesian_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                       const double fz[6], double *qdd);

/* One diagonal Newton step on z at the predicted state and z' = A c';
 * *residual_m = largest bar-length error left; d->work.sc1 receives the
 * sin/cos of q1's head angles. 0. */
int hg_cartesian_stabilize(const hg_model *m, hg_data *d, double *q1, double *qd1,
                           double *residual_m);

/* hg_dae.hold: the carriages of `held` back at z0 with zero speed by
 * moving the head pose (Newton on the held bars' constraints, minimum
 * norm in the step start's reduced mass matrix) and its velocity. */
void hg_cartesian_hold(const hg_model *m, hg_data *d, const double z0[6], unsigned held,
                       double *q1, double *qd1);

/* The three as an hg_dae. */
extern const hg_dae hg_cartesian_dae;

/* Accelerations as hg_cartesian_accel, from the generated
 * hg_gen_fused_accel (Eq. 13 as one function, the first part of the fused
 * step): the fused kind's stages under Heun and RK4. 0 or HG_ERR_SINGULAR_MASS. */
int hg_fused_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                   const double fz[6], double *qdd);

/* hg_fused_accel with the Reduced Cartesian stabilization, as an hg_dae. */
extern const hg_dae hg_fused_dae;

/* The fused improved-Euler step (generated hg_gen_fused_step, same
 * algorithm as improved Euler on hg_cartesian_dae): sin/cos of q0's head
 * angles sc0, forces fz; writes q1, qd1, qdd, d->work.sc1, *residual_m.
 * 0 or HG_ERR_SINGULAR_MASS. */
int hg_fused_step(const hg_model *m, hg_data *d, const double *q0, const double *qd0,
                  const double sc0[6], const double fz[6], double dt, double *q1,
                  double *qd1, double *qdd, double *residual_m);

#endif
