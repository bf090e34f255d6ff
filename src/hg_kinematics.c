/* hg_kinematics.c - Hexaglide frames, closed-form inverse kinematics and
 * Newton-Raphson forward kinematics with the analytic Jacobian. */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_kinematics.h"
#include "hg_compiler.h"
#include "hg_linalg.h"
#include "hg_errors.h"
#include "hg_units.h"
#include "hg_text.h"

/* cos and sin of the post angles alpha = 0, +120, -120 degrees */
static const double post_cos[3] = {1.0, -0.5, -0.5};
static const double post_sin[3] = {0.0, 0.86602540378443864676, -0.86602540378443864676};

/* 1 when every one of the n positions is within HG_MAX_ABS_POSITION_BARS bar lengths. */
static int within_reach(const hg_geometry *g, int n, const double *x)
{
    int k;
    for (k = 0; k < n; k++)
        if (!(fabs(x[k]) <= HG_MAX_ABS_POSITION_BARS * g->l_m))
            return 0;
    return 1;
}

/* Newton steps larger than this (m or rad) mean the iteration ran away */
#define HG_FK_MAX_STEP 1.0
void hg_fk_options_default(hg_fk_options *o)
{
    o->max_iterations = 30;
    o->tolerance_m = 1e-12;
}

int hg_fk_options_check(const hg_fk_options *o, const char **field, const char **why)
{
    const char *f = 0, *w = 0;
    if (!(o->max_iterations >= HG_FK_ITERATION_MIN && o->max_iterations <= HG_FK_ITERATION_CAP))
        f = "max_iterations", w = "must be a whole number from 3 to 100 (the solve stops when its step is below the "
                                  "tolerance: with fewer, a moving machine never gets there)";
    else if (!(o->tolerance_m >= HG_FK_TOLERANCE_MIN_M && o->tolerance_m <= HG_FK_TOLERANCE_MAX_M))
        f = "tolerance", w = "must be from 1e-13 to 1e-6 m: a finer Newton step than 1e-13 m is below what double "
                             "precision resolves, a coarser one than 1e-6 m would leave the pose off by more than "
                             "an encoder count";
    if (field)
        *field = f;
    if (why)
        *why = w;
    return f ? HG_ERR_BAD_PARAM : HG_OK;
}

void hg_fk_session_init(hg_fk_session *s)
{
    memset(s, 0, sizeof *s);
    hg_fk_options_default(&s->in_force);
    s->refused_iterations = s->in_force.max_iterations;   /* a valid pair: nothing refused yet */
    s->refused_tolerance_m = s->in_force.tolerance_m;
}

int hg_fk_session_settings(hg_fk_session *s, int max_iterations, double tolerance_m, const char **field,
                           const char **why)
{
    hg_fk_options o = s->in_force;
    o.max_iterations = max_iterations;
    o.tolerance_m = tolerance_m;
    if (hg_fk_options_check(&o, field, why) == 0) {
        s->in_force = o;
        s->refused_iterations = max_iterations;   /* a valid pair: the next refusal is said again */
        s->refused_tolerance_m = tolerance_m;
        return HG_FK_SAY_NOTHING;
    }
    if (max_iterations == s->refused_iterations &&
        memcmp(&tolerance_m, &s->refused_tolerance_m, sizeof tolerance_m) == 0) // NOLINT(bugprone-suspicious-memory-comparison): bitwise, NaN equals itself
        return HG_FK_SAY_NOTHING;      /* refused and said already */
    s->refused_iterations = max_iterations;
    s->refused_tolerance_m = tolerance_m;
    return HG_FK_SAY_REFUSED;
}

int hg_fk_session_result(hg_fk_session *s, int rc)
{
    const int was_failing = s->failing;
    const unsigned code = rc < 0 && rc > -32 ? 1u << -rc : 1u;   /* (another value: bit 0) */
    s->failing = (rc != 0);
    if (rc) {
        s->fail_count++;
        if (!was_failing) {
            s->said_codes = code;
            return HG_FK_SAY_FAILING;
        }
        if (s->said_codes & code)
            return HG_FK_SAY_NOTHING;
        s->said_codes |= code;
        return HG_FK_SAY_FAILS_OTHERWISE;
    }
    return was_failing ? HG_FK_SAY_SOLVES_AGAIN : HG_FK_SAY_NOTHING;
}

int hg_mm_per_unit_check(double mm_per_unit)
{
    return (mm_per_unit >= HG_MM_PER_UNIT_MIN && mm_per_unit <= HG_MM_PER_UNIT_MAX) ? HG_OK : HG_ERR_BAD_PARAM;
}

void hg_units_init(hg_units_setting *u)
{
    u->in_force = HG_MM_PER_UNIT_DEFAULT;
    u->refused = HG_MM_PER_UNIT_DEFAULT;
}

int hg_say_refused_once(double *last, double value, int accepted)
{
    if (!accepted && memcmp(&value, last, sizeof value) == 0) // NOLINT(bugprone-suspicious-memory-comparison): bitwise, NaN equals itself
        return HG_FK_SAY_NOTHING;      /* refused and said already */
    *last = value;                     /* a valid value: the next refusal is said again */
    return accepted ? HG_FK_SAY_NOTHING : HG_FK_SAY_REFUSED;
}

int hg_units_take(hg_units_setting *u, double mm_per_unit)
{
    int accepted = (hg_mm_per_unit_check(mm_per_unit) == HG_OK);
    if (accepted)
        u->in_force = mm_per_unit;
    return hg_say_refused_once(&u->refused, mm_per_unit, accepted);
}

/* (x * mm_per_unit) / 1000 and (x * 1000) / mm_per_unit: with mm_per_unit 1
 * the same roundings as x / 1000 and x * 1000; the angles as hg_units.h's. */
void hg_pose_from_machine(const double user[6], double mm_per_unit, double pose[6])
{
    double mm[6];
    int k;
    for (k = 0; k < 6; k++)
        mm[k] = k < 3 ? user[k] * mm_per_unit : user[k];
    hg_pose_from_user(mm, pose);
}

void hg_pose_to_machine(const double pose[6], double mm_per_unit, double user[6])
{
    int k;
    hg_pose_to_user(pose, user);
    for (k = 0; k < 3; k++)
        user[k] /= mm_per_unit;
}

void hg_joints_from_machine(const double joints[6], double mm_per_unit, double z[6])
{
    int k;
    for (k = 0; k < 6; k++)
        z[k] = joints[k] * mm_per_unit / HG_MM_PER_M;
}

void hg_joints_to_machine(const double z[6], double mm_per_unit, double joints[6])
{
    int k;
    for (k = 0; k < 6; k++)
        joints[k] = z[k] * HG_MM_PER_M / mm_per_unit;
}

void hg_tool_tip(const double pose[6], double tool_d_m, double tip[3])
{
    double R[9];
    int i;
    hg_rotation(pose[3], pose[4], pose[5], R);
    for (i = 0; i < 3; i++)
        tip[i] = pose[i] - tool_d_m * R[3 * i + 2];
}

int hg_tool_offset_check(const hg_geometry *g, double tool_offset_m)
{
    return within_reach(g, 1, &tool_offset_m) ? HG_OK : HG_ERR_BAD_PARAM;
}

/* op = c + d (R z - z) in X Y Z, the angles as they are: with d 0 or an
 * untilted head R z - z is exactly 0 and op is c (up to the sign of a zero). */
void hg_pose_offset_to_op(const double commanded[6], double tool_offset_m, double op[6])
{
    double R[9];
    int i;
    for (i = 0; i < 6; i++)
        op[i] = commanded[i];
    if (tool_offset_m == 0.0)
        return;                        /* no tool offset: no rotation to compute */
    hg_rotation(commanded[3], commanded[4], commanded[5], R);
    for (i = 0; i < 3; i++)
        op[i] += tool_offset_m * (R[3 * i + 2] - (i == 2));
}

void hg_pose_op_to_offset(const double op[6], double tool_offset_m, double commanded[6])
{
    hg_pose_offset_to_op(op, -tool_offset_m, commanded);
}

double hg_tool_offset_jump(const double commanded[6], double from_m, double to_m)
{
    double a[6], b[6];
    hg_pose_offset_to_op(commanded, from_m, a);
    hg_pose_offset_to_op(commanded, to_m, b);
    return sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
}

int hg_kins_coordinates_ok(const char *coordinates)
{
    return !coordinates || !coordinates[0] || hg_text_is_word(coordinates, strlen(coordinates), "xyzabc");
}

int hg_identity_kinematics(const double in[6], double out[6])
{
    if (!hg_all_finite(6, in))
        return HG_ERR_NONFINITE_INPUT;
    memcpy(out, in, 6 * sizeof *in);
    return HG_OK;
}

int hg_kins_switch_restart(hg_kins_switch *s)
{
    if (s->restart <= 0)
        return 0;
    s->restart--;
    return 1;
}

void hg_kins_switch_init(hg_kins_switch *s)
{
    s->type = HG_KINS_HEXAGLIDE;
    s->restart = 0;
}

int hg_kins_switch_to(hg_kins_switch *s, int type)
{
    if (type != HG_KINS_HEXAGLIDE && type != HG_KINS_IDENTITY)
        return HG_ERR_BAD_PARAM;
    if (type == HG_KINS_HEXAGLIDE && s->type != HG_KINS_HEXAGLIDE)
        s->restart = HG_KINS_RESTART_CALLS;
    s->type = type;
    return HG_OK;
}

void hg_tool_offset_init(hg_tool_offset_setting *t)
{
    memset(t, 0, sizeof *t);
}

int hg_tool_offset_take(hg_tool_offset_setting *t, const hg_geometry *g, double tool_offset_m, int applied)
{
    int accepted = (hg_tool_offset_check(g, tool_offset_m) == HG_OK);
    int say = hg_say_refused_once(&t->given_m, tool_offset_m, accepted);
    t->refusing = !accepted;
    if (accepted && tool_offset_m != t->in_force_m) {
        t->jump_m = applied ? hg_tool_offset_jump(t->last_inverse, t->in_force_m, tool_offset_m) : 0.0;
        t->in_force_m = tool_offset_m;
        if (t->jump_m > HG_TOOL_OFFSET_JUMP_SAY_M)
            say = HG_FK_SAY_JUMP;
    }
    return say;
}

/* Rz(alpha_i) (radial, s_j e, 0) for bar k. */
static void post_point(int k, double radial, double e, double out[3])
{
    int i = k / 2;
    double s = (k % 2 == 0) ? 1.0 : -1.0;
    out[0] = post_cos[i] * radial - post_sin[i] * s * e;
    out[1] = post_sin[i] * radial + post_cos[i] * s * e;
    out[2] = 0.0;
}

void hg_guide_point(const hg_geometry *g, int k, double out[3])
{
    post_point(k, g->lb_m, g->e_m, out);
}

void hg_head_point(const hg_geometry *g, int k, double out[3])
{
    post_point(k, g->lp_m, g->e_m, out);
}

void hg_head_trig(const double *c, double sc[6])
{
    sc[0] = sin(c[3]);
    sc[1] = cos(c[3]);
    sc[2] = sin(c[4]);
    sc[3] = cos(c[4]);
    sc[4] = sin(c[5]);
    sc[5] = cos(c[5]);
}

void hg_rotation_sc(const double t[6], double R[9])
{
    const double sa = t[0], ca = t[1], sb = t[2], cb = t[3], sc = t[4], cc = t[5];
    R[0] = cc * cb; R[1] = cc * sb * sa - sc * ca; R[2] = cc * sb * ca + sc * sa;
    R[3] = sc * cb; R[4] = sc * sb * sa + cc * ca; R[5] = sc * sb * ca - cc * sa;
    R[6] = -sb;     R[7] = cb * sa;                R[8] = cb * ca;
}

void hg_rotation(double a, double b, double c, double R[9])
{
    const double pose[6] = {0.0, 0.0, 0.0, a, b, c};
    double sc[6];
    hg_head_trig(pose, sc);
    hg_rotation_sc(sc, R);
}

/* out = R p. */
static inline void rotate(const double R[9], const double p[3], double out[3])
{
    int r;
    for (r = 0; r < 3; r++)
        out[r] = R[3 * r] * p[0] + R[3 * r + 1] * p[1] + R[3 * r + 2] * p[2];
}

/* World offsets w[k] = R r_k of the head joints from Op. */
static void head_offsets(const hg_geometry *g, const double R[9], double w[6][3])
{
    int k;
    for (k = 0; k < HG_NBARS; k++) {
        double p[3];
        hg_head_point(g, k, p);
        rotate(R, p, w[k]);
    }
}

void hg_frame_of(const hg_geometry *g, hg_frame *f)
{
    int k;
    f->h = hg_home_height(g);
    for (k = 0; k < HG_NBARS; k++) {
        hg_guide_point(g, k, f->guide[k]);
        hg_head_point(g, k, f->head[k]);
    }
}

void hg_joint_points(const hg_geometry *g, const double z[6], const double pose[6],
                     double B[6][3], double A[6][3])
{
    hg_frame f;
    double R[9];
    hg_frame_of(g, &f);
    hg_rotation(pose[3], pose[4], pose[5], R);
    hg_joint_points_rot(&f, R, z, pose, B, A);
}

void hg_joint_points_rot(const hg_frame *f, const double R[9], const double z[6],
                         const double pose[6], double B[6][3], double A[6][3])
{
    int k, r;
    for (k = 0; k < HG_NBARS; k++) {
        const double *p = f->head[k];
        B[k][0] = f->guide[k][0];
        B[k][1] = f->guide[k][1];
        B[k][2] = f->h + z[k];
        for (r = 0; r < 3; r++)        /* Op + R r_k, rotate() in place (the guard's hot path) */
            A[k][r] = pose[r] + (R[3 * r] * p[0] + R[3 * r + 1] * p[1] + R[3 * r + 2] * p[2]);
    }
}

/* A bar's constraint |B - A|^2 - l^2. */
static inline double bar_phi(const double B[3], const double A[3], double l)
{
    double dx = B[0] - A[0], dy = B[1] - A[1], dz = B[2] - A[2];
    return dx * dx + dy * dy + dz * dz - l * l;
}

void hg_constraints(const hg_geometry *g, const double z[6], const double pose[6],
                    double phi[6])
{
    double B[6][3], A[6][3];
    int k;
    hg_joint_points(g, z, pose, B, A);
    for (k = 0; k < HG_NBARS; k++)
        phi[k] = bar_phi(B[k], A[k], g->l_m);
}

/* The axes the Euler angles turn about, in the world: d(R r)/d(A,B,C) = axis_m x (R r). */
static void rotation_axes(const double R[9], const double sc[6], double axis[3][3])
{
    axis[0][0] = R[0]; axis[0][1] = R[3]; axis[0][2] = R[6];          /* Rz Ry e_x */
    axis[1][0] = -sc[4]; axis[1][1] = sc[5]; axis[1][2] = 0;          /* Rz e_y */
    axis[2][0] = 0; axis[2][1] = 0; axis[2][2] = 1;                   /* e_z */
}

/* One bar's row of d(phi)/d(pose) from its head offset w = R r and d = B - A:
 * dPhi/dP = -2 d ; dPhi/dangle_m = -2 d . (axis_m x w) = -2 axis_m . (w x d). */
static void jacobian_row(const double axis[3][3], const double w[3], const double d[3], double row[6])
{
    double wxd[3];
    int m;
    wxd[0] = w[1] * d[2] - w[2] * d[1];
    wxd[1] = w[2] * d[0] - w[0] * d[2];
    wxd[2] = w[0] * d[1] - w[1] * d[0];
    for (m = 0; m < 3; m++)
        row[m] = -2.0 * d[m];
    for (m = 0; m < 3; m++)
        row[3 + m] = -2.0 * (axis[m][0] * wxd[0] + axis[m][1] * wxd[1] + axis[m][2] * wxd[2]);
}

void hg_constraint_jacobian(const hg_geometry *g, const double z[6], const double pose[6],
                            double jac_pose[36], double dphi_dz[6])
{
    const double h = hg_home_height(g);
    double R[9], w[6][3], sc[6];
    double axis[3][3];
    int k;
    hg_head_trig(pose, sc);
    hg_rotation_sc(sc, R);
    head_offsets(g, R, w);
    rotation_axes(R, sc, axis);
    for (k = 0; k < HG_NBARS; k++) {
        double d[3], b[3];
        hg_guide_point(g, k, b);
        d[0] = b[0] - pose[0] - w[k][0];
        d[1] = b[1] - pose[1] - w[k][1];
        d[2] = h + z[k] - pose[2] - w[k][2];
        jacobian_row(HG_CONST_ROWS3(axis), w[k], d, jac_pose + 6 * k);
        if (dphi_dz)
            dphi_dz[k] = 2.0 * d[2];
    }
}

int hg_inverse_kinematics(const hg_geometry *g, const double pose[6], double z[6])
{
    const double h = hg_home_height(g);
    double R[9], w[6][3], out[6];
    int k;
    if (!hg_all_finite(6, pose))
        return HG_ERR_NONFINITE_INPUT;
    if (fabs(pose[4]) > HG_MAX_ABS_B_RAD)
        return HG_ERR_EULER_SINGULAR;
    if (!within_reach(g, 3, pose))
        return HG_ERR_UNREACHABLE;
    hg_rotation(pose[3], pose[4], pose[5], R);
    head_offsets(g, R, w);
    for (k = 0; k < HG_NBARS; k++) {
        double b[3], dx, dy, rad;
        hg_guide_point(g, k, b);
        dx = b[0] - pose[0] - w[k][0];
        dy = b[1] - pose[1] - w[k][1];
        rad = g->l_m * g->l_m - dx * dx - dy * dy;
        if (!(rad > 0.0))
            return HG_ERR_UNREACHABLE;
        out[k] = pose[2] + w[k][2] - h + sqrt(rad);
    }
    if (!hg_all_finite(6, out))
        return HG_ERR_NONFINITE_INPUT;
    for (k = 0; k < HG_NBARS; k++)
        z[k] = out[k];
    return HG_OK;
}

double hg_bar_length_error(const hg_geometry *g, const double z[6], const double pose[6])
{
    double phi[6], worst = 0.0;
    int k;
    hg_constraints(g, z, pose, phi);
    for (k = 0; k < HG_NBARS; k++) {
        /* |d| - l = phi / (|d| + l) */
        double len = sqrt(phi[k] + g->l_m * g->l_m);
        double err = fabs(phi[k]) / (len + g->l_m);
        if (!(err <= worst))
            worst = err; /* also catches NaN */
    }
    return worst;
}

/* One Newton iteration's phi and d(phi)/d(pose) at pose c: what
 * hg_constraints and hg_constraint_jacobian give, bit for bit (the same
 * operations in the same order), from one sin/cos and rotation instead of
 * two and the frame f made once per solve. */
static void newton_terms(const hg_geometry *g, const hg_frame *f, const double z[6], const double c[6],
                         double phi[6], double jac[36])
{
    double R[9], sc[6], axis[3][3];
    int k, r;
    hg_head_trig(c, sc);
    hg_rotation_sc(sc, R);
    rotation_axes(R, sc, axis);
    for (k = 0; k < HG_NBARS; k++) {
        const double *b = f->guide[k];
        const double B[3] = {b[0], b[1], f->h + z[k]};   /* hg_joint_points_rot's joints */
        double w[3], a[3], d[3];
        rotate(R, f->head[k], w);
        for (r = 0; r < 3; r++)
            a[r] = c[r] + w[r];
        phi[k] = bar_phi(B, a, g->l_m);
        d[0] = b[0] - c[0] - w[0];     /* hg_constraint_jacobian's d */
        d[1] = b[1] - c[1] - w[1];
        d[2] = f->h + z[k] - c[2] - w[2];
        jacobian_row(HG_CONST_ROWS3(axis), w, d, jac + 6 * k);
    }
}

/* 1 when every carriage joint is above its head joint (the machine's branch). */
static int on_machine_branch(const hg_geometry *g, const double z[6], const double pose[6])
{
    double B[6][3], A[6][3];
    int k;
    hg_joint_points(g, z, pose, B, A);
    for (k = 0; k < HG_NBARS; k++)
        if (!(B[k][2] > A[k][2]))
            return 0;
    return 1;
}

int hg_forward_solve(const hg_geometry *g, const double z[6], double pose[6], const hg_fk_options *opt,
                     int *iterations, double *residual_m)
{
    hg_fk_options o;
    hg_frame f;
    double c[6], phi[6], jac[36], residual;
    int piv[6], it, k, rc = HG_ERR_NO_CONVERGENCE;
    if (opt)
        o = *opt;
    else
        hg_fk_options_default(&o);
    if (iterations)
        *iterations = 0;
    if (residual_m)
        *residual_m = 0.0;
    if (hg_fk_options_check(&o, 0, 0))
        return HG_ERR_BAD_PARAM;      /* nothing clamped: the caller names the setting (hg_fk_options_check) */
    if (!hg_all_finite(6, z) || !hg_all_finite(6, pose) || !isfinite(o.tolerance_m))
        return HG_ERR_NONFINITE_INPUT;
    if (!within_reach(g, 6, z))
        return HG_ERR_UNREACHABLE;
    for (k = 0; k < 6; k++)
        c[k] = pose[k];
    hg_frame_of(g, &f);
    for (it = 1; it <= o.max_iterations; it++) {
        double step = 0.0;
        newton_terms(g, &f, z, c, phi, jac);
        if (hg_lu_factor(6, jac, piv)) {
            rc = HG_ERR_SINGULAR_JACOBIAN;
            break;
        }
        hg_lu_solve(6, jac, piv, 1, phi); /* phi <- J^-1 phi */
        for (k = 0; k < 6; k++) {
            double sk = fabs(phi[k]) * (k < 3 ? 1.0 : g->l_m); /* angles as arc length */
            c[k] -= phi[k];
            if (!(sk <= step))
                step = sk;
        }
        if (iterations)
            *iterations = it;
        if (!(step <= HG_FK_MAX_STEP * g->l_m) || !hg_all_finite(6, c)) {
            rc = HG_ERR_DIVERGED;
            break;
        }
        if (step <= o.tolerance_m) {
            rc = HG_OK;
            break;
        }
    }
    residual = hg_bar_length_error(g, z, c);
    if (residual_m)
        *residual_m = residual;
    /* the last step was below tolerance, so the residual is far below it;
     * the margin only guards against a Jacobian that lied */
    if (rc == HG_OK && !(residual <= 1e3 * o.tolerance_m + 1e-12))
        rc = HG_ERR_NO_CONVERGENCE;
    if (rc == HG_OK && fabs(c[4]) > HG_MAX_ABS_B_RAD)
        rc = HG_ERR_EULER_SINGULAR;
    if (rc == HG_OK && !on_machine_branch(g, z, c))
        rc = HG_ERR_WRONG_BRANCH;
    if (rc == HG_OK)
        for (k = 0; k < 6; k++)
            pose[k] = c[k];
    return rc;
}
