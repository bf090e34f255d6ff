/* hg_forces.h - non-inertial forces on the six carriages: drive (DAC volts
 * -> amplifier current with its clamp -> motor torque -> ball screw),
 * viscous and smoothed Coulomb friction, and the mechanical hard stops
 * (stiff spring-dampers that only push). Gravity and the inertia of the
 * rotors are in the generated mass matrix and forces. Pure C and libm. */
#ifndef HG_FORCES_H
#define HG_FORCES_H

#include "hg_params.h"

/* Amplifier current (A) for a DAC command: volts clamped to +-10 V
 * (non-finite counts as 0), then ka V clamped to +-i_max. */
double hg_drive_current(const hg_params *p, double volts);

/* Force (N, along +z) of the hard stops on a carriage at z_m moving at
 * zd_mps: k_stop penetration plus c_stop zd beyond stop_min/stop_max,
 * never pulling the carriage into the stop. */
double hg_stop_force(const hg_params *p, double z_m, double zd_mps);

/* Net force on each carriage (N, +z up): drive + friction + stops; the
 * clamped currents go to current_a (may be 0). */
void hg_carriage_forces(const hg_params *p, const double z_m[6], const double zd_mps[6],
                        const double volts[6], double force_n[6], double current_a[6]);

#endif
