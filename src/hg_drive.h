/* hg_drive.h - the six servo amplifiers and motor windings: what current a
 * DAC command puts into a winding over one (sub)step.
 *
 * Amplifier: torque mode, current command ka V; velocity mode, a PI loop
 * on the carriage speed, i = kp_vel (v_ref - z') + ki_vel xi with
 * v_ref = V v_rated / 10 and xi the integrated speed error; the command is
 * limited to +-i_max. The amplifier's current loop is fast: it puts the
 * full bus voltage +-v_bus on the winding until the current reaches the
 * command, then holds it. The winding is R, L and the back-EMF
 * e = kt (2 pi / lead) z' (kt = ke in SI):
 *   L di/dt = u - R i - e,  |u| <= v_bus,
 * so the current a drive can push falls as its speed rises, and at full
 * command the carriage reaches the voltage-limited top speed
 *   v = (v_bus kt k / R - load) / (c_visc + kt^2 k^2 / R),  k = 2 pi / lead.
 * Over a step the speed (back-EMF) and the command are held at the step's
 * start and the winding equation is solved exactly (piecewise
 * exponential); the mechanics get the step's mean current, constant over
 * the step like the DAC's output. A disabled amplifier (E-STOP, amp-fail,
 * fault) passes no current and resets its velocity loop.
 *
 * Units SI. Pure C and rtapi_math (no log: hg_drive.c has its own). */
#ifndef HG_DRIVE_H
#define HG_DRIVE_H

#include "hg_model.h"

/* One step of the drives. */
typedef struct {
    double i_mean[6];   /* mean winding current over the step (A) */
    double i_end[6];    /* winding current at the end of the step (A) */
    double i_ref[6];    /* the amplifier's current command after i_max (A) */
    double v_ref[6];    /* velocity mode: the speed command (m/s) */
    unsigned limited;   /* bit k: the command hit i_max or the bus voltage (no integral windup) */
} hg_drive_out;

/* The drives over one step of dt from d's state (current_a, zd_mps,
 * vloop_int_m, amp_enabled) with DAC volts (clamped to +-10 V,
 * non-finite counts as 0 V). */
void hg_drive_step(const hg_model *m, const hg_data *d, const double volts[6], double dt,
                   hg_drive_out *o);

/* Velocity loop integral after a step that moved the carriages from z0 to
 * z1: xi += v_ref dt - (z1 - z0), exactly the integral of the speed error,
 * unless the command was limited (conditional integration); 0 for
 * disabled amplifiers and in torque mode. */
void hg_drive_integral(const hg_model *m, unsigned enabled, const hg_drive_out *o,
                       const double z0[6], const double z1[6], double dt, double vint[6]);

/* ln x for x >= 1 with rtapi_math's functions (square roots, then the
 * series of ln(1 + y)); relative error below 1e-12. */
double hg_drive_log(double x);

#endif
