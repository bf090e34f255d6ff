/* hg_stability.h - can the chosen step integrate a plant's parameters at
 * the running period? Plant agnostic: a plant describes each of its axes
 * (hg_stability_axis: the Hexaglide one carriage, all six alike; a serial
 * machine each axis) by the inertias and stiff parts that act on it: the
 * hard stop (k_stop with c_visc + c_stop), viscous friction, the back-EMF
 * of a bus-limited drive (force_per_amp^2 / r_winding through the
 * winding's L/R), the velocity-mode amplifier's loop (kp_vel, ki_vel) and
 * a flexible drive train's mode (k_axial, c_axial). Each is a linear test
 * system on one axis; one step of the scheme (the very sequence the plants
 * run: drive from the step's start, stages, winding update) maps its
 * state linearly, and the step is stable when every eigenvalue of that
 * map lies inside the unit circle (Jury's test on its characteristic
 * polynomial, no root finding). Sliding and static friction are resolved
 * implicitly (hg_friction.h) and set no bound.
 *
 * A train with backlash is not linear: its flanks part and meet, and an
 * explicit step can return more speed from an impact than came in (a
 * stable linear mode near its bound does: the rotor then chatters in the
 * free play until the step diverges). For such an axis the step must also
 * pass the impact test: the rotor pushed across the free play onto the
 * load by shares of the drive's force (HG_STAB_IMPACT_FORCES), stepped by the very
 * scheme with the train's own force law (hg_drivetrain_force), must not
 * hold more energy than the force has put in, beyond HG_STAB_IMPACT_ENERGY
 * times it (the exact motion holds at most 1 times it).
 *
 * Pure C, bounded loops. */
#ifndef HG_STABILITY_H
#define HG_STABILITY_H

#include "hg_scheme.h"

#define HG_STAB_AXES_MAX 8            /* axes of one check */
#define HG_STAB_AXIS_SYSTEMS 8        /* test systems of one axis, at most */
#define HG_STAB_SYSTEMS_MAX (HG_STAB_AXES_MAX * HG_STAB_AXIS_SYSTEMS)

/* Which of an axis's parameters a test system is named after. */
enum {
    HG_STAB_C_VISC = 0, HG_STAB_K_STOP, HG_STAB_C_STOP, HG_STAB_R_WINDING, HG_STAB_KP_VEL,
    HG_STAB_KI_VEL, HG_STAB_K_AXIAL, HG_STAB_C_AXIAL, HG_STAB_BACKLASH, HG_STAB_NAMES
};

/* The impact test's bound: the train's energy at most this many times the
 * drive's work (the default trains with any backlash hold 1.00 to 1.01 at
 * their linear bound; the steps that chattered and diverged, 3 to 1e7). */
#define HG_STAB_IMPACT_ENERGY 1.2
/* The impact test's forces on the rotor, shares of the drive's largest (a
 * smaller force crosses the free play slower and meets the flank with less
 * work done: the test is stricter). */
#define HG_STAB_IMPACT_FORCES 0.05, 0.2, 1.0

/* One axis (SI, in its load coordinate: m or rad, N or N m). */
typedef struct {
    double m_rigid;         /* inertia of load and rotor moving as one (a rigid train) */
    double m_load;          /* the least inertia of the load alone (behind a flexible train) */
    double m_rotor;         /* the rotor's reflected inertia, j_rotor (2 pi / lead)^2 */
    double c_visc;          /* viscous friction */
    double k_stop, c_stop;  /* hard stop */
    double force_per_amp;   /* kt 2 pi / lead: force per ampere, back-EMF per speed */
    double r_winding, l_winding;
    int velocity_mode;      /* 1: the amplifier closes a velocity loop (kp_vel, ki_vel) */
    double kp_vel, ki_vel;
    double k_axial, c_axial; /* the drive train; k_axial 0: rigid */
    double backlash;        /* its total lost motion (0: none; the impact test with it) */
    double f_max;           /* the drive's largest force, i_max force_per_amp (the impact test's) */
    const char *name[HG_STAB_NAMES]; /* spec names of the parameters above, by HG_STAB_* */
} hg_stability_axis;

/* What the check found. */
typedef struct {
    unsigned substeps;      /* steps per period needed (>= the requested), 0: none up to the maximum */
    const char *param;      /* spec name of the parameter that limits the step, 0 if none does */
    double dt_max_s;        /* with it, the longest stable step (s); 0 if none limits */
} hg_stability;

/* The substeps (from substeps_min up to substeps_max) the scheme needs to
 * integrate the n axes ax[] stably at period_s; writes *out (the bound's
 * parameter: of the systems unstable at the last count, in the axes'
 * order, the one with the shortest stable step, or the first within 5%
 * of it; the backlash when the impact test alone raised the count, with
 * the step of the first count that passes it, 0 when none up to four
 * times substeps_max does). 0, or HG_ERR_STIFF when substeps_max are not
 * enough. */
int hg_stability_check_axes(const hg_stability_axis *ax, int n, hg_integrator scheme, double period_s,
                            unsigned substeps_min, unsigned substeps_max, hg_stability *out);

#endif
