/* hg_drive.h - servo amplifiers and motor windings, one channel each: what
 * current a DAC command puts into a winding over one (sub)step. Plant
 * agnostic: n <= HG_DRIVE_MAX channels, each with its own parameters (the
 * Hexaglide passes its six identical ones, hg_model's drive[]).
 *
 * Amplifier: torque mode, current command ka V; velocity mode, a PI loop
 * on the axis speed, i = kp_vel (v_ref - z') + ki_vel xi with
 * v_ref = V v_rated / 10 and xi the integrated speed error; the command is
 * limited to +-i_max. The amplifier's current loop is fast: it puts the
 * full bus voltage +-v_bus on the winding until the current reaches the
 * command, then holds it. The winding is R, L and the back-EMF
 * e = kt (2 pi / lead) z' (kt = ke in SI):
 *   L di/dt = u - R i - e,  |u| <= v_bus,
 * so the current a drive can push falls as its speed rises, and at full
 * command the axis reaches the voltage-limited top speed
 *   v = (v_bus kt k / R - load) / (c_visc + kt^2 k^2 / R),  k = 2 pi / lead.
 * Over a step the speed (back-EMF) and the command are held at the step's
 * start and the winding equation is solved exactly (piecewise
 * exponential); the mechanics get the step's mean current, constant over
 * the step like the DAC's output. A disabled amplifier (E-STOP, amp-fail,
 * fault) passes no current and resets its velocity loop.
 *
 * Units SI. Pure C and rtapi_math (no log: hg_drive.c has its own); no
 * malloc, bounded loops. */
#ifndef HG_DRIVE_H
#define HG_DRIVE_H

#include "hg_analog.h"      /* HG_DAC_VOLTS_MAX: the command range, +-10 V */

#define HG_DRIVE_MAX 8      /* channels of one call */

/* One channel's parameters (SI; the Hexaglide's: hg_params' drive fields). */
typedef struct {
    double kt_nm_per_a;        /* motor torque constant (= back-EMF constant, V s/rad) */
    double lead_m;             /* ball-screw lead per revolution */
    double r_winding_ohm;      /* winding resistance */
    double l_winding_h;        /* winding inductance */
    double amp_mode;           /* 0 torque (current) mode, 1 velocity mode */
    double ka_a_per_v;         /* torque mode: current per command volt */
    double i_max_a;            /* current limit */
    double v_bus_v;            /* bus voltage: the most the amplifier puts on the winding */
    double v_rated_mps;        /* velocity mode: axis speed at +10 V */
    double kp_vel_as_per_m;    /* velocity mode: current per speed error */
    double ki_vel_a_per_m;     /* velocity mode: current per integrated speed error */
} hg_drive_params;

/* A channel: its parameters and the constants that follow (hg_drive_init). */
typedef struct {
    hg_drive_params p;
    double force_per_amp_n;    /* kt 2 pi / lead: axis force per ampere (N/A), back-EMF per speed */
    double tau_s;              /* l_winding / r_winding: the winding's time constant */
} hg_drive_channel;

/* exp(-dt / tau) of each channel for the step length it was last used
 * with (computed when first needed): a self-contained fact, valid in any
 * copy; all zero = empty. */
typedef struct {
    double dt_s[HG_DRIVE_MAX], tau_s[HG_DRIVE_MAX], decay[HG_DRIVE_MAX];
} hg_drive_memo;

/* One step of the drives. */
typedef struct {
    double i_mean[HG_DRIVE_MAX]; /* mean winding current over the step (A) */
    double i_end[HG_DRIVE_MAX];  /* winding current at the end of the step (A) */
    double i_ref[HG_DRIVE_MAX];  /* the amplifier's current command after i_max (A) */
    double v_ref[HG_DRIVE_MAX];  /* velocity mode: the speed command (m/s) */
    unsigned limited;            /* bit k: the command hit i_max or the bus voltage (no integral windup) */
} hg_drive_out;

/* The channel of parameters p. */
void hg_drive_init(hg_drive_channel *c, const hg_drive_params *p);

/* The n channels c[] over one step of dt from their state (winding
 * current_a, axis speed_mps, velocity loop integral vloop_int_m, bit k of
 * enabled: amplifier k on) with DAC volts (clamped to +-10 V, non-finite
 * counts as 0 V); memo (may be 0) keeps exp(-dt / tau) between calls. */
void hg_drive_step(const hg_drive_channel *c, int n, const double *volts, const double *current_a,
                   const double *speed_mps, const double *vloop_int_m, unsigned enabled, double dt,
                   hg_drive_memo *memo, hg_drive_out *o);

/* Velocity loop integral after a step that moved the axes from z0 to
 * z1: xi += v_ref dt - (z1 - z0), exactly the integral of the speed error,
 * unless the command was limited (conditional integration); 0 for
 * disabled amplifiers and in torque mode. */
void hg_drive_integral(const hg_drive_channel *c, int n, unsigned enabled, const hg_drive_out *o,
                       const double *z0, const double *z1, double dt, double *vint);

/* ln x for x >= 1 with rtapi_math's functions (square roots, then the
 * series of ln(1 + y)); relative error below 1e-12. */
double hg_drive_log(double x);

#endif
