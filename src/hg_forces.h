/* hg_forces.h - the smooth non-inertial forces on the six carriages: the
 * drive (the winding current of the step, hg_drive.h, times kt 2 pi / lead),
 * viscous friction and the mechanical hard stops (stiff spring-dampers that
 * only push). They are evaluated at every integration stage. Sliding and
 * static friction are not smooth: hg_friction.h resolves them once per step
 * at the velocity level. Gravity and the rotors' inertia are in the
 * generated mass matrix and forces. Pure C and libm. */
#ifndef HG_FORCES_H
#define HG_FORCES_H

#include "hg_model.h"
#include "hg_analog.h"            /* HG_DAC_VOLTS_MAX: the drives' +-10 V command range */

/* Net smooth force on each carriage (N, +z up): drive_n (the drive's force
 * over the step) - c_visc z' + the hard stops: k_stop times the
 * penetration beyond stop_min/stop_max plus c_stop z', never pulling the
 * carriage in. */
void hg_carriage_forces(const hg_model *m, const double z_m[6], const double zd_mps[6],
                        const double drive_n[6], double force_n[6]);

#endif
