/* hg_step_broken.h - the machine with the bars of d->broken_bars removed
 * (fault injection), any kind, for hg_integrate: the lumped-bar model
 * (m->k_lumped) in q = [z(6), c(6)] keeping only the intact bars'
 * constraints (the broken bars' lumped masses stay: see docs/dynamics.md).
 * Accelerations from the augmented (KKT) system; stabilization by an
 * M-weighted Newton projection of q (bounded) and the projection of q'
 * onto the remaining constraints. */
#ifndef HG_STEP_BROKEN_H
#define HG_STEP_BROKEN_H

#include "hg_integrate.h"

/* Accelerations qdd[12] at (q, qd) with carriage forces fz (N); scratch in
 * d->work.step. 0 or HG_ERR_SINGULAR_JACOBIAN. */
int hg_broken_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                    const double fz[6], double *qdd);

/* Project the predicted (q1, qd1) in place; *residual_m = largest
 * intact-bar length error. 0, SINGULAR_JACOBIAN, DIVERGED or STABILIZATION
 * (hg_step then applies hg_guard_check, the region of the broken machine
 * included). */
int hg_broken_stabilize(const hg_model *m, hg_data *d, double *q1, double *qd1,
                        double *residual_m);

/* The two as an hg_dae. */
extern const hg_dae hg_broken_dae;

#endif
