/* hg_step.h - internal contract between hg_dynamics.c and the per-model
 * integration steps. State vectors: reduced models q = [z(6), c(6)],
 * standard q = [z(6), a(12), c(6)] (a = phi_k, theta_k per bar), all SI.
 * Each step reads (q0, qd0) and the carriage forces fz (N) and writes the
 * new state (q1, qd1) and the accelerations of the step (qdd); it never
 * touches its inputs, so a failed step leaves the caller's state intact.
 * residual_m receives the largest bar-length error after the stabilization. */
#ifndef HG_STEP_H
#define HG_STEP_H

#include "hg_dynamics.h"

#define HG_NQ_REDUCED 12
#define HG_NQ_STANDARD 24
#define HG_NQ_MAX 24

/* One parametrization as dense blocks, q = [z(6), d(nd)]: nd = 18
 * (standard: 12 bar angles then c) or 6 (reduced: c). */
typedef struct {
    int nd;
    double mzz[6];               /* M_zz, diagonal */
    double Mzd[6 * 18];          /* M_zd, 6 x nd */
    double Mdd[18 * 18];         /* M_dd, nd x nd */
    double Q[24];                /* gravity - velocity terms, [z, d] (no carriage forces) */
    double Phi_d[18 * 18];       /* dPhi/dd, nd x nd */
    double Phi_z[18 * 6];        /* dPhi/dz, nd x 6 */
    double gamma[18];            /* (Phi_q q')_q q' */
} hg_system;

/* Fill s from the generated terms of m's parametrization at (q, qd). */
void hg_system_terms(const hg_model *m, const double *q, const double *qd, hg_system *s);

/* Constraints phi (nd) and their Jacobian blocks Phi_d, Phi_z at q. */
void hg_system_constraints(const hg_model *m, const double *q, double *phi,
                           double *Phi_d, double *Phi_z);

/* Number of coordinates of m's parametrization (12 or 24). */
int hg_system_nq(const hg_model *m);

/* Improved Euler: qd1 = qd0 + qdd dt, q1 = q0 + qd0 dt + qdd dt^2/2. */
void hg_improved_euler(int n, const double *q0, const double *qd0, const double *qdd,
                       double dt, double *q1, double *qd1);

/* With X = Phi_d^-1 [Phi_z | Phi] (nd x 7) at the predicted state: the one
 * Newton-Raphson iteration d1 -= Phi_d^-1 Phi and the projection d1' = A z1'. */
void hg_stabilize_dependent(int nd, const double *X, double *q1, double *qd1);

/* Standard and Reduced Joints: z independent (Eq. 13 with A = -Phi_d^-1 Phi_z),
 * one Newton-Raphson position iteration and the velocity projection. */
int hg_step_joints(const hg_model *m, const double *q0, const double *qd0,
                   const double fz[6], double dt, double *q1, double *qd1, double *qdd,
                   double *residual_m);

/* Standard with the bar structure of Phi_d and M_dd exploited (same
 * algorithm and results as hg_step_joints on the standard model). */
int hg_step_standard(const hg_model *m, const double *q0, const double *qd0,
                     const double fz[6], double dt, double *q1, double *qd1, double *qdd,
                     double *residual_m);

/* Reduced Cartesian: c independent, Phi_z diagonal (A = -Phi_z^-1 Phi_c).
 * sc0: sin/cos of q0's head angles (hg_head_trig); sc1 receives q1's. */
int hg_step_cartesian(const hg_model *m, const double *q0, const double *qd0,
                      const double sc0[6], const double fz[6], double dt, double *q1,
                      double *qd1, double *qdd, double sc1[6], double *residual_m);

/* Fused Reduced Cartesian: the whole step is the generated hg_gen_fused_step
 * (same algorithm as hg_step_cartesian). */
int hg_step_fused(const hg_model *m, const double *q0, const double *qd0,
                  const double sc0[6], const double fz[6], double dt, double *q1,
                  double *qd1, double *qdd, double sc1[6], double *residual_m);

/* Machine with the bars in mask `broken` removed, any kind: the lumped-bar
 * model (m->k_lumped) in q = [z(6), c(6)] keeping only the intact bars'
 * constraints (the broken bars' lumped masses stay: see docs/dynamics.md),
 * accelerations from the augmented (KKT) system, improved Euler, then an
 * M-weighted Newton projection of q (bounded) and projection of q' onto
 * the remaining constraints. residual_m: largest intact-bar length error.
 * 0, SINGULAR_JACOBIAN, DIVERGED, STABILIZATION or OUT_OF_VOLUME
 * (the region of hg_step's contract in hg_dynamics.h). */
int hg_step_broken(const hg_model *m, unsigned broken, const double *q0, const double *qd0,
                   const double fz[6], double dt, double *q1, double *qd1, double *qdd,
                   double *residual_m);

/* Kinetic (J, rotor included) and gravity potential (J, up to a constant)
 * energies of the lumped-bar model with constants k at (q, qd), q = [z, c]. */
void hg_lumped_energy(const double *k, const double *q, const double *qd,
                      double *kinetic_j, double *potential_j);

/* sc = sin A, cos A, sin B, cos B, sin C, cos C of pose c = X Y Z A B C. */
void hg_head_trig(const double *c, double sc[6]);

/* Full Newton-Raphson on the dependent positions of q (z fixed; for the
 * reduced models the head pose c, for the standard model the bar angles
 * and c) from the guess in q. 0, HG_ERR_NO_CONVERGENCE or HG_ERR_SINGULAR_JACOBIAN. */
int hg_solve_positions(const hg_model *m, double *q);

/* Kinetic energy 1/2 q'^T M q' (J, rotor inertia included) and gravity
 * potential (J, up to a constant) of the state (q, qd). */
void hg_model_energy(const hg_model *m, const double *q, const double *qd,
                     double *kinetic_j, double *potential_j);

#endif
