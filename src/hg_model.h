/* hg_model.h - the dynamics' data types, MuJoCo-style: hg_model is
 * constant after hg_model_init (parameters and the parameter-only
 * subexpressions of the generated code); hg_data is the mutable state and
 * its scratch. Both are plain structs without pointers, so the HAL driver
 * can place them in hal_malloc'd memory. Functions: hg_dynamics.h.
 *
 * Units: SI and radians. z = carriage heights relative to HOME (m, up),
 * pose = X Y Z (m) A B C (rad) of the head reference point, as in
 * hg_kinematics.h. */
#ifndef HG_MODEL_H
#define HG_MODEL_H

#include <stddef.h>
#include "hg_params.h"
#include "hg_guard.h"
#include "hg_scheme.h"
#include "hg_drive.h"
#include "hg_friction.h"
#include "hg_drivetrain.h"

/* The parametrizations of the paper's section 7, plus the fused one. */
typedef enum {
    HG_MODEL_STANDARD = 0,          /* q = [z, 12 bar angles, c], z independent */
    HG_MODEL_REDUCED_JOINTS = 1,    /* bars lumped, q = [z, c], z independent */
    HG_MODEL_REDUCED_CARTESIAN = 2, /* bars lumped, q = [z, c], c independent */
    HG_MODEL_FUSED_CARTESIAN = 3,   /* reduced Cartesian, whole step generated as one function */
    HG_MODEL_COUNT = 4
} hg_model_kind;


#define HG_MAX_CONSTS 256   /* room for hoisted parameter-only subexpressions */
#define HG_MAX_LUMPED_CONSTS 64 /* room for the lumped-bar model's */

typedef struct {
    hg_params p;                 /* the parameter set this model was built from */
    hg_model_kind kind;
    hg_integrator integrator;    /* scheme of hg_step (hg_model_init: Heun) */
    hg_drive_channel drive[6];   /* the six drives, alike (hg_drive_init of p's drive fields):
                                    force per ampere kt 2 pi / lead, winding time constant */
    double force_per_volt_n;     /* ka kt 2 pi / lead (N/V): torque mode, every drive alike */
    hg_friction_channel fric[6]; /* each carriage's sliding and static friction (p's, alike) */
    double rotor_mass_kg;        /* j_rotor (2 pi / lead)^2, inertia without weight */
    hg_drivetrain_channel train[6]; /* each drive train (p's k_axial, c_axial, backlash, alike) */
    int flexible;                /* 1: the trains have a spring (k_axial > 0): the rotors are bodies
                                    of their own (hg_data.zr_m) and k holds the machine without
                                    their inertia; 0: rigid, the rotors' inertia in the carriages' */
    double m_min_kg;             /* a lower bound of a carriage's effective mass: m_carriage plus
                                    the rotor's when rigid, m_carriage alone when flexible */
    double potential_home_j;     /* gravity potential at HOME (energies are relative to it) */
    hg_guard_geo guard;          /* the guard's constants of p.geo (hg_guard_prepare) */
    double k[HG_MAX_CONSTS];     /* generated init: parameter-only subexpressions */
    double k_lumped[HG_MAX_LUMPED_CONSTS]; /* the lumped-bar model's (broken-bar step), any kind */
    double potential_lumped_home_j; /* lumped-bar gravity potential at HOME */
} hg_model;

#define HG_DT_MAX_S 0.01              /* hg_step refuses longer steps (HG_ERR_BAD_DT) */
#define HG_STAB_MAX_RESIDUAL_M 1e-6   /* bar-length error after stabilization that counts as diverged */
#define HG_BARS_ALL 0x3fu             /* broken_bars: bit k is bar k (joint k) */

/* The reduced mass data of a step's start, saved by the parametrization's
 * first acceleration evaluation of the step when hg_integrate asks for it
 * (friction, hg_friction.h, needs the carriages' response to impulses):
 * kind 1, the reduced mass matrix in the independent coordinates (LDL^T,
 * hg_spd6) and the map T from independent to carriage velocities; kind 2
 * (broken bars), the factored augmented (KKT) matrix. */
#define HG_KKT_MAX 18
typedef struct {
    int want;                    /* set by hg_integrate: the next accel saves its data */
    int kind;                    /* 0 nothing saved, 1 reduced mass matrix + T, 2 KKT */
    double ldl[36], inv_d[6];    /* kind 1: factored reduced mass matrix */
    double T[36];                /* kind 1: carriage velocities = T x independent velocities */
    int t_identity;              /* kind 1: T is the identity (z independent) */
    double kkt[HG_KKT_MAX * HG_KKT_MAX]; /* kind 2: LU of [M J^T; J 0] */
    int piv[HG_KKT_MAX], nkkt;   /* kind 2: its pivots and size */
} hg_mass_snapshot;

/* Preallocated scratch for one hg_step: the integrator's stage vectors
 * and the parametrization's 6x6 (and 18x7) temporaries, so that no
 * realtime stack frame exceeds 2560 bytes (kernel/RTAI modules). Each
 * user lays its own struct over these arrays (sizes checked at compile
 * time). */
#define HG_WORK_STAGE 160
#define HG_WORK_STEP 800    /* the largest user: the Standard step, 778 */
typedef struct {
    double stage[HG_WORK_STAGE]; /* hg_integrate's stage states and sums */
    double step[HG_WORK_STEP];   /* the parametrization's accelerations/stabilization */
    double sc1[6];               /* Reduced Cartesian: sin/cos of the stabilized head angles */
    double sc1_key[3];           /* ... the angles sc1 holds when sc1_valid (set by the hold, */
    int sc1_valid;               /*     whose last angles the stabilization keeps) */
    hg_mass_snapshot mass;       /* the step start's mass data (friction) */
    double fric_est_n[6];        /* friction hg_step expects and holds in the stages (N) */
    double fric_impulse[6];      /* friction impulses of the step (N s), committed by hg_step */
    unsigned fric_stuck;         /* carriages stuck at the step's end */
    double motor_n[6];           /* flexible trains: the motors' force over the step (held) */
    double train_n[6];           /* ... the trains' force at the step's start (hg_step: in fz0) */
    double rotor1_m[6], rotor1_mps[6]; /* ... the rotors at the step's end, committed by hg_step */
    /* caches that outlive the call: each holds a self-contained fact (valid
     * in any copy of the hg_data, whatever its state), emptied by hg_data_reset */
    hg_guard_memo guard;         /* the bar-clearance bound's reference state (hg_guard.h) */
    hg_drive_memo drive;         /* the windings' exp(-dt / tau) for the last step length */
} hg_work;

typedef struct {
    double t_s;                  /* simulated time since reset */
    double z_m[6];               /* carriage heights relative to HOME */
    double zd_mps[6];            /* carriage velocities */
    double zdd_mps2[6];          /* carriage accelerations of the last step */
    double pose[6];              /* head pose: X Y Z (m) A B C (rad) */
    double posed[6];             /* its time derivative */
    double bar_rad[12];          /* bar angles (standard model only) */
    double bar_radps[12];        /* their rates (standard model only) */
    double current_a[6];         /* winding currents (A): the state of the drives (hg_drive.h) */
    double vloop_int_m[6];       /* velocity mode: each amplifier's integrated speed error (m) */
    unsigned amp_enabled;        /* bit k: amplifier k is enabled (hg_data_reset: all) */
    unsigned stuck;              /* bit k: carriage k sticks (static friction holds it exactly) */
    double fric_n[6];            /* sliding or static friction on each carriage over the last
                                    step (N, mean): what the next step's stages expect */
    double force_n[6];           /* net non-inertial force on each carriage over the last step
                                    (drive + friction + stops, mean) */
    double residual_m;           /* max bar-length error after the last stabilization */
    int last_error;              /* code of the last failed step, 0 if none */
    hg_guard_report guard;       /* the mechanical limit the last failed step crossed
                                    (JOINT_RANGE, BAR_CLEARANCE, OUT_OF_VOLUME) */
    unsigned broken_bars;        /* fault injection: bit k set = bar k removed (HG_BARS_ALL);
                                    hg_data_reset clears it (all bars intact) */
    double zr_m[6];              /* flexible trains: each motor's rotor as a carriage height (its
                                    angle times lead / 2 pi, from HOME): what the encoder reads */
    double zrd_mps[6];           /* ... its velocity (rigid trains: both unused, the rotor is z) */
    /* internal cache of the Reduced Cartesian steps: sin/cos of the head
     * angles of pose[3..5] (the stabilization's are the next step's) */
    double trig_key_rad[3];      /* the angles trig_sc belongs to */
    double trig_sc[6];           /* sin A, cos A, sin B, cos B, sin C, cos C */
    int trig_valid;              /* 0: recompute */
    /* scratch of hg_step (contents undefined between calls but for its
     * caches; last, so that a copy of the state alone is
     * memcpy(dst, src, HG_DATA_STATE_BYTES)) */
    hg_work work;
} hg_data;

/* Bytes of hg_data before the scratch: the whole state. */
#define HG_DATA_STATE_BYTES offsetof(hg_data, work)

#endif
