/* hg_trainid.h - the drive trains as the encoders see them, for
 * identifying each train's stiffness k_axial, damping c_axial and its
 * rotor's reflected mass (docs/identification.md: the drive train).
 *
 * The small fast motion of the six rotors, their trains and the machine's
 * carriages about a slow motion: per drive k
 *   m_r[k] xr''[k] = u[k] - f[k],   f[k] = k[k] (xr[k] - x[k]) + c[k] (xr'[k] - x'[k])
 *   M_L x''        = f - diag(c_visc) x'
 * with u the motor's force (the drive current times kt 2 pi / lead), xr
 * the rotor (what the encoder counts) and x the carriage, both in the
 * load's coordinate (hg_drivetrain.h), and M_L the carriages' mass matrix
 * of the rigid model at the slow motion's pose with the rotors taken out
 * (M - diag(m_r): the rigid model's carriage masses hold the rotors). The
 * slow motion's gravity, velocity terms and sliding friction do not
 * change at the fast motion's amplitudes (a carriage sliding fast enough
 * that its speed keeps its sign), so they are not in it; no free play
 * (the train's force keeps its sign: the caller keeps to such stretches).
 *
 * Stepped as the board steps the machine: the scheme's stages (improved
 * Euler, Heun, RK4: hg_integrate's tableaus) on ns substeps per period,
 * the motor force held over each substep (the board's mean current). A
 * real machine is continuous: RK4 on enough substeps.
 * Host code (not in the realtime module). Pure C, no malloc. */
#ifndef HG_TRAINID_H
#define HG_TRAINID_H

#include "hg_scheme.h"
#include "hg_model.h"

/* The trains' parameters of one response (SI). */
typedef struct {
    double k[6];          /* axial stiffness (N/m), > 0 */
    double c[6];          /* axial damping (N s/m), >= 0 */
    double m_rotor[6];    /* rotor's reflected mass j_rotor (2 pi / lead)^2 (kg), > 0 */
    double c_visc[6];     /* the carriages' viscous friction (N s/m) */
} hg_trainid_params;

/* The state: rotor positions, rotor speeds, carriage positions, carriage speeds (6 each). */
#define HG_TRAINID_NSTATE 24

/* Respond to np periods of dt from state x (HG_TRAINID_NSTATE, updated):
 * period n's motor forces u[(n ns + s) 6 + k] over substep s of ns, the
 * rigid model's mass matrix of period n at mass[(n / every) 36] (row-major
 * 6x6, symmetric; a new one factored when it changes). motor[n 6 + k]
 * (and load[n 6 + k] when not 0): rotor (carriage) k at the end of period
 * n. 0, or HG_ERR_BAD_PARAM (an unknown scheme, ns < 1, every < 1, a
 * stiffness or rotor mass not positive) or HG_ERR_SINGULAR_MASS (M_L not
 * positive definite: a rotor mass above what the rigid model's carriage
 * masses hold). */
int hg_trainid_response(const hg_trainid_params *p, hg_integrator scheme, int ns, double dt, long np,
                        const double *mass, long every, const double *u, double x[HG_TRAINID_NSTATE],
                        double *motor, double *load);

/* The motors' force (N) over each of ns substeps of each of np periods of
 * dt, as the board's step makes it: m's amplifiers and windings
 * (hg_drive_step, the mean current of each substep times kt 2 pi / lead)
 * under DAC output volts[n 6 + k] (after the DAC: hg_dac_output), at
 * rotor speeds speed[n 6 + k] (m/s, held over the period), from no current
 * and an empty velocity loop; amplifiers on. u[(n ns + s) 6 + k]. 0 or
 * HG_ERR_BAD_PARAM (ns < 1, dt not positive). */
int hg_trainid_drive(const hg_model *m, int ns, double dt, long np, const double *volts, const double *speed,
                     double *u);

#endif
