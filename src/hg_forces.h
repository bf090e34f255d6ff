/* hg_forces.h - non-inertial forces on the six carriages: drive (DAC volts
 * -> amplifier current with its clamp -> motor torque -> ball screw),
 * viscous and smoothed Coulomb friction, and the mechanical hard stops
 * (stiff spring-dampers that only push). Gravity and the inertia of the
 * rotors are in the generated mass matrix and forces. Pure C and libm. */
#ifndef HG_FORCES_H
#define HG_FORCES_H

#include "hg_model.h"

/* The drives' (and the MOTENC-100 DAC's) command range: +-10 V. */
#define HG_DAC_VOLTS_MAX 10.0

/* Net force on each carriage (N, +z up): drive + friction + stops; the
 * clamped currents go to current_a (may be 0). The drive current is
 * ka V with V clamped to +-HG_DAC_VOLTS_MAX (non-finite counts as 0 V),
 * then clamped to +-i_max, times m->force_per_amp_n; a hard stop adds
 * k_stop times the penetration beyond stop_min/stop_max plus c_stop z',
 * never pulling the carriage in. */
void hg_carriage_forces(const hg_model *m, const double z_m[6], const double zd_mps[6],
                        const double volts[6], double force_n[6], double current_a[6]);

#endif
