/* hg_system.h - what every parametrization's step shares: the state
 * vector layouts, the full Newton-Raphson position solve (reset at HOME),
 * bar angles from the geometry, and the energies (the head's sin/cos:
 * hg_head_trig, hg_kinematics.h).
 * State vectors: reduced models q = [z(6), c(6)], standard
 * q = [z(6), a(12), c(6)] (a = phi_k, theta_k per bar), all SI. */
#ifndef HG_SYSTEM_H
#define HG_SYSTEM_H

#include "hg_model.h"
#include "hg_kinematics.h"   /* hg_head_trig */

#define HG_NQ_REDUCED 12
#define HG_NQ_STANDARD 24
#define HG_NQ_MAX 24

/* Number of coordinates of m's parametrization (12 or 24). */
int hg_system_nq(const hg_model *m);

/* Bar angles a[12] (phi_k, theta_k: u_k = (A_k - B_k)/l = Rx(phi) Ry(theta)
 * (0,0,-1)) of the geometry at carriage heights z and head pose c; a bar
 * whose ends meet keeps its entries. */
void hg_bar_angles(const hg_params *p, const double z[6], const double c[6], double a[12]);

/* Full Newton-Raphson on the dependent positions of q (z fixed) from the
 * guess in q: the head pose c with the lumped-bar constraints (6x6), then,
 * for the standard model, the bar angles from the geometry. 0,
 * HG_ERR_NO_CONVERGENCE or HG_ERR_SINGULAR_JACOBIAN. */
int hg_solve_positions(const hg_model *m, double *q);

/* The constraint stabilization of the z-independent steps, with
 * X = Phi_d^-1 [Phi_z | Phi] (nd x 7) at the predicted state: the one
 * Newton-Raphson iteration d1 -= Phi_d^-1 Phi and the projection
 * d1' = A z1' (A = -X[:, :6]); q1 = [z, d(nd)]. */
void hg_stabilize_dependent(int nd, const double *X, double *q1, double *qd1);

/* Kinetic energy 1/2 q'^T M q' (J, rotor inertia included) and gravity
 * potential (J, up to a constant) of the state (q, qd). */
void hg_model_energy(const hg_model *m, const double *q, const double *qd,
                     double *kinetic_j, double *potential_j);

/* The same for the lumped-bar model with constants k at q = [z, c]. */
void hg_lumped_energy(const double *k, const double *q, const double *qd,
                      double *kinetic_j, double *potential_j);

#endif
