/* hg_mujoco_model.h - the Hexaglide as a MuJoCo (2.2.2) model, written as
 * MJCF text from an hg_params so the machine is described in one place.
 *
 * This is the project's independent engine: a second formulation of the
 * same machine (maximal coordinates, closed loops as <connect> equality
 * constraints, MuJoCo's own solver and integrator) used by make bench as
 * the speed peer and by tests/engine as an accuracy referee.
 *
 * The MJCF follows docs/model.md directly: one static "post"
 * frame per post rotated by alpha_i about z, in which each carriage sits at
 * (lb, s_j e, h) on a vertical slide and its bar hangs in the post's x-z
 * plane towards (lp, s_j e, 0). Host-side code (malloc, stdio): not for
 * src/, which is pure project math.
 *
 * The Makefile builds one .c per bench program, so bench_mujoco*.c include
 * hg_mujoco_model.c directly. */
#ifndef HG_MUJOCO_MODEL_H
#define HG_MUJOCO_MODEL_H

#include <stddef.h>
#include <mujoco/mujoco.h>
#include "hg_params.h"

/* Engine settings that are not machine parameters. */
typedef struct {
    double timestep_s;        /* MuJoCo timestep (the servo period) */
    const char *integrator;   /* "RK4", "Euler" or "implicit" */
    int iterations;           /* Newton solver iteration bound */
    double tolerance;         /* solver tolerance (relative cost improvement) */
    double eq_timeconst_s;    /* connect solref[0]: constraint time constant */
    double eq_impedance;      /* connect solimp[0] = solimp[1]: 1 is a hard constraint */
                              /* (the same two for the slides' frictionloss: solreffriction,
                                 solimpfriction) */
    double bar_spin_kgm2;     /* bar inertia about its own axis (neglected by the project) */
    int hard_stops;           /* 1: slide range [stop_min, stop_max] limited="true" */
} hgmj_options;

/* Indices into mjModel/mjData of the parts the project talks about. */
typedef struct {
    int slide_qpos[6];        /* qpos address of carriage z_k (k = 2(i-1)+(j-1)) */
    int slide_dof[6];         /* qvel address of the same joint */
    int head_qpos;            /* qpos address of the head free joint (x y z qw qx qy qz) */
    int head_dof;             /* qvel address of the head free joint */
    int bar_end_site[6];      /* site at the lower end of bar k (moves with the bar) */
    int head_joint_site[6];   /* site at A_k on the head (moves with the head) */
} hgmj_index;

/* The settings used by make bench and tests/engine (see the .c for why). */
void hgmj_options_default(hgmj_options *o);

/* The default machine as the peer models it: no Coulomb or static friction
 * (the closed-form facts of tests/engine are frictionless) and the
 * amplifier in torque mode as an ideal current source (a 1 nH winding on a
 * 1 MV bus: the current reaches its command at the start of each step, so
 * neither back-EMF nor winding lag acts). Viscous friction stays. */
void hgmj_peer_params(hg_params *p);

/* The same with the default Coulomb friction f_coulomb on every carriage,
 * the law both engines have: MuJoCo's dry friction (frictionloss) on each
 * slide, the project's stick-slip law with f_static = f_coulomb (no
 * breakaway above the sliding force, so no Stribeck curve either). What
 * bench_mujoco times. */
void hgmj_peer_params_friction(hg_params *p);

/* 1 when p is such a parameter set (hgmj_write_mjcf refuses any other):
 * the ideal current source, f_static = f_coulomb (0 or not), rigid trains. */
int hgmj_is_peer(const hg_params *p, const hgmj_options *o);

/* Write the MJCF of the machine p into buf (size n): the text length, or -1
 * when it does not fit, -2 when the head height at HOME is not positive or
 * a mass property is not positive, -3 when p is not a peer parameter set
 * (hgmj_is_peer). */
int hgmj_write_mjcf(const hg_params *p, const hgmj_options *o, char *buf, size_t n);

/* Write the MJCF and compile it with mj_loadXML (from memory, through a
 * VFS): the model, or 0 with a message in err. */
mjModel *hgmj_load(const hg_params *p, const hgmj_options *o, char *err, int err_sz);

/* Look up joints and sites by name: 0, or -1 if the model lacks one. */
int hgmj_index_build(const mjModel *m, hgmj_index *ix);

/* Largest distance (m) between a bar's lower end and its head joint A_k,
 * from the site positions: call mj_kinematics (or mj_forward) on the state
 * first (after mj_step with RK4 they belong to an intermediate stage). */
double hgmj_connect_violation(const mjData *d, const hgmj_index *ix);

/* Carriage heights relative to HOME (m). */
void hgmj_joints(const mjData *d, const hgmj_index *ix, double z[6]);

/* Head pose X Y Z (m) A B C (rad), R = Rz(C) Ry(B) Rx(A), from the free
 * joint's position and quaternion. */
void hgmj_head_pose(const mjData *d, const hgmj_index *ix, double pose[6]);

/* Drive force per volt (N/V): ka kt 2 pi / lead, the motor gear. */
double hgmj_force_per_volt(const hg_params *p);

#endif
