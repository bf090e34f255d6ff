/* hg_stability.h - can the chosen step integrate a parameter set at the
 * running period? The stiff parts of the model act on each carriage, whose
 * inertia is at least its own mass plus the rotor's reflected inertia
 * (m_carriage + j_rotor (2 pi / lead)^2): the hard stop (k_stop with
 * c_visc + c_stop), viscous friction, the back-EMF of a bus-limited drive
 * (kt^2 (2 pi / lead)^2 / r_winding through the winding's L/R) and the
 * velocity-mode amplifier's loop (kp_vel, ki_vel). Each is a linear test
 * system on one carriage; one step of the scheme (the very sequence
 * hg_step runs: drive from the step's start, stages, winding update) maps
 * its state linearly, and the step is stable when every eigenvalue of that
 * map lies inside the unit circle (Jury's test on its characteristic
 * polynomial, no root finding). Sliding and static friction are resolved
 * implicitly (hg_friction.h) and set no bound.
 *
 * Pure C, bounded loops. */
#ifndef HG_STABILITY_H
#define HG_STABILITY_H

#include "hg_params.h"
#include "hg_model.h"

/* What the check found. */
typedef struct {
    unsigned substeps;      /* steps per period needed (>= the requested), 0: none up to the maximum */
    const char *param;      /* spec name of the parameter that limits the step, 0 if none does */
    double dt_max_s;        /* with it, the longest stable step (s); 0 if none limits */
} hg_stability;

/* The substeps (from substeps_min up to substeps_max) the scheme needs to
 * integrate p stably at period_s; writes *out. 0, or HG_ERR_STIFF when
 * substeps_max are not enough (out names the parameter and its bound). */
int hg_stability_check(const hg_params *p, hg_integrator scheme, double period_s, unsigned substeps_min,
                       unsigned substeps_max, hg_stability *out);

#endif
