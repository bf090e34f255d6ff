/* hg_kinematics.h - Hexaglide geometry, inverse and forward kinematics.
 *
 * Conventions (docs/model.md): SI units and radians inside.
 *   joints z[6]  = z11 z12 z21 z22 z31 z32, carriage heights relative to
 *                  HOME, metres, positive up (LinuxCNC joints 0..5).
 *   pose c[6]    = X Y Z (m) of the head reference point Op and
 *                  A B C (rad), R = Rz(C) Ry(B) Rx(A).
 *   bar k = 2*(i-1) + (j-1) for post i = 1..3, guide j = 1..2.
 *   B_k = Rz(alpha_i) (lb, s_j e, 0) + (0, 0, h + z_k)   carriage joint
 *   A_k = P + R Rz(alpha_i) (lp, s_j e, 0)               head joint
 *   Phi_k = |B_k - A_k|^2 - l^2 = 0                       bar constraint
 *
 * Pure C and libm: no LinuxCNC dependency, no malloc, no stdio, bounded
 * loops. Shared by hexaglidekins, the virtual driver and build/hexaglide. */
#ifndef HG_KINEMATICS_H
#define HG_KINEMATICS_H

#include "hg_geometry.h"

/* The points of a geometry that do not move: home height, guide and head
 * joint points (hg_frame_of). */
typedef struct {
    double h;                  /* hg_home_height */
    double guide[6][3];        /* hg_guide_point of each bar */
    double head[6][3];         /* hg_head_point of each bar */
} hg_frame;

#define HG_NBARS 6
/* positions (pose X Y Z, joints) beyond this many bar lengths are refused
 * as unreachable: far outside any machine, and where rounding would
 * swallow the bar length */
#define HG_MAX_ABS_POSITION_BARS 100.0
/* poses with |B| above this are refused (3-2-1 Euler singularity at 90 deg) */
#define HG_MAX_ABS_B_RAD 1.4835298641951802 /* 85 degrees */

/* Newton-Raphson settings and report for the forward kinematics. */
typedef struct {
    int max_iterations;        /* hard bound on iterations, HG_FK_ITERATION_MIN..HG_FK_ITERATION_CAP */
    double tolerance_m;        /* stop when the Newton step (m, angles as arc length l*rad)
                                  is below this; the residual is then far below it */
} hg_fk_options;

/* Default FK options: 30 iterations, 1e-12 m. */
void hg_fk_options_default(hg_fk_options *o);

#define HG_FK_ITERATION_MIN 3      /* max_iterations at least this: the solve stops when its step is below
                                      the tolerance; from the last servo period's pose the first step is the
                                      period's motion, the second about its square (a few nm at 1 m bars), the
                                      third below 1e-12 m: with 1 or 2 a moving machine never converges and
                                      LinuxCNC's position stays at the last solved pose */
#define HG_FK_ITERATION_CAP 100    /* max_iterations at most this */
#define HG_FK_TOLERANCE_MIN_M 1e-13 /* tolerance_m at least this: double precision resolves a Newton step of
                                      about 1e-15 m at 1 m bars (the step stalls there and the solve
                                      fails); 100 times that (tests/unit/test_kinematics) */
#define HG_FK_TOLERANCE_MAX_M 1e-6 /* tolerance_m at most this: a coarser Newton step would leave the
                                      pose off by more than the machine's 1 um encoder count */

/* 0 when o can be used, else HG_ERR_BAD_PARAM with *field ("max_iterations"
 * or "tolerance", either pointer may be 0) and *why (static strings). */
int hg_fk_options_check(const hg_fk_options *o, const char **field, const char **why);

/* What a kinematics module keeps between forward calls (hexaglidekins):
 * the settings in force, the last pair refused (said once), the run
 * of failed calls (its start said once, its end once) and the last pose
 * solved (what the module answers while its calls fail). */
typedef struct {
    hg_fk_options in_force;    /* the last valid settings */
    int refused_iterations;    /* the last refused pair, as given */
    double refused_tolerance_m;
    int failing;               /* 1: the last forward call failed */
    unsigned said_codes;       /* bit -code: a failure code said in the run of failures */
    unsigned fail_count;       /* failed calls since init (wraps as a HAL u32) */
    int have_last;             /* 1: last_pose holds an answer */
    double last_pose[6];       /* the last pose solved (hg_fk_session_solve, hg_guard.h) */
} hg_fk_session;

/* What a session asks its caller to say. */
enum {
    HG_FK_SAY_NOTHING = 0,
    HG_FK_SAY_REFUSED = 1,     /* a new invalid pair: refused, in_force kept */
    HG_FK_SAY_FAILING = 2,     /* the first failure of a run: the pose shown stays */
    HG_FK_SAY_SOLVES_AGAIN = 3, /* the first success after a run of failures */
    HG_FK_SAY_JUMP = 4,        /* a new tool offset moved Op at once (hg_tool_offset_take) */
    HG_FK_SAY_FAILS_OTHERWISE = 5 /* a run of failures meets a code not said in it yet */
};

/* A session with the default settings in force, nothing refused or failed. */
void hg_fk_session_init(hg_fk_session *s);

/* Take the settings given (iterations, tolerance in m) into s->in_force
 * if hg_fk_options_check accepts them (the other fields of in_force stay);
 * else keep in_force and return HG_FK_SAY_REFUSED, with *field and *why
 * from the check, when this pair differs from the one given before
 * (bitwise: a NaN equals itself), HG_FK_SAY_NOTHING while it stays. */
int hg_fk_session_settings(hg_fk_session *s, int max_iterations, double tolerance_m, const char **field,
                           const char **why);

/* Note a forward call's result rc (0 or an hg_error code): counts a
 * failure; HG_FK_SAY_FAILING at the first of a run,
 * HG_FK_SAY_FAILS_OTHERWISE at the first call of the run failing with a code
 * not said in it yet (a NaN joint after a diverged solve; at most once per
 * code, so a run never floods the log), HG_FK_SAY_SOLVES_AGAIN at the first
 * success after one, else HG_FK_SAY_NOTHING. */
int hg_fk_session_result(hg_fk_session *s, int rc);

/* Machine units. LinuxCNC exchanges X Y Z and the joints (carriage
 * heights) with a kinematics module in the machine's linear units
 * ([TRAJ]LINEAR_UNITS: mm, or inch); the geometry stays in mm (the
 * machine's own facts, [HEXAGLIDE]) and A B C in degrees. mm_per_unit is
 * the mm in one machine unit: 1 for mm, 25.4 for inch. With 1 the
 * conversions below round exactly as a plain mm <-> m conversion does
 * (x * 1 is x): an mm machine's numbers are unchanged. */
#define HG_MM_PER_UNIT_DEFAULT 1.0
#define HG_MM_PER_UNIT_MIN 0.001   /* a micrometre per unit */
#define HG_MM_PER_UNIT_MAX 1000.0  /* a metre per unit */

/* HG_OK when mm_per_unit is finite and within [HG_MM_PER_UNIT_MIN,
 * HG_MM_PER_UNIT_MAX], else HG_ERR_BAD_PARAM (0, negative, NaN, inf, absurd). */
int hg_mm_per_unit_check(double mm_per_unit);

/* The machine-units setting of a kinematics module: the value in force
 * and the last one refused (said once, as hg_fk_session's settings). */
typedef struct {
    double in_force;           /* the last valid mm_per_unit */
    double refused;            /* the last value given, as given (bitwise) */
} hg_units_setting;

/* A value said once when refused: HG_FK_SAY_REFUSED when not accepted and
 * value differs (bitwise: a NaN equals itself) from *last, the value given
 * before; HG_FK_SAY_NOTHING otherwise. *last becomes value. */
int hg_say_refused_once(double *last, double value, int accepted);

/* in_force HG_MM_PER_UNIT_DEFAULT, nothing refused. */
void hg_units_init(hg_units_setting *u);

/* Take mm_per_unit into u->in_force if hg_mm_per_unit_check accepts it;
 * else keep in_force and return HG_FK_SAY_REFUSED when this value differs
 * from the one given before (bitwise: a NaN equals itself), else
 * HG_FK_SAY_NOTHING. */
int hg_units_take(hg_units_setting *u, double mm_per_unit);

/* Machine pose (X Y Z in machine units, A B C deg) <-> core pose (m, rad). */
void hg_pose_from_machine(const double user[6], double mm_per_unit, double pose[6]);
void hg_pose_to_machine(const double pose[6], double mm_per_unit, double user[6]);
/* Machine joints (carriage heights in machine units) <-> core joints (m). */
void hg_joints_from_machine(const double joints[6], double mm_per_unit, double z[6]);
void hg_joints_to_machine(const double z[6], double mm_per_unit, double joints[6]);

/* LinuxCNC's switchable kinematics (switchkins.h, motion.switchkins-type):
 * hexaglidekins has the Hexaglide's kinematics (type 0, the default) and
 * identity (type 1: world X Y Z A B C are joints 0..5 as they are, to move
 * one carriage at a time in world mode, as genhexkins' type 1). Type 2,
 * a user template in LinuxCNC's switchkins modules, it has not. */
enum { HG_KINS_HEXAGLIDE = 0, HG_KINS_IDENTITY = 1 };

/* The type in force and how many of the next Hexaglide forward calls
 * must start from the pose tracked while another type was in force:
 * motion's guesses in the period of a switch are that type's world, not a
 * Hexaglide pose, for both its streams (the commanded joints at the switch,
 * then the feedback joints in the same period). */
#define HG_KINS_RESTART_CALLS 2
typedef struct {
    int type;                  /* HG_KINS_HEXAGLIDE or HG_KINS_IDENTITY */
    int restart;               /* > 0: the next Hexaglide forward calls start from the tracked pose */
} hg_kins_switch;

/* 1 when a kinematics module's coordinates parameter suits the Hexaglide:
 * left out (0 or "") or XYZABC in any case, its joints' order; else 0. */
int hg_kins_coordinates_ok(const char *coordinates);

/* Identity kinematics (HG_KINS_IDENTITY) either way: out = in (joints
 * 0..5 <-> X Y Z A B C, machine units as given), HG_OK; or
 * HG_ERR_NONFINITE_INPUT, out untouched, when one of in is not finite. */
int hg_identity_kinematics(const double in[6], double out[6]);

/* 1 when this Hexaglide forward call starts from the tracked pose (one of
 * the restart calls, counted down), else 0. */
int hg_kins_switch_restart(hg_kins_switch *s);

/* Type HG_KINS_HEXAGLIDE, no restart. */
void hg_kins_switch_init(hg_kins_switch *s);

/* Switch to type: HG_OK (restart HG_KINS_RESTART_CALLS when the
 * Hexaglide's kinematics come back from identity), or HG_ERR_BAD_PARAM for a
 * type hexaglidekins does not have, the type in force kept. */
int hg_kins_switch_to(hg_kins_switch *s, int type);

/* Base point of guide k at height 0: Rz(alpha_i)(lb, s_j e, 0). */
void hg_guide_point(const hg_geometry *g, int k, double out[3]);

/* Head joint k in head coordinates: Rz(alpha_i)(lp, s_j e, 0). */
void hg_head_point(const hg_geometry *g, int k, double out[3]);

/* sc = sin A, cos A, sin B, cos B, sin C, cos C of pose c = X Y Z A B C. */
void hg_head_trig(const double *c, double sc[6]);

/* Rotation matrix R = Rz(c) Ry(b) Rx(a), row-major R[3*row+col]. */
void hg_rotation(double a, double b, double c, double R[9]);

/* The same R from the angles' sin/cos sc (hg_head_trig's order): the same
 * bits as hg_rotation of those angles. */
void hg_rotation_sc(const double sc[6], double R[9]);

/* World positions of the carriage joints B[k] and head joints A[k]. */
void hg_joint_points(const hg_geometry *g, const double z[6], const double pose[6],
                     double B[6][3], double A[6][3]);

/* Fill f for g. */
void hg_frame_of(const hg_geometry *g, hg_frame *f);

/* hg_joint_points with the frame f and the pose's rotation R
 * (hg_rotation_sc) given: the same bits. */
void hg_joint_points_rot(const hg_frame *f, const double R[9], const double z[6],
                         const double pose[6], double B[6][3], double A[6][3]);

/* The tool tip of pose (tool_d below Op along the head's -z axis), world frame (m). */
void hg_tool_tip(const double pose[6], double tool_d_m, double tip[3]);

/* RTCP: the tool length offset of LinuxCNC's G43 (motion.tooloffset.z into
 * hexaglidekins.tool-offset, docs/linuxcnc.md). Motion hands the
 * kinematics X Y Z = the programmed tool tip + d along world Z. A tool d
 * long points along the head's -z axis (as hg_tool_tip), so its tip stays
 * at the programmed point whatever the tilt when
 *     Op = P + d (R z - z)        (z = (0 0 1), R the head's rotation);
 * d 0 or an untilted head: Op is P to the bit (up to the sign of a zero).
 * The angles pass unchanged. */
/* HG_OK when tool_offset_m is finite and within HG_MAX_ABS_POSITION_BARS
 * bar lengths, else HG_ERR_BAD_PARAM. */
int hg_tool_offset_check(const hg_geometry *g, double tool_offset_m);
/* The head pose op (Op) of a commanded pose whose X Y Z carry the offset. */
void hg_pose_offset_to_op(const double commanded[6], double tool_offset_m, double op[6]);
/* The commanded pose of the head pose op: the inverse of the above. */
void hg_pose_op_to_offset(const double op[6], double tool_offset_m, double commanded[6]);
/* How far Op moves at once when the offset changes from from_m to to_m at
 * the commanded pose (m): |to - from| |R z - z|, 0 with the head level. */
double hg_tool_offset_jump(const double commanded[6], double from_m, double to_m);
/* A jump above this (an encoder count) is one the joints cannot follow
 * within a servo period: hg_tool_offset_take says so. */
#define HG_TOOL_OFFSET_JUMP_SAY_M 1e-6

/* The tool offset of a kinematics module (hexaglidekins.tool-offset): the
 * value in force, the last one given (a refusal said once, as
 * hg_units_setting's) and the pose of the last inverse call, where a new
 * offset moves Op: motion asks the inverse of its commanded pose as the
 * last call of every period and sees a new offset in a later one, whose
 * first call may be the inverse of a queued move's end point. */
typedef struct {
    double in_force_m;         /* the last valid offset (m) */
    double given_m;            /* the last one given, as given (bitwise) */
    int refusing;              /* 1: the last one given was refused */
    double jump_m;             /* how far Op moved at the last change (hg_tool_offset_jump) */
    double last_inverse[6];    /* the commanded pose of the last inverse call (m, rad) */
} hg_tool_offset_setting;

/* 0 in force, nothing refused, the last inverse at HOME (level). */
void hg_tool_offset_init(hg_tool_offset_setting *t);

/* Take tool_offset_m into t->in_force_m if hg_tool_offset_check accepts it;
 * else keep in_force_m and set refusing. HG_FK_SAY_REFUSED for a new
 * refused value (bitwise: a NaN equals itself), HG_FK_SAY_JUMP when a new
 * valid value moves Op at the last inverse call's pose by more than
 * HG_TOOL_OFFSET_JUMP_SAY_M (jump_m: how far) and applied is 1, else
 * HG_FK_SAY_NOTHING. applied 0: the kinematics in force apply no offset
 * (identity, hg_identity_kinematics), so a new one moves nothing (jump_m 0). */
int hg_tool_offset_take(hg_tool_offset_setting *t, const hg_geometry *g, double tool_offset_m, int applied);

/* Bar constraints Phi_k = |B_k - A_k|^2 - l^2 (m^2). */
void hg_constraints(const hg_geometry *g, const double z[6], const double pose[6],
                    double phi[6]);

/* Largest bar-length error | |B_k - A_k| - l | over the six bars (metres),
 * from Phi without cancellation: |B-A| - l = Phi / (|B-A| + l). NaN-safe:
 * a non-finite error is returned as such. */
double hg_bar_length_error(const hg_geometry *g, const double z[6], const double pose[6]);

/* Analytic Jacobian dPhi/dpose (6x6 row-major, phi row k, pose column) and,
 * if dphi_dz is not 0, the diagonal dPhi_k/dz_k. */
void hg_constraint_jacobian(const hg_geometry *g, const double z[6], const double pose[6],
                            double jac_pose[36], double dphi_dz[6]);

/* Closed-form inverse kinematics: pose -> joints. 0, or
 * HG_ERR_NONFINITE_INPUT, HG_ERR_EULER_SINGULAR, HG_ERR_UNREACHABLE (also for
 * |X|, |Y|, |Z| beyond HG_MAX_ABS_POSITION_BARS l) (joints untouched on failure). */
int hg_inverse_kinematics(const hg_geometry *g, const double pose[6], double z[6]);

/* Forward kinematics by Newton-Raphson on the six bar equations with the
 * analytic Jacobian, starting from pose (the guess) and overwriting it with
 * the answer on success only; *iterations and *residual_m (either may be
 * 0) are the iterations used and the largest bar-length error at the last
 * iterate. An answer on the other branch, a carriage below its head joint,
 * is refused (HG_ERR_WRONG_BRANCH); the mechanical limits are not checked:
 * hg_forward_kinematics (hg_guard.h) is the solve the machine answers
 * with, this one a measure near a pose it holds (the commanded tool of a
 * tool-path error). 0, or HG_ERR_BAD_PARAM (opt refused by
 * hg_fk_options_check), HG_ERR_NONFINITE_INPUT, HG_ERR_UNREACHABLE (a joint
 * beyond HG_MAX_ABS_POSITION_BARS l), HG_ERR_NO_CONVERGENCE,
 * HG_ERR_SINGULAR_JACOBIAN, HG_ERR_DIVERGED, HG_ERR_EULER_SINGULAR. */
int hg_forward_solve(const hg_geometry *g, const double z[6], double pose[6], const hg_fk_options *opt,
                     int *iterations, double *residual_m);

#endif
