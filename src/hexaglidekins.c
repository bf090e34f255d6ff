/* hexaglidekins.c - LinuxCNC kinematics module for the UPNa Hexaglide.
 *
 * Thin HAL glue around src/hg_kinematics.c: joints 0..5 are the carriage
 * heights z11 z12 z21 z22 z31 z32 (machine units, relative to HOME),
 * world is X Y Z A B C of the head reference point (machine units,
 * degrees). Machine units are mm unless hexaglidekins.mm-per-unit says
 * otherwise (25.4 for [TRAJ]LINEAR_UNITS inch); the geometry is in mm.
 * Inverse: closed form, then the guard (a bar beyond its joint's range or two
 * bars touching is refused). Forward: Newton-Raphson from the previous pose,
 * guarded too.
 *
 * HAL parameters (rw): the geometry of hg_params' table (hg_param_is_geometry),
 *   by HAL name and HAL unit: hexaglidekins.l .lb .e .lp (mm), .cone-carriage
 *   .cone-head (deg), .d-bar (mm); h follows from l, lb, lp
 *   hexaglidekins.mm-per-unit (default 1): mm in one machine unit, 0.001..1000;
 *   scales X Y Z and the joints (hg_joints_from_machine ...), a refused value
 *   is said once and the last valid one kept and written back
 * HAL pins:
 *   hexaglidekins.fk-iterations      s32 out  iterations of the last forward call
 *   hexaglidekins.fk-max-iterations  s32 in   iteration bound (default 30)
 *   hexaglidekins.fk-tolerance       float in convergence tolerance, mm whatever mm-per-unit (default 1e-9)
 *   hexaglidekins.fk-residual        float out bar-length error of the last answer, mm whatever mm-per-unit
 *   hexaglidekins.fk-error           s32 out  0 or the hg_error code of the last forward call
 *   hexaglidekins.fk-fault           bit out  the last forward call failed
 *   hexaglidekins.fk-fail-count      u32 out  forward failures since load
 *   hexaglidekins.ik-error           s32 out  0 or the hg_error code of the last inverse call
 *   hexaglidekins.tool-offset        float in the tool length offset (machine units; net it to
 *                                    motion.tooloffset.z): X Y Z are the tool tip's, tool-offset
 *                                    along the head's axis below Op, at any tilt (RTCP,
 *                                    hg_pose_offset_to_op); 0 (default): Op's
 * Switchable kinematics (LinuxCNC's switchkins, motion.switchkins-type):
 *   type 0 (default) the Hexaglide's, type 1 identity (joint n is world X Y Z
 *   A B C's n-th: one carriage at a time in world mode); type 2 is refused.
 *   The Hexaglide's forward kinematics keeps solving under identity, so the
 *   head's pose stays known and the way back to type 0 starts from it.
 *   kinstype.is-0 .is-1 .is-2        bit out  the type in force (switchkins' names)
 *   skgui.x .y .z .a .b .c           float out the world pose by the Hexaglide's
 *                                    kinematics whatever the type (the tool tip with
 *                                    tool-offset, as in type 0; for a vismach GUI)
 * Module parameter coordinates: XYZABC (any case) or left out; the Hexaglide
 *   needs all six in that order. */
#include "rtapi.h"
#include "rtapi_app.h"
#include "rtapi_math.h"
#include "rtapi_string.h"
#include "hal.h"
#include "kinematics.h"

#include "hg_errors.h"
#include "hg_kinematics.h"
#include "hg_guard.h"
#include "hg_guard_text.h"
#include "hg_params.h"
#include "hg_text.h"
#include "hg_units.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("virtual Hexaglide project");
MODULE_DESCRIPTION("Kinematics of the UPNa Hexaglide parallel machine");

typedef struct {
    hal_float_t geo[HG_PARAMS_MAX];                /* geometry parameters, HAL units, by table index */
    hal_float_t mm_per_unit;                       /* mm in one machine unit (param, rw) */
    hg_units_setting units;                        /* the value in force, the last refused */
    hal_s32_t *fk_iterations;
    hal_s32_t *fk_max_iterations;
    hal_float_t *fk_tolerance_mm;
    hal_float_t *fk_residual_mm;
    hal_s32_t *fk_error;
    hal_bit_t *fk_fault;
    hal_u32_t *fk_fail_count;
    hal_s32_t *ik_error;
    int ik_refusing;                               /* the inverse's guard refused since its last success */
    hal_float_t *tool_offset;                      /* machine units */
    hg_tool_offset_setting tool;                   /* the offset in force, refused, its jumps */
    hal_u32_t *board_geometry;                     /* the board's geometry-fingerprint, 0: unconnected */
    int mismatch_calls;                            /* consecutive calls that found a mismatch */
    hg_geometry_setting geometry;                  /* the geometry last checked, its answer */
    hg_fk_session fk;                              /* the settings in force, what was refused, failing */
    hg_kins_switch kins;                           /* the kinematics type in force */
    EmcPose head;                                  /* the Hexaglide's kinematics' last world pose (skgui) */
    hal_bit_t *kinstype_is[3];                     /* kinstype.is-0 .. is-2 */
    hal_float_t *gui[6];                           /* skgui.x .. skgui.c: head */
} hexaglidekins_hal;

static hexaglidekins_hal *hd; /* the module's one instance, in HAL shared memory */
static int comp_id;
static char *coordinates = "";
RTAPI_MP_STRING(coordinates, "XYZABC (any case) or left out: the world coordinates, in joint order");

/* Geometry from the HAL parameters (HAL units -> SI); HG_ERR_BAD_PARAM,
 * reported once on the RTAPI log, when the user set an impossible one. */
static int current_geometry(hg_geometry *g)
{
    const char *field, *why;
    double given[HG_PARAMS_MAX];
    int i, n, set;
    const hg_param_info *t = hg_params_table(&n);
    for (i = 0; i < n; i++)
        given[i] = hd->geo[i];
    if (hg_geometry_take(&hd->geometry, given, &field, &why, &set)) {  /* once per refused geometry */
        char reason[HG_TEXT_VALUE_LEN * 8] = "", value[HG_TEXT_VALUE_LEN];
        const int e = hg_param_find(t, n, field);
        hg_param_hal_reason(reason, sizeof reason, why, e >= 0 ? &t[e] : 0);
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: parameter hexaglidekins.%s %s; kinematics refused until "
                        "it is fixed with setp\n", hg_params_hal_name(field), reason);
        if (set >= 0) {                  /* another field's rule: a line of its own (LinuxCNC keeps 254 characters) */
            hg_text_value(value, given[set]);
            rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: that rule failed after hexaglidekins.%s was set to %s\n",
                            t[set].hal_name, value);
        }
    }
    *g = hd->geometry.geo;
    if (hg_geometry_mismatch(*hd->board_geometry, hd->geometry.fingerprint, &hd->mismatch_calls))
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: the geometry differs from the board's "
                        "(hexaglidekins.board-geometry): LinuxCNC would drive another machine than the one "
                        "simulated; set both from the same [HEXAGLIDE] keys (compare halcmd show param "
                        "hexaglidekins. and motenc-hexaglide.0.)\n");
    return hd->geometry.rc;
}

/* The forward solver's settings from the pins into the session (the core
 * keeps the last valid pair); a refused pair is said once. */
static void fk_settings(void)
{
    const char *field = "", *why = "";
    if (hg_fk_session_settings(&hd->fk, *hd->fk_max_iterations, *hd->fk_tolerance_mm / HG_MM_PER_M, &field,
                               &why) == HG_FK_SAY_REFUSED) {
        char min_mm[HG_TEXT_VALUE_LEN], max_mm[HG_TEXT_VALUE_LEN], kept_mm[HG_TEXT_VALUE_LEN];
        hg_text_value(min_mm, HG_FK_TOLERANCE_MIN_M * HG_MM_PER_M);
        hg_text_value(max_mm, HG_FK_TOLERANCE_MAX_M * HG_MM_PER_M);
        hg_text_value(kept_mm, hd->fk.in_force.tolerance_m * HG_MM_PER_M);
        if (strcmp(field, "max_iterations") == 0)
            rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: pin hexaglidekins.fk-max-iterations %s; keeping %d\n",
                            why, hd->fk.in_force.max_iterations);
        else
            rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: pin hexaglidekins.fk-tolerance must be from %s to %s mm "
                            "(a finer Newton step is below what double precision resolves, a coarser one would "
                            "leave the pose off by more than an encoder count); keeping %s mm\n", min_mm, max_mm,
                            kept_mm);
    }
}

/* The machine units from the parameter into the setting (the core keeps
 * the last valid value); a refused value is said once and the parameter
 * shows the value in force again. The mm per unit in force. */
static double mm_per_unit(void)
{
    if (hg_units_take(&hd->units, hd->mm_per_unit) == HG_FK_SAY_REFUSED) {
        char got[HG_TEXT_VALUE_LEN], kept[HG_TEXT_VALUE_LEN];
        hg_text_value(got, hd->mm_per_unit);
        hg_text_value(kept, hd->units.in_force);
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: parameter hexaglidekins.mm-per-unit %s must be from 0.001 "
                        "to 1000 (mm in one machine unit: 1 for LINEAR_UNITS mm, 25.4 for inch); keeping %s\n",
                        got, kept);
        hd->mm_per_unit = hd->units.in_force;     /* halcmd show param shows what is in force, as the board */
    }
    return hd->units.in_force;
}

/* The tool offset from its pin into the setting, in m (*d_m: the one in
 * force); HG_ERR_BAD_PARAM while it is refused (the kinematics refuse their
 * calls until it is fixed). Says a refused value once, and a new offset
 * that moves Op at once (G43 or G49 taken with the head tilted: the joints
 * jump, and motion trips on them). */
static int tool_offset(const hg_geometry *g, double mpu, double *d_m)
{
    double given = *hd->tool_offset, was = hd->tool.in_force_m * HG_MM_PER_M / mpu;
    int say = hg_tool_offset_take(&hd->tool, g, given * mpu / HG_MM_PER_M, hd->kins.type == HG_KINS_HEXAGLIDE);
    char a[HG_TEXT_VALUE_LEN], b[HG_TEXT_VALUE_LEN], c[HG_TEXT_VALUE_LEN];
    *d_m = hd->tool.in_force_m;
    if (say == HG_FK_SAY_NOTHING)      /* every call but the rare ones that say something */
        return hd->tool.refusing ? HG_ERR_BAD_PARAM : HG_OK;
    hg_text_value(a, given);
    if (say == HG_FK_SAY_JUMP) {
        hg_text_value(b, was);
        hg_text_value(c, hd->tool.jump_m * HG_MM_PER_M);
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: the tool offset changed from %s to %s machine units "
                        "with the head tilted: Op moves %s mm at once and the joints jump (a following-error "
                        "trip); take G43 and G49 with A = B = 0\n", b, a, c);
    } else if (say == HG_FK_SAY_REFUSED) {
        hg_text_value(b, HG_MAX_ABS_POSITION_BARS * g->l_m * HG_MM_PER_M / mpu);
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: pin hexaglidekins.tool-offset %s is not a tool length "
                        "(finite, at most %s machine units either way); kinematics refused until it is "
                        "(net it to motion.tooloffset.z)\n", a, b);
    }
    return hd->tool.refusing ? HG_ERR_BAD_PARAM : HG_OK;
}

/* EmcPose (machine units, deg) -> core pose (m, rad). */
static void pose_from_emc(const EmcPose *pos, double mpu, double pose[6])
{
    double user[6] = {pos->tran.x, pos->tran.y, pos->tran.z, pos->a, pos->b, pos->c};
    hg_pose_from_machine(user, mpu, pose);
}

/* core pose (m, rad) -> EmcPose (machine units, deg); u v w are 0. */
static void pose_to_emc(const double pose[6], double mpu, EmcPose *pos)
{
    double user[6];
    hg_pose_to_machine(pose, mpu, user);
    pos->tran.x = user[0]; pos->tran.y = user[1]; pos->tran.z = user[2];
    pos->a = user[3]; pos->b = user[4]; pos->c = user[5];
    pos->u = pos->v = pos->w = 0.0;
}

/* The Hexaglide's forward kinematics of joints from the guess *pos into
 * *pos, its pins and messages: 0, or the hg_error code (then *pos is the
 * last pose solved). */
static int hexaglide_forward(const double *joints, EmcPose *pos)
{
    hg_geometry g;
    hg_fk_report rep = {0, 0.0};
    double z[6], commanded[6], pose[6], d_m = hd->tool.in_force_m;
    double mpu = mm_per_unit();
    int rc, say;
    pose_from_emc(pos, mpu, commanded);
    hg_joints_from_machine(joints, mpu, z);
    fk_settings();
    rc = current_geometry(&g);
    if (rc == 0)
        rc = tool_offset(&g, mpu, &d_m);
    hg_pose_offset_to_op(commanded, d_m, pose);                    /* the guess, as Op */
    if (rc == 0)
        rc = hg_fk_session_solve(&hd->fk, &g, z, pose, &rep);   /* on failure: the last pose solved */
    else
        hg_fk_session_hold(&hd->fk, pose);
    *hd->fk_iterations = rep.iterations;
    *hd->fk_residual_mm = rep.residual_m * HG_MM_PER_M;
    *hd->fk_error = rc;
    *hd->fk_fault = (rc != 0);
    say = hg_fk_session_result(&hd->fk, rc);
    *hd->fk_fail_count = hd->fk.fail_count;
    if (say == HG_FK_SAY_FAILING && hd->kins.type == HG_KINS_IDENTITY)
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: the Hexaglide's forward kinematics failed (code %d: %s) "
                        "under identity kinematics (type 1), which answer on; skgui.* stays at the last solved "
                        "pose until it succeeds (hexaglidekins.fk-error, fk-fail-count)\n", rc, hg_strerror(rc));
    else if (say == HG_FK_SAY_FAILING) /* the first of a run of failures: motion keeps the last pose */
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: forward kinematics failed (code %d: %s); the "
                        "position shown stays at the last solved pose until it succeeds "
                        "(hexaglidekins.fk-error, fk-fail-count)\n", rc, hg_strerror(rc));
    else if (say == HG_FK_SAY_FAILS_OTHERWISE)
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: forward kinematics now fails with code %d: %s (the "
                        "same run of failures; the position shown stays at the last solved pose)\n", rc,
                        hg_strerror(rc));
    else if (say == HG_FK_SAY_SOLVES_AGAIN)
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: forward kinematics solves again (after %u failed calls "
                        "in all)\n", hd->fk.fail_count);
    /* also on failure: motion keeps what is written here as its position
     * (it shows the last solved pose, not the world home it passes as the
     * next guess) */
    hg_pose_op_to_offset(pose, d_m, commanded);
    pose_to_emc(commanded, mpu, pos);
    return rc;
}

/* Identity (hg_identity_kinematics): world X Y Z A B C are joints 0..5;
 * pos untouched on failure. */
static int identity_forward(const double *joints, EmcPose *pos)
{
    double world[6];
    int rc = hg_identity_kinematics(joints, world);
    if (rc == HG_OK) {
        pos->tran.x = world[0]; pos->tran.y = world[1]; pos->tran.z = world[2];
        pos->a = world[3]; pos->b = world[4]; pos->c = world[5];
        pos->u = pos->v = pos->w = 0.0;
    }
    return rc;
}

/* The world pose by the Hexaglide's kinematics (the tool tip with tool-offset) into skgui.*. */
static void gui_pins(void)
{
    const double v[6] = {hd->head.tran.x, hd->head.tran.y, hd->head.tran.z, hd->head.a, hd->head.b, hd->head.c};
    int i;
    for (i = 0; i < 6; i++)
        *hd->gui[i] = v[i];
}

int kinematicsForward(const double *joints, EmcPose *pos,
                      const KINEMATICS_FORWARD_FLAGS *fflags,
                      KINEMATICS_INVERSE_FLAGS *iflags)
{
    int rc;
    (void)fflags;
    (void)iflags;
    if (hd->kins.type == HG_KINS_IDENTITY) {
        hexaglide_forward(joints, &hd->head);  /* tracked; its failure is on fk-error, not identity's */
        gui_pins();
        return identity_forward(joints, pos);
    }
    if (hg_kins_switch_restart(&hd->kins))    /* back from identity: motion's guesses are identity's world */
        *pos = hd->head;
    rc = hexaglide_forward(joints, pos);
    hd->head = *pos;
    gui_pins();
    return rc;
}

/* The first of a run of guard refusals of the inverse, on the RTAPI log:
 * the pose (machine units and deg, to 1e-6 of them: motion's poses carry
 * 1e-8 of rounding) and the limit it crosses, within the 255 characters
 * LinuxCNC's error channel keeps. */
static void say_ik_refused(const EmcPose *pos, int rc, const hg_guard_report *why)
{
    static const char *const axis[6] = {"X", " Y", " Z", " A", " B", " C"};
    const double user[6] = {pos->tran.x, pos->tran.y, pos->tran.z, pos->a, pos->b, pos->c};
    char what[HG_GUARD_TEXT_LEN], at[6 * (HG_TEXT_VALUE_LEN + 2)] = "";
    int k;
    for (k = 0; k < 6; k++) {
        hg_text_add(at, sizeof at, axis[k]);
        hg_text_add_value(at, sizeof at, floor(user[k] * 1e6 + 0.5) / 1e6 + 0.0);   /* (+0.0: no -0) */
    }
    hg_guard_describe(why, 1, what);
    rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: pose %s refused (code %d): %s\n", at, rc, what);
}

int kinematicsInverse(const EmcPose *pos, double *joints,
                      const KINEMATICS_INVERSE_FLAGS *iflags,
                      KINEMATICS_FORWARD_FLAGS *fflags)
{
    hg_geometry g;
    double commanded[6], pose[6], z[6], d_m = 0.0;
    double mpu = mm_per_unit();
    int rc;
    (void)iflags;
    (void)fflags;
    if (hd->kins.type == HG_KINS_IDENTITY) {
        const double world[6] = {pos->tran.x, pos->tran.y, pos->tran.z, pos->a, pos->b, pos->c};
        *hd->ik_error = hg_identity_kinematics(world, joints);
        return *hd->ik_error;
    }
    pose_from_emc(pos, mpu, commanded);
    rc = current_geometry(&g);
    if (rc == 0)
        rc = tool_offset(&g, mpu, &d_m);
    memcpy(hd->tool.last_inverse, commanded, sizeof commanded);
    if (rc == 0) {
        hg_guard_report why;
        hg_pose_offset_to_op(commanded, d_m, pose);
        rc = hg_inverse_kinematics_guarded(&g, pose, z, &why);   /* a pose the machine cannot take: refused */
        if (rc && why.kind != HG_GUARD_NONE && !hd->ik_refusing)
            say_ik_refused(pos, rc, &why);
        hd->ik_refusing = rc && why.kind != HG_GUARD_NONE;
    }
    *hd->ik_error = rc;
    if (rc)
        return rc;
    hg_joints_to_machine(z, mpu, joints);
    return 0;
}

KINEMATICS_TYPE kinematicsType(void)
{
    return KINEMATICS_BOTH;
}

int kinematicsSwitchable(void)
{
    return 1;
}

/* motion.switchkins-type changed (motion aborts on -1). */
int kinematicsSwitch(int type)
{
    int i;
    if (hg_kins_switch_to(&hd->kins, type)) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: there is no kinematics type %d (motion.switchkins-type): "
                        "0 is the Hexaglide's, 1 identity (joint n is X Y Z A B C's n-th); type %d stays in "
                        "force\n", type, hd->kins.type);
        return -1;
    }
    for (i = 0; i < 3; i++)
        *hd->kinstype_is[i] = (i == hd->kins.type);
    return 0;
}

/* Export the pins and parameters with the spec's defaults. */
static int export_hal(void)
{
    hg_params p;
    int r = 0, i, n;
    const hg_param_info *t = hg_params_table(&n);
    hg_params_default(&p);
    for (i = 0; i < n; i++)
        if (hg_param_is_geometry(i)) {
            r |= hal_param_float_newf(HAL_RW, &hd->geo[i], comp_id, "hexaglidekins.%s", t[i].hal_name);
            hd->geo[i] = hg_params_get(&p, i) * t[i].hal_scale;
        }
    r |= hal_param_float_newf(HAL_RW, &hd->mm_per_unit, comp_id, "hexaglidekins.mm-per-unit");
    r |= hal_pin_s32_newf(HAL_OUT, &hd->fk_iterations, comp_id, "hexaglidekins.fk-iterations");
    r |= hal_pin_s32_newf(HAL_IN, &hd->fk_max_iterations, comp_id, "hexaglidekins.fk-max-iterations");
    r |= hal_pin_float_newf(HAL_IN, &hd->fk_tolerance_mm, comp_id, "hexaglidekins.fk-tolerance");
    r |= hal_pin_float_newf(HAL_OUT, &hd->fk_residual_mm, comp_id, "hexaglidekins.fk-residual");
    r |= hal_pin_s32_newf(HAL_OUT, &hd->fk_error, comp_id, "hexaglidekins.fk-error");
    r |= hal_pin_bit_newf(HAL_OUT, &hd->fk_fault, comp_id, "hexaglidekins.fk-fault");
    r |= hal_pin_u32_newf(HAL_OUT, &hd->fk_fail_count, comp_id, "hexaglidekins.fk-fail-count");
    r |= hal_pin_s32_newf(HAL_OUT, &hd->ik_error, comp_id, "hexaglidekins.ik-error");
    r |= hal_pin_u32_newf(HAL_IN, &hd->board_geometry, comp_id, "hexaglidekins.board-geometry");
    r |= hal_pin_float_newf(HAL_IN, &hd->tool_offset, comp_id, "hexaglidekins.tool-offset");
    for (i = 0; i < 3; i++)
        r |= hal_pin_bit_newf(HAL_OUT, &hd->kinstype_is[i], comp_id, "kinstype.is-%d", i);
    for (i = 0; i < 6; i++)
        r |= hal_pin_float_newf(HAL_OUT, &hd->gui[i], comp_id, "skgui.%c", "xyzabc"[i]);
    if (r)
        return r;
    hg_fk_session_init(&hd->fk);
    hg_units_init(&hd->units);
    hd->mm_per_unit = hd->units.in_force;
    *hd->fk_max_iterations = hd->fk.in_force.max_iterations;
    *hd->fk_tolerance_mm = hd->fk.in_force.tolerance_m * HG_MM_PER_M;
    *hd->fk_iterations = 0;
    *hd->fk_residual_mm = 0.0;
    *hd->fk_error = 0;
    *hd->fk_fault = 0;
    *hd->fk_fail_count = 0;
    *hd->ik_error = 0;
    hd->ik_refusing = 0;
    *hd->board_geometry = 0;
    *hd->tool_offset = 0.0;
    hg_tool_offset_init(&hd->tool);
    hd->mismatch_calls = 0;
    hg_geometry_setting_init(&hd->geometry);
    memset(&hd->head, 0, sizeof hd->head);     /* HOME: X Y Z A B C = 0 */
    hg_kins_switch_init(&hd->kins);
    kinematicsSwitch(hd->kins.type);
    gui_pins();
    return 0;
}

int rtapi_app_main(void)
{
    if (!hg_kins_coordinates_ok(coordinates)) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: coordinates=%s: the Hexaglide's joints are X Y Z A B C "
                        "in that order; give coordinates=XYZABC or leave it out\n", coordinates);
        return -1;
    }
    comp_id = hal_init("hexaglidekins");
    if (comp_id < 0)
        return comp_id;
    hd = hal_malloc(sizeof *hd);
    if (!hd) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: out of HAL shared memory\n");
        hal_exit(comp_id);
        return -1;
    }
    if (export_hal()) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hexaglidekins: could not export pins/parameters\n");
        hal_exit(comp_id);
        return -1;
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    hal_exit(comp_id);
}

EXPORT_SYMBOL(kinematicsSwitchable);
EXPORT_SYMBOL(kinematicsSwitch);
EXPORT_SYMBOL(kinematicsType);
EXPORT_SYMBOL(kinematicsForward);
EXPORT_SYMBOL(kinematicsInverse);
