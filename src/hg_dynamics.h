/* hg_dynamics.h - forward dynamics of the whole Hexaglide (head, six bars,
 * six carriages, six drives), one integration step per call, after
 * Ros et al., Multibody Dynamics 2011 (shared/paper).
 *
 * MuJoCo-style split: hg_model is constant after hg_model_init (parameters
 * and the parameter-only subexpressions of the generated code); hg_data is
 * the mutable state and workspace. Both are plain structs without pointers,
 * so the HAL driver can place them in hal_malloc'd memory.
 *
 * Units: SI and radians. z = carriage heights relative to HOME (m, up),
 * pose = X Y Z (m) A B C (rad) of the head reference point, as in
 * hg_kinematics.h. Volts are the DAC commands of joints 0..5.
 *
 * Pure C and libm: no LinuxCNC dependency; hg_step has no malloc, no stdio
 * and bounded loops, and never leaves a non-finite number in hg_data. */
#ifndef HG_DYNAMICS_H
#define HG_DYNAMICS_H

#include "hg_params.h"
#include "hg_kinematics.h"

/* The parametrizations of the paper's section 7, plus the fused one. */
typedef enum {
    HG_MODEL_STANDARD = 0,          /* q = [z, 12 bar angles, c], z independent */
    HG_MODEL_REDUCED_JOINTS = 1,    /* bars lumped, q = [z, c], z independent */
    HG_MODEL_REDUCED_CARTESIAN = 2, /* bars lumped, q = [z, c], c independent */
    HG_MODEL_FUSED_CARTESIAN = 3,   /* reduced Cartesian, whole step generated as one function */
    HG_MODEL_COUNT = 4
} hg_model_kind;

/* Name used on the command line and in HAL ("standard", "reduced-joints",
 * "reduced-cartesian", "fused-cartesian"); 0 for an invalid kind. */
const char *hg_model_name(hg_model_kind kind);

/* Kind for a name, or -1 when the name is unknown. */
int hg_model_from_name(const char *name);

/* Time integration scheme of one step (hg_integrate.[ch] holds the schemes). */
typedef enum {
    HG_INTEGRATOR_IMPROVED_EULER = 0, /* the paper's: q += qd dt + qdd dt^2/2, qd += qdd dt (default) */
    HG_INTEGRATOR_HEUN = 1,           /* second order (RK2), then the same stabilization */
    HG_INTEGRATOR_RK4 = 2,            /* classical fourth order, then the same stabilization */
    HG_INTEGRATOR_COUNT = 3
} hg_integrator;

/* Name of a scheme ("improved-euler", "heun", "rk4"); 0 for an invalid one. */
const char *hg_integrator_name(hg_integrator which);

/* Scheme for a name, or -1 when the name is unknown. */
int hg_integrator_from_name(const char *name);

#define HG_MAX_CONSTS 256   /* room for hoisted parameter-only subexpressions */
#define HG_MAX_LUMPED_CONSTS 64 /* room for the lumped-bar model's */

typedef struct {
    hg_params p;                 /* the parameter set this model was built from */
    hg_model_kind kind;
    hg_integrator integrator;    /* scheme of hg_step (hg_model_init: improved Euler) */
    double force_per_volt_n;     /* ka kt 2 pi / lead */
    double force_max_n;          /* i_max kt 2 pi / lead */
    double rotor_mass_kg;        /* j_rotor (2 pi / lead)^2, inertia without weight */
    double potential_home_j;     /* gravity potential at HOME (energies are relative to it) */
    double k[HG_MAX_CONSTS];     /* generated init: parameter-only subexpressions */
    double k_lumped[HG_MAX_LUMPED_CONSTS]; /* the lumped-bar model's (broken-bar step), any kind */
    double potential_lumped_home_j; /* lumped-bar gravity potential at HOME */
} hg_model;

#define HG_DT_MAX_S 0.01              /* hg_step refuses longer steps (HG_ERR_BAD_DT) */
#define HG_STAB_MAX_RESIDUAL_M 1e-6   /* bar-length error after stabilization that counts as diverged */
#define HG_BARS_ALL 0x3fu             /* broken_bars: bit k is bar k (joint k) */
#define HG_BROKEN_HEAD_Z_MIN_M (-0.6) /* broken machine: head Z below this is out of volume */
#define HG_BROKEN_REACH_M 1.0         /* broken machine: |X|, |Y| or a |z_k| above this is out of volume */
#define HG_BROKEN_ROT_MAX_RAD 0.3490658503988659 /* broken machine: |A|, |B| or |C| above 20 deg is out of volume */

typedef struct {
    double t_s;                  /* simulated time since reset */
    double z_m[6];               /* carriage heights relative to HOME */
    double zd_mps[6];            /* carriage velocities */
    double zdd_mps2[6];          /* carriage accelerations of the last step */
    double pose[6];              /* head pose: X Y Z (m) A B C (rad) */
    double posed[6];             /* its time derivative */
    double bar_rad[12];          /* bar angles (standard model only) */
    double bar_radps[12];        /* their rates (standard model only) */
    double current_a[6];         /* motor currents after the amplifier clamp */
    double force_n[6];           /* net non-inertial force on each carriage (drive+friction+stop) */
    double residual_m;           /* max bar-length error after the last stabilization */
    int last_error;              /* code of the last failed step, 0 if none */
    unsigned broken_bars;        /* fault injection: bit k set = bar k removed (HG_BARS_ALL);
                                    hg_data_reset clears it (all bars intact) */
    /* internal cache of the Reduced Cartesian steps: sin/cos of the head
     * angles of pose[3..5] (the stabilization's are the next step's) */
    double trig_key_rad[3];      /* the angles trig_sc belongs to */
    double trig_sc[6];           /* sin A, cos A, sin B, cos B, sin C, cos C */
    int trig_valid;              /* 0: recompute */
} hg_data;

/* Check p and build the model: 0, or HG_ERR_BAD_PARAM with *bad_field and
 * *why naming the cause (static strings), or another negative code. */
int hg_model_init(hg_model *m, const hg_params *p, hg_model_kind kind,
                  const char **bad_field, const char **why);

/* Use scheme `which` from now on: 0, or HG_ERR_BAD_PARAM (m unchanged)
 * when which is not in [0, HG_INTEGRATOR_COUNT). */
int hg_model_set_integrator(hg_model *m, int which);

/* Put the machine at HOME at rest (z = 0, z' = 0), solving the dependent
 * coordinates and velocities with full Newton-Raphson. 0 or a negative code. */
int hg_data_reset(const hg_model *m, hg_data *d);

/* Integrate one step of dt_s seconds with the given DAC volts (clamped to
 * +-10 V; non-finite volts count as 0). 0, or a negative code (BAD_DT,
 * STATE_NONFINITE, STABILIZATION, SINGULAR_MASS, ...) in which case d is
 * left exactly as it was before the call except last_error.
 * With any bit of d->broken_bars set, every kind takes the broken-bar step
 * (lumped bars in q = [z, c], only the intact bars' constraints, see
 * hg_step_broken in hg_step.h; standard: bar angles follow the geometry,
 * their rates are 0); it also fails with OUT_OF_VOLUME (head Z below
 * HG_BROKEN_HEAD_Z_MIN_M, |X|, |Y| or a |z_k| above HG_BROKEN_REACH_M, a
 * head angle beyond HG_BROKEN_ROT_MAX_RAD: the model has no contacts, and a
 * head swinging further would strike bars that it passes through here),
 * SINGULAR_JACOBIAN or DIVERGED.
 * Clearing bits again needs hg_data_reset (the broken bar's length is
 * not restored). */
int hg_step(const hg_model *m, hg_data *d, const double volts[6], double dt_s);

/* Kinetic energy (J, rotor included) and potential energy (J, gravity,
 * zero at HOME) of the state in d (of the lumped-bar model when a bar is
 * broken). */
void hg_energy(const hg_model *m, const hg_data *d, double *kinetic_j, double *potential_j);

#endif
