/* hg_integrate.h - the time integration schemes of hg_step (the
 * hg_integrator enum of hg_model.h), shared by every parametrization.
 *
 * A parametrization is seen as the ODE of its accelerations (the paper's
 * Eq. 13: q'' with the independent coordinates' dynamics and the
 * dependent coordinates' accelerations that keep the constraints) plus a
 * constraint stabilization of the predicted state. A scheme advances the
 * whole state (q, q') over dt with the drive force held (zero-order hold,
 * as the DAC and hg_drive.h's mean current), re-evaluating the smooth
 * carriage forces (viscous friction, stops) at each stage:
 *   improved Euler (paper): q1 = q0 + q0' dt + q0'' dt^2/2, q1' = q0' + q0'' dt
 *                           (one evaluation; first order in q', second in q)
 *   Heun (RK2):  two evaluations, second order
 *   RK4:         four evaluations, fourth order (classical weights)
 * then resolves sliding and static friction at the velocity level
 * (hg_friction.h: impulses on the independent velocities, a carriage that
 * sticks from one step to the next keeps its position exactly), then
 * applies the stabilization once (one Newton-Raphson iteration on the
 * dependent positions and the velocity projection). The stabilization
 * changes the dependent coordinates by the constraint drift of one step,
 * O(dt^(p+1)), so the schemes keep their order (measured: docs/dynamics.md). */
#ifndef HG_INTEGRATE_H
#define HG_INTEGRATE_H

#include "hg_model.h"

/* One parametrization as the integrator sees it; ctx is the hg_data whose
 * scratch the functions may use (its state is not touched). */
typedef struct {
    int n;  /* coordinates: 12 or 24 */
    int io; /* the independent velocities the stabilization keeps start at q[io] (0 or 6) */
    int ni; /* ... and there are ni of them (6, or 12 for the broken-bar step) */
    /* accelerations qdd[n] at (q, qd) with carriage forces fz (N): 0 or a code;
     * when ctx->work.mass.want is set, also saves the mass data there (hg_model.h) */
    int (*accel)(const hg_model *m, hg_data *ctx, const double *q, const double *qd,
                 const double fz[6], double *qdd);
    /* put the carriages of mask `held` at heights z0 with zero speed in the
     * predicted (q1, qd1), before the stabilization, which must then leave them there */
    void (*hold)(const hg_model *m, hg_data *ctx, const double z0[6], unsigned held, double *q1,
                 double *qd1);
    /* stabilize the predicted (q1, qd1) in place; *residual_m the largest
     * bar-length error left (m): 0 or a code */
    int (*stabilize)(const hg_model *m, hg_data *ctx, double *q1, double *qd1,
                     double *residual_m);
} hg_dae;

/* Advance (q0, qd0) by dt with `scheme`: drive_n the forces held over
 * the step (N: the drives', hg_drive.h, plus the friction expected,
 * ctx->work.fric_est_n: the last step's), fz0 the smooth carriage forces at the start
 * (hg_carriage_forces of q0, qd0, drive_n; flexible trains: plus the
 * trains' force, also in ctx->work.train_n, with the motors' in
 * ctx->work.motor_n, as hg_step sets them), later stages compute their
 * own. Friction (when the parameters have it) writes its impulses and the
 * stuck carriages to ctx->work.fric_*; carriages stuck in ctx->stuck that
 * stay stuck keep their heights exactly, those that stop within the step
 * rest where a constant deceleration stops them. Holding the expected friction in the
 * stages keeps sliding and stuck carriages, and the rest of the machine
 * coupled to them, at the scheme's order between stick-slip events. Writes q1, qd1 and qdd (the step's mean
 * acceleration, (q1' - q0')/dt before the stabilization). Stage vectors
 * in ctx->work.stage. 0 or the first failing function's code
 * (HG_ERR_BAD_PARAM for an unknown scheme). */
int hg_integrate(const hg_model *m, hg_integrator scheme, const hg_dae *f, hg_data *ctx,
                 const double *q0, const double *qd0, const double drive_n[6],
                 const double fz0[6], double dt, double *q1, double *qd1, double *qdd,
                 double *residual_m);

/* Save the reduced mass matrix (factored by hg_spd6_factor; ldl and
 * inv_d may be s's own arrays, factored in place) and the map T from
 * independent to carriage velocities (0: the identity) as the step's mass
 * data. */
void hg_mass_save_reduced(hg_mass_snapshot *s, const double ldl[36], const double inv_d[6],
                          const double *T);

/* Save the LU factors of the n x n augmented (KKT) matrix as the step's
 * mass data (broken bars). */
void hg_mass_save_kkt(hg_mass_snapshot *s, int n, const double *lu, const int *piv);

/* hg_dae.hold of the parametrizations whose carriage heights are
 * independent (q1[k] = z0[k], q1'[k] = 0). */
void hg_hold_independent(const hg_model *m, hg_data *ctx, const double z0[6], unsigned held,
                         double *q1, double *qd1);

/* Carriage speed changes dz[6] and independent velocity changes dv[ni]
 * for carriage impulses p[6] (N s), from the mass data s of the step's
 * start (0 for kind 0: no data). */
void hg_mass_response(const hg_mass_snapshot *s, const double p[6], double *dv, double dz[6]);

/* W (6x6 row-major): column k the carriage speed changes dz of
 * hg_mass_response for a unit impulse on carriage k, bit for bit, for all
 * six columns at once where the mass data allow (kind 1 with a finite T),
 * else column by column. */
void hg_mass_response_matrix(const hg_mass_snapshot *s, double W[36]);

#endif
