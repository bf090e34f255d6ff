/* test_kinematics.c - inverse/forward kinematics against independent facts:
 * bar lengths from a second formulation, round trips, finite-difference
 * Jacobian, spec facts (HOME, pure vertical motion), refusals. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_errors.h"
#include "hg_kinematics.h"
#include "hg_guard.h"
#include "hg_units.h"

#define DEG (3.14159265358979323846 / 180.0)

/* Second formulation of the head joint: elementary rotations applied one
 * after another (x first, then y, then z), post angle by atan2-free
 * rotation of (r, s e) with cos/sin of the literal angle. */
static void head_joint_world(const hg_geometry *g, const double pose[6], int k, double out[3])
{
    double alpha = (k / 2 == 0) ? 0.0 : (k / 2 == 1 ? 120.0 * DEG : -120.0 * DEG);
    double s = (k % 2 == 0) ? 1.0 : -1.0;
    double p[3] = {cos(alpha) * g->lp_m - sin(alpha) * s * g->e_m,
                   sin(alpha) * g->lp_m + cos(alpha) * s * g->e_m, 0.0};
    double t;
    /* Rx(A) */
    t = cos(pose[3]) * p[1] - sin(pose[3]) * p[2];
    p[2] = sin(pose[3]) * p[1] + cos(pose[3]) * p[2];
    p[1] = t;
    /* Ry(B) */
    t = cos(pose[4]) * p[0] + sin(pose[4]) * p[2];
    p[2] = -sin(pose[4]) * p[0] + cos(pose[4]) * p[2];
    p[0] = t;
    /* Rz(C) */
    t = cos(pose[5]) * p[0] - sin(pose[5]) * p[1];
    p[1] = sin(pose[5]) * p[0] + cos(pose[5]) * p[1];
    p[0] = t;
    out[0] = pose[0] + p[0];
    out[1] = pose[1] + p[1];
    out[2] = pose[2] + p[2];
}

/* Largest | |B-A| - l | computed with the second formulation (metres). */
static double bar_error_independent(const hg_geometry *g, const double z[6], const double pose[6])
{
    double worst = 0.0;
    int k;
    for (k = 0; k < 6; k++) {
        double alpha = (k / 2 == 0) ? 0.0 : (k / 2 == 1 ? 120.0 * DEG : -120.0 * DEG);
        double s = (k % 2 == 0) ? 1.0 : -1.0;
        double b[3] = {cos(alpha) * g->lb_m - sin(alpha) * s * g->e_m,
                       sin(alpha) * g->lb_m + cos(alpha) * s * g->e_m,
                       sqrt(g->l_m * g->l_m - (g->lb_m - g->lp_m) * (g->lb_m - g->lp_m)) + z[k]};
        double a[3], len;
        head_joint_world(g, pose, k, a);
        len = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                   (b[2] - a[2]) * (b[2] - a[2]));
        if (fabs(len - g->l_m) > worst)
            worst = fabs(len - g->l_m);
    }
    return worst;
}

/* A random pose in the working volume (joints inside the +-240 mm soft limits). */
static int random_pose(const hg_geometry *g, double pose[6], double z[6])
{
    int tries;
    for (tries = 0; tries < 1000; tries++) {
        pose[0] = hg_test_uniform(-0.12, 0.12);
        pose[1] = hg_test_uniform(-0.12, 0.12);
        pose[2] = hg_test_uniform(-0.20, 0.20);
        pose[3] = hg_test_uniform(-20, 20) * DEG;
        pose[4] = hg_test_uniform(-20, 20) * DEG;
        pose[5] = hg_test_uniform(-25, 25) * DEG;
        if (hg_inverse_kinematics(g, pose, z) == HG_OK) {
            int k, inside = 1;
            for (k = 0; k < 6; k++)
                if (fabs(z[k]) > 0.240)
                    inside = 0;
            if (inside)
                return 1;
        }
    }
    return 0;
}

static void test_home(const hg_params *p)
{
    double pose[6] = {0, 0, 0, 0, 0, 0}, z[6], worst = 0, up[6];
    int k;
    double h = sqrt(1.0 - (0.484 - 0.073085) * (0.484 - 0.073085)); /* spec: sqrt(l^2-(lb-lp)^2) */
    CHECK(fabs(hg_home_height(&p->geo) - h) < 1e-15 && fabs(h - 0.9116736602) < 1e-10,
          "h = sqrt(l^2-(lb-lp)^2) = %.10f m as in the spec", hg_home_height(&p->geo));
    CHECK(hg_inverse_kinematics(&p->geo, pose, z) == HG_OK, "IK of HOME succeeds");
    for (k = 0; k < 6; k++)
        if (fabs(z[k]) > worst)
            worst = fabs(z[k]);
    CHECK(worst < 1e-14, "HOME pose gives all joints 0 (max |z| = %.2e m)", worst);
    /* pure vertical motion moves all six carriages equally (spec fact) */
    pose[2] = 0.0731;
    CHECK(hg_inverse_kinematics(&p->geo, pose, up) == HG_OK, "IK of HOME + 73.1 mm in Z");
    worst = 0;
    for (k = 0; k < 6; k++)
        if (fabs(up[k] - 0.0731) > worst)
            worst = fabs(up[k] - 0.0731);
    CHECK(worst < 1e-15, "pure vertical motion moves every carriage by dZ (err %.2e m)", worst);
}

static void test_rotation_convention(void)
{
    double R[9], x[3];
    /* C = 90 deg maps x to y; B = 90 deg maps x to -z; A = 90 deg maps y to z */
    hg_rotation(0, 0, 90 * DEG, R);
    x[0] = R[0]; x[1] = R[3]; x[2] = R[6];
    CHECK(fabs(x[0]) < 1e-15 && fabs(x[1] - 1) < 1e-15, "Rz(C=90) maps x to y");
    hg_rotation(0, 90 * DEG, 0, R);
    CHECK(fabs(R[6] + 1) < 1e-15, "Ry(B=90) maps x to -z");
    hg_rotation(90 * DEG, 0, 0, R);
    CHECK(fabs(R[7] - 1) < 1e-15, "Rx(A=90) maps y to z");
    /* 3-2-1 order: R = Rz(C) Ry(B) Rx(A): R[6] = -sin B regardless of A, C */
    hg_rotation(0.3, 0.2, 0.1, R);
    CHECK(fabs(R[6] + sin(0.2)) < 1e-15 && fabs(R[2] - (cos(0.1) * sin(0.2) * cos(0.3) + sin(0.1) * sin(0.3))) < 1e-15,
          "R = Rz(C) Ry(B) Rx(A) (3-2-1 Euler)");
}

static void test_ik_bar_lengths(const hg_params *p)
{
    double pose[6], z[6], worst = 0;
    int n;
    for (n = 0; n < 2000; n++) {
        double e;
        if (!random_pose(&p->geo, pose, z))
            continue;
        e = bar_error_independent(&p->geo, z, pose);
        if (e > worst)
            worst = e;
    }
    CHECK(worst < 1e-13, "IK joints give bar length l by a second formulation (max err %.2e m, 2000 poses)", worst);
}

static void test_round_trip(const hg_params *p)
{
    int n, done = 0, fails = 0, hist[31] = {0}, maxit = 0;
    double worst_lin = 0, worst_ang = 0;
    for (n = 0; n < 10000; n++) {
        double pose[6], z[6], fk[6] = {0, 0, 0, 0, 0, 0};
        hg_fk_report rep;
        int k, rc;
        if (!random_pose(&p->geo, pose, z))
            continue;
        rc = hg_forward_kinematics(&p->geo, z, fk, 0, &rep); /* from HOME */
        done++;
        if (rc) {
            fails++;
            continue;
        }
        if (rep.iterations <= 30)
            hist[rep.iterations]++;
        if (rep.iterations > maxit)
            maxit = rep.iterations;
        for (k = 0; k < 3; k++) {
            if (fabs(fk[k] - pose[k]) * 1e3 > worst_lin)
                worst_lin = fabs(fk[k] - pose[k]) * 1e3;
            if (fabs(fk[k + 3] - pose[k + 3]) / DEG > worst_ang)
                worst_ang = fabs(fk[k + 3] - pose[k + 3]) / DEG;
        }
    }
    CHECK(done == 10000, "10000 random reachable poses in the working volume (%d)", done);
    CHECK(fails == 0, "forward kinematics from HOME converged for every pose (%d failures)", fails);
    CHECK(worst_lin < 1e-9, "round trip position error %.2e mm < 1e-9 mm", worst_lin);
    CHECK(worst_ang < 1e-9, "round trip angle error %.2e deg < 1e-9 deg", worst_ang);
    printf("# FK from HOME iterations: max %d; histogram:", maxit);
    for (n = 1; n <= maxit && n <= 30; n++)
        printf(" %d:%d", n, hist[n]);
    printf("\n");
    CHECK(maxit <= 10, "FK from HOME needs at most 10 iterations (max %d)", maxit);
}

/* The finest tolerance allowed (HG_FK_TOLERANCE_MIN_M) is one double
 * precision reaches: the solve from HOME converges at it for every random
 * reachable pose; half of it is refused by the check. */
static void test_fk_tolerance_floor(const hg_params *p)
{
    const hg_fk_options finest = {HG_FK_ITERATION_CAP, HG_FK_TOLERANCE_MIN_M};
    hg_fk_options half = finest;
    int n, done = 0, fails = 0, maxit = 0;
    for (n = 0; n < 10000; n++) {
        double pose[6], z[6], fk[6] = {0, 0, 0, 0, 0, 0};
        int it = 0;
        if (!random_pose(&p->geo, pose, z))
            continue;
        done++;
        if (hg_forward_solve(&p->geo, z, fk, &finest, &it, 0))
            fails++;
        else if (it > maxit)
            maxit = it;
    }
    CHECK(done == 10000 && fails == 0, "tolerance %g m (the finest allowed): the solve from HOME converged for "
          "all %d random reachable poses (%d failures, at most %d iterations)", HG_FK_TOLERANCE_MIN_M, done, fails,
          maxit);
    half.tolerance_m = HG_FK_TOLERANCE_MIN_M / 2;
    CHECK(hg_fk_options_check(&finest, 0, 0) == HG_OK && hg_fk_options_check(&half, 0, 0) == HG_ERR_BAD_PARAM,
          "the check takes %g m and refuses half of it", HG_FK_TOLERANCE_MIN_M);
}

static void test_far_poses_from_home(const hg_params *p)
{
    /* corners of the working volume, from HOME as the guess */
    static const double corners[][6] = {
        {0.12, 0.12, 0.2, 20, 20, 25}, {-0.12, 0.1, -0.2, -20, 15, -25},
        {0.1, -0.12, 0.15, 15, -20, 10}, {0, 0, 0.22, 0, 0, 0}, {0, 0, -0.22, 0, 0, 0},
        {0, 0, 0, 0, 0, 45}, {0.05, 0.05, 0, 25, 25, 0},
    };
    unsigned n;
    for (n = 0; n < sizeof corners / sizeof corners[0]; n++) {
        double pose[6], z[6], fk[6] = {0, 0, 0, 0, 0, 0}, err = 0;
        hg_fk_report rep;
        int k, rc;
        for (k = 0; k < 6; k++)
            pose[k] = corners[n][k] * (k < 3 ? 1.0 : DEG);
        rc = hg_inverse_kinematics(&p->geo, pose, z);
        CHECK(rc == HG_OK, "IK of far pose %u", n);
        if (rc)
            continue;
        rc = hg_forward_kinematics(&p->geo, z, fk, 0, &rep);
        for (k = 0; k < 6; k++)
            if (fabs(fk[k] - pose[k]) > err)
                err = fabs(fk[k] - pose[k]);
        CHECK(rc == HG_OK && err < 1e-12,
              "FK from HOME to far pose %u (%.2f %.2f %.2f m, %.0f %.0f %.0f deg): %d iterations, err %.1e",
              n, corners[n][0], corners[n][1], corners[n][2], corners[n][3], corners[n][4],
              corners[n][5], rep.iterations, err);
    }
}

/* Rotate v by -angle about axis 0 (x), 1 (y) or 2 (z). */
static void unrotate(double v[3], int axis, double angle)
{
    int i = (axis + 1) % 3, j = (axis + 2) % 3;
    double c = cos(angle), s = sin(angle), t = c * v[i] + s * v[j];
    v[j] = -s * v[i] + c * v[j];
    v[i] = t;
}

/* Largest angle (rad) of a bar from its HOME direction: in its carriage
 * joint (world axes) when head is 0, in its head joint (head axes, the bar
 * rotated back by Rz(C), Ry(B), Rx(A) in turn) when head is 1. Carriage
 * joint as in bar_error_independent, head joint from head_joint_world. */
static double joint_angle_independent(const hg_geometry *g, const double z[6], const double pose[6],
                                      int head)
{
    static const double home[6] = {0, 0, 0, 0, 0, 0};
    const double h = sqrt(g->l_m * g->l_m - (g->lb_m - g->lp_m) * (g->lb_m - g->lp_m));
    double worst = 0.0;
    int k, r;
    for (k = 0; k < 6; k++) {
        double alpha = (k / 2 == 0) ? 0.0 : (k / 2 == 1 ? 120.0 * DEG : -120.0 * DEG);
        double s = (k % 2 == 0) ? 1.0 : -1.0;
        double bx = cos(alpha) * g->lb_m - sin(alpha) * s * g->e_m;
        double by = sin(alpha) * g->lb_m + cos(alpha) * s * g->e_m;
        double a[3], a0[3], u[3], u0[3], nu = 0, nu0 = 0, c = 0;
        head_joint_world(g, pose, k, a);
        head_joint_world(g, home, k, a0);
        u[0] = a[0] - bx, u[1] = a[1] - by, u[2] = a[2] - (h + z[k]);
        u0[0] = a0[0] - bx, u0[1] = a0[1] - by, u0[2] = a0[2] - h;
        if (head) {
            unrotate(u, 2, pose[5]);
            unrotate(u, 1, pose[4]);
            unrotate(u, 0, pose[3]);
        }
        for (r = 0; r < 3; r++) {
            nu += u[r] * u[r];
            nu0 += u0[r] * u0[r];
            c += u[r] * u0[r];
        }
        worst = fmax(worst, acos(fmin(1.0, c / sqrt(nu * nu0))));
    }
    return worst;
}

/* Forward kinematics never answers with an assembly the machine cannot
 * take: the crossed assembly a far guess converges to is refused. */
static void test_fk_guard(const hg_params *p)
{
    static const double z[6] = {0, 0, 0, 0, 0, 0};
    hg_params wide = *p;
    hg_fk_report rep;
    double pose[6] = {0, 0, 0, 0, 0, 170 * DEG}, keep[6], ang;
    int rc, k;
    memcpy(keep, pose, sizeof keep);
    rc = hg_forward_kinematics(&p->geo, z, pose, 0, &rep);
    CHECK((rc == HG_ERR_JOINT_RANGE || rc == HG_ERR_BAR_CLEARANCE) && memcmp(pose, keep, sizeof pose) == 0 &&
              rep.guard.kind != HG_GUARD_NONE,
          "joints 0, guess C = 170 deg: refused (%s, code %d), guess untouched", hg_strerror(rc), rc);
    wide.geo.cone_carriage_rad = 1.55;   /* without the ranges: where Newton went */
    wide.geo.cone_head_rad = 3.1;
    wide.geo.d_bar_m = 0.0;           /* there bars 0 and 1 cross: their axes meet */
    rc = hg_forward_kinematics(&wide.geo, z, pose, 0, &rep);
    ang = joint_angle_independent(&p->geo, z, pose, 1);
    CHECK(rc == HG_OK && fabs(fabs(pose[5]) - 180 * DEG) < 1e-6 && ang > p->geo.cone_head_rad,
          "without the joint ranges the same guess converges to the crossed assembly C = %.1f deg, Z = %.1f mm, "
          "with a bar %.1f deg off its HOME direction in its head joint (range %.0f deg)",
          pose[5] / DEG, pose[2] * 1e3, ang / DEG, p->geo.cone_head_rad / DEG);
    for (k = 0; k < 6; k++)
        pose[k] = 0;
    pose[5] = 30 * DEG;
    rc = hg_forward_kinematics(&p->geo, z, pose, 0, &rep);
    CHECK(rc == HG_OK && fabs(pose[5]) < 1e-9, "joints 0, guess C = 30 deg: HOME (%s)", hg_strerror(rc));
}

static void test_jacobian_fd(const hg_params *p)
{
    double worst = 0, worst_z = 0;
    int n;
    for (n = 0; n < 200; n++) {
        double pose[6], z[6], J[36], dz[6];
        int k, m;
        if (!random_pose(&p->geo, pose, z))
            continue;
        hg_constraint_jacobian(&p->geo, z, pose, J, dz);
        for (m = 0; m < 6; m++) {
            double hstep = 1e-6, pp[6], pm[6], fp[6], fm[6];
            memcpy(pp, pose, sizeof pp);
            memcpy(pm, pose, sizeof pm);
            pp[m] += hstep;
            pm[m] -= hstep;
            hg_constraints(&p->geo, z, pp, fp);
            hg_constraints(&p->geo, z, pm, fm);
            for (k = 0; k < 6; k++) {
                double fd = (fp[k] - fm[k]) / (2 * hstep);
                if (fabs(fd - J[6 * k + m]) > worst)
                    worst = fabs(fd - J[6 * k + m]);
            }
        }
        for (k = 0; k < 6; k++) {
            double zp[6], zm[6], fp[6], fm[6], fd;
            memcpy(zp, z, sizeof zp);
            memcpy(zm, z, sizeof zm);
            zp[k] += 1e-6;
            zm[k] -= 1e-6;
            hg_constraints(&p->geo, zp, pose, fp);
            hg_constraints(&p->geo, zm, pose, fm);
            fd = (fp[k] - fm[k]) / 2e-6;
            if (fabs(fd - dz[k]) > worst_z)
                worst_z = fabs(fd - dz[k]);
        }
    }
    CHECK(worst < 1e-8, "analytic dPhi/dpose matches central differences (max diff %.2e)", worst);
    CHECK(worst_z < 1e-8, "analytic dPhi/dz matches central differences (max diff %.2e)", worst_z);
}

static void test_refusals(const hg_params *p)
{
    double z[6] = {0, 0, 0, 0, 0, 0}, guess[6] = {0, 0, 0, 0, 0, 0};
    double far[6] = {0.9, 0, 0, 0, 0, 0}, tilt[6] = {0, 0, 0, 0, 89 * DEG, 0};
    double nan_pose[6] = {NAN, 0, 0, 0, 0, 0}, inf_pose[6] = {0, 0, INFINITY, 0, 0, 0};
    double zbad[6] = {0.9, -0.9, 0.9, -0.9, 0.9, -0.9}, znan[6] = {0, 0, NAN, 0, 0, 0};
    double zsave[6] = {1, 2, 3, 4, 5, 6}, out[6];
    double above[6] = {0, 0, 1.8, 0, 0, 0};
    hg_geometry shortbars = p->geo;
    const char *field = 0, *why = 0;
    int rc;
    memcpy(out, zsave, sizeof out);
    CHECK(hg_inverse_kinematics(&p->geo, far, out) == HG_ERR_UNREACHABLE &&
              memcmp(out, zsave, sizeof out) == 0,
          "IK refuses X = 900 mm as unreachable and leaves joints untouched");
    CHECK(hg_inverse_kinematics(&p->geo, tilt, out) == HG_ERR_EULER_SINGULAR,
          "IK refuses B = 89 deg (Euler singularity)");
    CHECK(hg_inverse_kinematics(&p->geo, nan_pose, out) == HG_ERR_NONFINITE_INPUT &&
              hg_inverse_kinematics(&p->geo, inf_pose, out) == HG_ERR_NONFINITE_INPUT,
          "IK refuses NaN and inf");
    rc = hg_forward_kinematics(&p->geo, zbad, guess, 0, 0);
    CHECK(rc < 0 && guess[0] == 0.0, "FK refuses joints +-900 mm (code %d: %s), guess untouched", rc,
          hg_strerror(rc));
    CHECK(hg_forward_kinematics(&p->geo, znan, guess, 0, 0) == HG_ERR_NONFINITE_INPUT,
          "FK refuses NaN joints");
    rc = hg_forward_kinematics(&p->geo, z, above, 0, 0);
    CHECK(rc == HG_ERR_WRONG_BRANCH, "FK started with the head above the carriages lands on the "
          "other branch and says so (code %d)", rc);
    {
        hg_fk_options o;
        double zfar[6], pose[6] = {0.12, 0.1, 0.2, 20 * DEG, 20 * DEG, 25 * DEG}, g0[6] = {0};
        hg_fk_report rep;
        hg_fk_options_default(&o);
        o.max_iterations = HG_FK_ITERATION_MIN;
        hg_inverse_kinematics(&p->geo, pose, zfar);
        rc = hg_forward_kinematics(&p->geo, zfar, g0, &o, &rep);
        CHECK(rc == HG_ERR_NO_CONVERGENCE && rep.iterations == HG_FK_ITERATION_MIN,
              "FK limited to %d iterations from HOME to a far pose reports no convergence (code %d)",
              HG_FK_ITERATION_MIN, rc);
        o.max_iterations = HG_FK_ITERATION_MIN - 1;
        CHECK(hg_fk_options_check(&o, &field, &why) == HG_ERR_BAD_PARAM && strcmp(field, "max_iterations") == 0,
              "max_iterations %d refused (%s)", o.max_iterations, why ? why : "");
        {   /* the bound's reason: following a move at 200 mm/s (0.2 mm a 1 ms period) from the last pose,
             * HG_FK_ITERATION_MIN iterations converge at the default tolerance and one fewer does not */
            double z1[6], p1[6] = {0}, moved[6] = {0.0002, 0.0, 0.0, 0.0, 0.0, 0.0};
            int it = 0;
            hg_fk_options_default(&o);
            hg_inverse_kinematics(&p->geo, moved, z1);
            rc = hg_forward_solve(&p->geo, z1, p1, &o, &it, 0);   /* from HOME, the last period's pose */
            CHECK(rc == HG_OK && it == HG_FK_ITERATION_MIN, "from the last period's pose, a 0.2 mm move converges "
                  "in %d iterations at the default tolerance (%d, code %d)", HG_FK_ITERATION_MIN, it, rc);
        }
    }
    shortbars.l_m = 0.3;
    CHECK(hg_geometry_check(&shortbars, &field, &why) == HG_ERR_BAD_PARAM && strcmp(field, "l") == 0,
          "geometry with bars too short is refused naming 'l' (%s)", why ? why : "");
    CHECK(hg_geometry_check(&p->geo, &field, &why) == HG_OK, "spec geometry passes the check");
    {   /* a kinematics module's geometry, set in HAL units: checked once per change, what was set named */
        hg_geometry_setting s;
        hg_params d;
        double hal[HG_PARAMS_MAX] = {0};
        int n, i, set, said[6], lb = -1, l = -1;
        const hg_param_info *t = hg_params_table(&n);
        hg_params_default(&d);
        for (i = 0; i < n; i++) {
            hal[i] = hg_params_get(&d, i) * t[i].hal_scale;
            lb = strcmp(t[i].name, "lb") == 0 ? i : lb;
            l = strcmp(t[i].name, "l") == 0 ? i : l;
        }
        hg_geometry_setting_init(&s);
        said[0] = hg_geometry_take(&s, hal, &field, &why, &set);
        CHECK(said[0] == 0 && s.rc == HG_OK && memcmp(&s.geo, &d.geo, sizeof d.geo) == 0 &&
                  s.fingerprint == hg_geometry_fingerprint(&d.geo),
              "the defaults in HAL units give the spec geometry in SI, bit for bit, and pass");
        hal[lb] = 4.0 * hg_params_get(&d, l) * t[lb].hal_scale;   /* lb - lp > l: rule "l > lb - lp" */
        said[1] = hg_geometry_take(&s, hal, &field, &why, &set);
        CHECK(said[1] == 1 && strcmp(field, "l") == 0 && set == lb && s.rc == HG_ERR_BAD_PARAM,
              "lb set 4 l: refused on l's rule (%s), naming lb as what was set", why);
        said[2] = hg_geometry_take(&s, hal, &field, &why, &set);
        CHECK(said[2] == 0 && s.rc == HG_ERR_BAD_PARAM, "unchanged: still refused, not said again");
        hal[lb] = NAN;
        said[3] = hg_geometry_take(&s, hal, &field, &why, &set);
        CHECK(said[3] == 1 && strcmp(field, "lb") == 0 && set == -1 && s.rc == HG_ERR_BAD_PARAM,
              "lb NaN: refused on lb's own rule (%s; nothing more to name)", why);
        said[4] = hg_geometry_take(&s, hal, &field, &why, &set);
        CHECK(said[4] == 0 && s.rc == HG_ERR_BAD_PARAM, "a NaN kept is no change: not said again");
        hal[lb] = hg_params_get(&d, lb) * t[lb].hal_scale;
        said[5] = hg_geometry_take(&s, hal, &field, &why, &set);
        CHECK(said[5] == 0 && s.rc == HG_OK && memcmp(&s.geo, &d.geo, sizeof d.geo) == 0,
              "lb back to its default: taken, the spec geometry again");
    }
    /* singular Jacobian: all head joints on the machine axis (lp = e = 0)
     * leaves the rotation about z undetermined */
    {
        hg_geometry sing = p->geo;
        double g1[6] = {0, 0, 0, 0, 0, 0};
        sing.lp_m = 1e-300;
        sing.e_m = 0.0;
        rc = hg_forward_kinematics(&sing, z, g1, 0, 0);
        CHECK(rc == HG_ERR_SINGULAR_JACOBIAN, "FK with a degenerate head (all joints at Op) reports a "
              "singular Jacobian (code %d)", rc);
    }
}

/* The geometry fingerprint: equal for an equal geometry, different when
 * any of its seven fields moves by one ulp; a mismatch with the board is
 * reported once, on its HG_GEOMETRY_MISMATCH_CALLS-th consecutive call,
 * again after a match, and never for an unconnected board (0). */
static void test_geometry_mismatch(const hg_params *p)
{
    double *f[7];
    hg_geometry g = p->geo, h = p->geo;
    unsigned own = hg_geometry_fingerprint(&g);
    int i, calls = 0, said = 0, first = -1;
    f[0] = &h.l_m; f[1] = &h.lb_m; f[2] = &h.e_m; f[3] = &h.lp_m;
    f[4] = &h.cone_carriage_rad; f[5] = &h.cone_head_rad; f[6] = &h.d_bar_m;
    CHECK(own != 0 && own == hg_geometry_fingerprint(&h), "an equal geometry has the same fingerprint (never 0)");
    for (i = 0; i < 7; i++) {
        double keep = *f[i];
        *f[i] = nextafter(keep, 2.0 * keep);
        said += hg_geometry_fingerprint(&h) != own;
        *f[i] = keep;
    }
    CHECK(said == 7, "one ulp in any of the 7 geometry fields changes the fingerprint (%d of 7)", said);
    said = 0;
    for (i = 0; i < 3 * HG_GEOMETRY_MISMATCH_CALLS; i++)
        if (hg_geometry_mismatch(own + 1u, own, &calls)) {
            said++;
            first = first < 0 ? i + 1 : first;
        }
    CHECK(said == 1 && first == HG_GEOMETRY_MISMATCH_CALLS, "a lasting mismatch is reported once (%d), on call %d "
          "(HG_GEOMETRY_MISMATCH_CALLS %d)", said, first, HG_GEOMETRY_MISMATCH_CALLS);
    said = hg_geometry_mismatch(own, own, &calls);
    for (i = 0; i < HG_GEOMETRY_MISMATCH_CALLS; i++)
        said += hg_geometry_mismatch(own + 1u, own, &calls);
    CHECK(said == 1, "after a match a new lasting mismatch is reported again (%d)", said);
    calls = 0;
    said = 0;
    for (i = 0; i < 3 * HG_GEOMETRY_MISMATCH_CALLS; i++)
        said += hg_geometry_mismatch(0u, own, &calls) + hg_geometry_mismatch(own, own, &calls);
    CHECK(said == 0, "no board connected (0) or a matching one: never reported (%d)", said);
}

/* hg_inverse_kinematics_guarded: the inverse's joints where the guard
 * passes, its refusal (with the bar named) where a joint's cone is
 * exceeded, the inverse's own codes otherwise; z untouched on failure. */
static void test_ik_guarded(const hg_params *p)
{
    const double pose[6] = {0.01, -0.02, 0.03, 0.05, -0.03, 0.07};
    const double spun[6] = {0, 0, 0, 0, 0, 3.14159265358979323846};   /* C = 180 deg */
    const double far[6] = {5.0, 0, 0, 0, 0, 0};
    double z0[6], z1[6], z2[6] = {7, 7, 7, 7, 7, 7};
    hg_guard_report rep;
    int rc0 = hg_inverse_kinematics(&p->geo, pose, z0), rc1 = hg_inverse_kinematics_guarded(&p->geo, pose, z1, &rep);
    CHECK(rc0 == 0 && rc1 == 0 && memcmp(z0, z1, sizeof z0) == 0 && rep.kind == HG_GUARD_NONE,
          "guarded ik of a pose inside the limits = the inverse's joints, bit for bit (%d %d)", rc0, rc1);
    rc0 = hg_inverse_kinematics(&p->geo, spun, z0);
    rc1 = hg_inverse_kinematics_guarded(&p->geo, spun, z2, &rep);
    CHECK(rc0 == 0 && rc1 == HG_ERR_JOINT_RANGE && rep.kind == HG_GUARD_HEAD_JOINT && rep.bar >= 0 &&
          rep.value > rep.limit && z2[0] == 7.0,
          "C = 180 deg: the inverse has joints (%d), the guarded one refuses it with JOINT_RANGE (%d), bar %d at "
          "%.1f deg in its head joint > %.1f deg, z untouched", rc0, rc1, rep.bar, rep.value * 57.29578,
          rep.limit * 57.29578);
    rc1 = hg_inverse_kinematics_guarded(&p->geo, far, z2, 0);
    CHECK(rc1 == HG_ERR_UNREACHABLE && z2[0] == 7.0, "an unreachable pose: the inverse's code (%d), report 0 taken",
          rc1);
}

/* A kinematics module's session (hexaglidekins): a valid pair is taken, an
 * invalid one keeps the last valid pair and is said once while it stays
 * (NaN included), again after a valid one; the run of failed forward calls
 * is said at its first failure and at the first success after it, and
 * counted, the count wrapping as a HAL u32. */
static void test_fk_session(void)
{
    hg_fk_session s;
    hg_fk_options def;
    const char *field = 0, *why = 0;
    int say, quiet = 1, k;
    hg_fk_options_default(&def);
    hg_fk_session_init(&s);
    CHECK(s.in_force.max_iterations == def.max_iterations && s.in_force.tolerance_m == def.tolerance_m &&
              !s.failing && s.fail_count == 0,
          "session starts with the default settings (%d, %g m), nothing failed", s.in_force.max_iterations,
          s.in_force.tolerance_m);
    CHECK(hg_fk_session_settings(&s, def.max_iterations, def.tolerance_m, 0, 0) == HG_FK_SAY_NOTHING,
          "the defaults as pins: nothing to say");
    CHECK(hg_fk_session_settings(&s, 12, 1e-10, 0, 0) == HG_FK_SAY_NOTHING && s.in_force.max_iterations == 12 &&
              s.in_force.tolerance_m == 1e-10,
          "a valid pair (12, 1e-10 m) is taken");
    say = hg_fk_session_settings(&s, 0, 1e-10, &field, &why);
    CHECK(say == HG_FK_SAY_REFUSED && field && strcmp(field, "max_iterations") == 0 && why &&
              s.in_force.max_iterations == 12,
          "0 iterations refused naming max_iterations (%s), 12 kept", why ? why : "");
    for (k = 0; k < 5; k++)
        quiet &= hg_fk_session_settings(&s, 0, 1e-10, 0, 0) == HG_FK_SAY_NOTHING;
    CHECK(quiet && s.in_force.max_iterations == 12, "the same refused pair is said once, not every call");
    say = hg_fk_session_settings(&s, 12, NAN, &field, &why);
    CHECK(say == HG_FK_SAY_REFUSED && strcmp(field, "tolerance") == 0 && s.in_force.tolerance_m == 1e-10,
          "a NaN tolerance: a new pair, refused naming tolerance, 1e-10 m kept");
    CHECK(hg_fk_session_settings(&s, 12, NAN, 0, 0) == HG_FK_SAY_NOTHING, "the NaN pair again: said already");
    CHECK(hg_fk_session_settings(&s, 12, HG_FK_TOLERANCE_MAX_M * 2, 0, 0) == HG_FK_SAY_REFUSED &&
              hg_fk_session_settings(&s, HG_FK_ITERATION_CAP + 1, 1e-10, 0, 0) == HG_FK_SAY_REFUSED,
          "tolerance 2e-6 m and %d iterations refused", HG_FK_ITERATION_CAP + 1);
    CHECK(hg_fk_session_settings(&s, HG_FK_ITERATION_CAP, HG_FK_TOLERANCE_MAX_M, 0, 0) == HG_FK_SAY_NOTHING &&
              s.in_force.max_iterations == HG_FK_ITERATION_CAP && s.in_force.tolerance_m == HG_FK_TOLERANCE_MAX_M,
          "the bounds themselves are valid");
    CHECK(hg_fk_session_settings(&s, 0, 1e-10, 0, 0) == HG_FK_SAY_REFUSED,
          "a pair refused before is said again after a valid one");
    /* the run of failures */
    CHECK(hg_fk_session_result(&s, 0) == HG_FK_SAY_NOTHING && s.fail_count == 0, "a success: nothing to say");
    CHECK(hg_fk_session_result(&s, HG_ERR_NO_CONVERGENCE) == HG_FK_SAY_FAILING && s.failing && s.fail_count == 1,
          "the first failure of a run is said");
    CHECK(hg_fk_session_result(&s, HG_ERR_UNREACHABLE) == HG_FK_SAY_FAILS_OTHERWISE && s.fail_count == 2,
          "another code in the same run is said (once)");
    quiet = 1;
    for (k = 0; k < 8; k++)
        quiet &= hg_fk_session_result(&s, k % 2 ? HG_ERR_NO_CONVERGENCE : HG_ERR_UNREACHABLE) == HG_FK_SAY_NOTHING;
    CHECK(quiet && s.fail_count == 10, "the rest of the run, alternating the two codes, is counted, not said (%u "
          "failures)", s.fail_count);
    CHECK(hg_fk_session_result(&s, HG_ERR_NONFINITE_INPUT) == HG_FK_SAY_FAILS_OTHERWISE &&
              hg_fk_session_result(&s, HG_ERR_NONFINITE_INPUT) == HG_FK_SAY_NOTHING && s.fail_count == 12,
          "a third code (NaN joints) said once");
    s.fail_count = 10;
    CHECK(hg_fk_session_result(&s, 0) == HG_FK_SAY_SOLVES_AGAIN && !s.failing, "the first success after it is said");
    CHECK(hg_fk_session_result(&s, 0) == HG_FK_SAY_NOTHING, "the next success: nothing");
    CHECK(hg_fk_session_result(&s, HG_ERR_UNREACHABLE) == HG_FK_SAY_FAILING && s.fail_count == 11,
          "a new run is said again");
    s.fail_count = 0xffffffffu;
    hg_fk_session_result(&s, HG_ERR_UNREACHABLE);
    CHECK(s.fail_count == 0, "the count wraps as a HAL u32 does");
}

/* A kinematics module's forward call with its session (hexaglidekins):
 * what LinuxCNC's motion does around it. Motion passes its last position as
 * the guess and, after a failed call, its world home (HOME) instead; it
 * shows what the call leaves in the pose either way. The answer is checked
 * against the joints by the second formulation of the bars; a struck
 * machine's joints (beyond a carriage joint's 25 deg: X = 420 mm) are
 * refused by the guard, and the pose then held is the last one solved,
 * never the guess (HOME is 420 mm from the machine). */
static void test_fk_session_solve(const hg_params *p)
{
    hg_fk_session s;
    hg_fk_report rep;
    const double near_strike[6] = {0.37, 0.0, 0.0, 0, 0, 0}, struck[6] = {0.42, 0.0, 0.0, 0, 0, 0};
    const double corner[6] = {-0.09, 0.09, -0.08, 8 * DEG, -8 * DEG, 15 * DEG};
    double z1[6], z2[6], zc[6], pose[6], zero[6] = {0, 0, 0, 0, 0, 0}, d = 0;
    int k, rc, same;
    hg_fk_session_init(&s);
    hg_inverse_kinematics(&p->geo, near_strike, z1);
    hg_inverse_kinematics(&p->geo, struck, z2);
    CHECK(hg_inverse_kinematics_guarded(&p->geo, near_strike, z1, 0) == HG_OK &&
              hg_inverse_kinematics_guarded(&p->geo, struck, z2, 0) == HG_ERR_JOINT_RANGE,
          "X = 370 mm is within the joints' ranges, X = 420 mm is not (the test's premise)");
    /* no pose solved yet: a failure leaves the guess */
    memcpy(pose, zero, sizeof pose);
    rc = hg_fk_session_solve(&s, &p->geo, z2, pose, &rep);
    CHECK(rc == HG_ERR_JOINT_RANGE && memcmp(pose, zero, sizeof pose) == 0 && !s.have_last,
          "nothing solved yet: a refused call leaves the guess (code %d)", rc);
    memcpy(pose, zero, sizeof pose);
    rc = hg_fk_session_solve(&s, &p->geo, z1, pose, &rep);
    CHECK(rc == HG_OK && bar_error_independent(&p->geo, z1, pose) < 1e-12 && fabs(pose[0] - 0.37) < 1e-12 &&
              s.have_last,
          "solved from HOME: X = %.9f m, bar error %.1e m", pose[0], bar_error_independent(&p->geo, z1, pose));
    /* the strike: guess = the last position, then HOME as motion passes it */
    rc = hg_fk_session_solve(&s, &p->geo, z2, pose, &rep);
    same = fabs(pose[0] - 0.37) < 1e-12;
    memcpy(pose, zero, sizeof pose);
    rc = rc == HG_ERR_JOINT_RANGE ? hg_fk_session_solve(&s, &p->geo, z2, pose, &rep) : rc;
    CHECK(rc == HG_ERR_JOINT_RANGE && same && fabs(pose[0] - 0.37) < 1e-12 && pose[1] == s.last_pose[1],
          "struck joints refused (code %d); the pose held is the last solved (X = %.3f m), also when the "
          "guess is HOME", rc, pose[0]);
    memcpy(pose, zero, sizeof pose);
    hg_fk_session_hold(&s, pose);
    CHECK(fabs(pose[0] - 0.37) < 1e-12, "a call refused before the solve holds the last solved pose too");
    /* the retry from the last pose: 4 iterations do not reach the corner
     * from HOME, but do from the last pose 0.01 mm away */
    hg_fk_session_settings(&s, 4, s.in_force.tolerance_m, 0, 0);
    hg_inverse_kinematics(&p->geo, corner, zc);
    memcpy(pose, corner, sizeof pose);
    rc = hg_fk_session_solve(&s, &p->geo, zc, pose, &rep);
    for (k = 0; k < 6; k++)
        zc[k] += 1e-5;
    memcpy(pose, zero, sizeof pose);
    CHECK(rc == HG_OK && hg_forward_kinematics(&p->geo, zc, pose, &s.in_force, 0) == HG_ERR_NO_CONVERGENCE,
          "premise: 4 iterations from HOME do not reach the corner (X-90 Y90 Z-80 A8 B-8 C15)");
    memcpy(pose, zero, sizeof pose);
    rc = hg_fk_session_solve(&s, &p->geo, zc, pose, &rep);
    for (k = 0; k < 3; k++)
        d = fmax(d, fabs(pose[k] - corner[k]));
    CHECK(rc == HG_OK && bar_error_independent(&p->geo, zc, pose) < 1e-12 && d < 2e-5 && rep.iterations <= 4,
          "with HOME as the guess the session solves from its last pose (%d iterations, bar error %.1e m, "
          "%.1e m from the corner)", rep.iterations, bar_error_independent(&p->geo, zc, pose), d);
}

/* Machine units (hexaglidekins.mm-per-unit): the range and the refusals
 * said once; 25.4 turns inches into the metres of the same length (an inch
 * is 0.0254 m by definition); 1 rounds exactly as the plain mm conversion
 * hg_pose_from_user / a division by 1000 did (an mm machine's numbers are
 * unchanged to the bit). */
static void test_machine_units(void)
{
    hg_units_setting u;
    const double in[6] = {0.4, -0.2, -0.8, 3.0, -2.0, 5.0};
    const double joints[6] = {-0.49, -0.56, -1.16, -0.64, -1.10, -0.91};
    double pose[6], back[6], z[6], jb[6], ref[6], worst = 0.0;
    const double bad[] = {0.0, -25.4, NAN, INFINITY, -INFINITY, 1e6, 1e-4, 1000.0001};
    int k, same = 1, refused = 1;
    CHECK(hg_mm_per_unit_check(1.0) == HG_OK && hg_mm_per_unit_check(25.4) == HG_OK &&
              hg_mm_per_unit_check(HG_MM_PER_UNIT_MIN) == HG_OK && hg_mm_per_unit_check(HG_MM_PER_UNIT_MAX) == HG_OK,
          "mm-per-unit 1, 25.4 and the bounds 0.001, 1000 are valid");
    for (k = 0; k < (int)(sizeof bad / sizeof bad[0]); k++)
        refused &= hg_mm_per_unit_check(bad[k]) == HG_ERR_BAD_PARAM;
    CHECK(refused, "0, -25.4, NaN, +-inf, 1e6, 1e-4, 1000.0001 are refused");
    hg_units_init(&u);
    CHECK(u.in_force == 1.0, "the default is 1 (mm)");
    CHECK(hg_units_take(&u, 25.4) == HG_FK_SAY_NOTHING && u.in_force == 25.4, "25.4 taken");
    CHECK(hg_units_take(&u, NAN) == HG_FK_SAY_REFUSED && u.in_force == 25.4, "NaN refused, 25.4 kept");
    CHECK(hg_units_take(&u, NAN) == HG_FK_SAY_NOTHING && u.in_force == 25.4, "NaN again: said already");
    CHECK(hg_units_take(&u, 0.0) == HG_FK_SAY_REFUSED && u.in_force == 25.4, "0 refused (a new value), 25.4 kept");
    CHECK(hg_units_take(&u, 25.4) == HG_FK_SAY_NOTHING && hg_units_take(&u, 0.0) == HG_FK_SAY_REFUSED,
          "after a valid value the same refusal is said again");
    hg_pose_from_machine(in, 25.4, pose);
    for (k = 0; k < 3; k++)
        worst = fmax(worst, fabs(pose[k] - in[k] * 0.0254));
    CHECK(worst < 1e-17, "inch pose -> m: X Y Z times 0.0254 (worst %.1e m)", worst);
    CHECK(fabs(pose[3] - 3.0 * DEG) < 1e-16 && fabs(pose[5] - 5.0 * DEG) < 1e-16, "A B C stay degrees, whatever the unit");
    hg_pose_to_machine(pose, 25.4, back);
    worst = 0.0;
    for (k = 0; k < 6; k++)
        worst = fmax(worst, fabs(back[k] - in[k]));
    CHECK(worst < 1e-15, "inch pose round trip (worst %.1e)", worst);
    hg_joints_from_machine(joints, 25.4, z);
    hg_joints_to_machine(z, 25.4, jb);
    worst = 0.0;
    for (k = 0; k < 6; k++)
        worst = fmax(worst, fmax(fabs(z[k] - joints[k] * 0.0254), fabs(jb[k] - joints[k])));
    CHECK(worst < 1e-15, "inch joints -> m (times 0.0254) and back (worst %.1e)", worst);
    hg_pose_from_machine(in, 1.0, pose);
    hg_pose_from_user(in, ref);
    hg_joints_from_machine(joints, 1.0, z);
    for (k = 0; k < 6; k++)
        same &= memcmp(&pose[k], &ref[k], sizeof ref[k]) == 0 && z[k] == joints[k] / 1000.0;
    hg_pose_to_machine(ref, 1.0, pose);
    hg_pose_to_user(ref, back);
    hg_joints_to_machine(z, 1.0, jb);
    for (k = 0; k < 6; k++)
        same &= memcmp(&pose[k], &back[k], sizeof back[k]) == 0 && jb[k] == z[k] * 1000.0;
    CHECK(same, "mm-per-unit 1: bit-identical to the mm conversions (hg_pose_from_user, x / 1000)");
}

/* RTCP (hg_pose_offset_to_op): a tool d long, along the head's -z axis,
 * ends at the programmed tip P - d z (what LinuxCNC's G43 handed the
 * kinematics) at any tilt. Independent of the code's R: the head's axis
 * R z = Rz(C) Ry(B) Rx(A) (0 0 1) written out here. */
static void test_tool_offset(const hg_params *p)
{
    const double d = 0.09, bad[] = {NAN, INFINITY, -INFINITY, 1e300};
    double worst_tip = 0.0, worst_len = 0.0, worst_back = 0.0;
    int n, k, same = 1, refused = 1;
    for (n = 0; n < 200; n++) {
        double c[6], op[6], back[6], tip[3], axis[3], len = 0.0;
        double dd = n % 2 ? d : -0.03;                       /* a negative offset too */
        c[0] = hg_test_uniform(-0.1, 0.1); c[1] = hg_test_uniform(-0.1, 0.1); c[2] = hg_test_uniform(-0.1, 0.1);
        c[3] = hg_test_uniform(-0.4, 0.4); c[4] = hg_test_uniform(-0.4, 0.4); c[5] = hg_test_uniform(-3.0, 3.0);
        axis[0] = cos(c[5]) * sin(c[4]) * cos(c[3]) + sin(c[5]) * sin(c[3]);
        axis[1] = sin(c[5]) * sin(c[4]) * cos(c[3]) - cos(c[5]) * sin(c[3]);
        axis[2] = cos(c[4]) * cos(c[3]);
        hg_pose_offset_to_op(c, dd, op);
        for (k = 0; k < 3; k++) {
            tip[k] = op[k] - dd * axis[k];                   /* the tool's tip, from Op along -R z */
            worst_tip = fmax(worst_tip, fabs(tip[k] - (c[k] - dd * (k == 2))));
            len += (op[k] - tip[k]) * (op[k] - tip[k]);
        }
        worst_len = fmax(worst_len, fabs(sqrt(len) - fabs(dd)));
        for (k = 3; k < 6; k++)
            same &= op[k] == c[k];
        hg_pose_op_to_offset(op, dd, back);
        for (k = 0; k < 6; k++)
            worst_back = fmax(worst_back, fabs(back[k] - c[k]));
    }
    CHECK(worst_tip < 1e-16, "tool offset at 200 tilts: the tip is the programmed point P - d z (worst %.1e m)",
          worst_tip);
    CHECK(worst_len < 1e-16 && same, "the tool is d long from Op, the angles unchanged (worst %.1e m)", worst_len);
    CHECK(worst_back < 1e-16, "hg_pose_op_to_offset undoes it (worst %.1e m)", worst_back);
    {
        const double c[6] = {0.01, -0.02, 0.03, 0.0, 0.0, 1.2}, z0[6] = {0.01, -0.02, 0.03, 0.3, -0.2, 0.1};
        double op[6], op0[6];
        hg_pose_offset_to_op(c, d, op);                       /* untilted: turned about z only */
        hg_pose_offset_to_op(z0, 0.0, op0);
        for (k = 0; k < 6; k++)
            same &= memcmp(&op[k], &c[k], sizeof op[k]) == 0 && memcmp(&op0[k], &z0[k], sizeof op0[k]) == 0;
        CHECK(same, "an untilted head (any C) or a zero offset: Op is the commanded pose to the bit");
    }
    {
        const double c[6] = {0.01, -0.02, 0.03, 0.1, -0.15, 0.7}, level[6] = {0.01, -0.02, 0.03, 0.0, 0.0, 0.7};
        double tilt = acos(cos(c[3]) * cos(c[4]));           /* the head axis' angle from z */
        double want = 0.05 * 2.0 * sin(tilt / 2.0), got = hg_tool_offset_jump(c, 0.09, 0.04);
        CHECK(fabs(got - want) < 1e-17 && hg_tool_offset_jump(level, 0.0, 0.09) == 0.0,
              "a new offset moves Op by |d' - d| 2 sin(tilt / 2) (%.6e m, expected %.6e), by 0 with the head level",
              got, want);
    }
    {
        hg_tool_offset_setting t;
        const double tilted[6] = {0.0, 0.0, -0.01, 0.0, 0.2, 0.0}, level[6] = {0.0, 0.0, -0.01, 0.0, 0.0, 0.4};
        int said[8];
        hg_tool_offset_init(&t);
        said[0] = hg_tool_offset_take(&t, &p->geo, 0.09, 1);          /* at HOME: level */
        memcpy(t.last_inverse, tilted, sizeof tilted);
        said[1] = hg_tool_offset_take(&t, &p->geo, 0.09, 1);          /* unchanged */
        said[2] = hg_tool_offset_take(&t, &p->geo, 0.0, 1);           /* G49 at B 0.2 rad */
        CHECK(said[0] == HG_FK_SAY_NOTHING && said[1] == HG_FK_SAY_NOTHING && said[2] == HG_FK_SAY_JUMP &&
                  fabs(t.jump_m - 0.09 * 2.0 * sin(0.1)) < 1e-17 && t.in_force_m == 0.0,
              "a new offset is said only where it moves Op (tilted: %.6e m, 0.09 x 2 sin(0.1 rad)), and taken",
              t.jump_m);
        said[3] = hg_tool_offset_take(&t, &p->geo, NAN, 1);
        said[4] = hg_tool_offset_take(&t, &p->geo, NAN, 1);
        CHECK(said[3] == HG_FK_SAY_REFUSED && said[4] == HG_FK_SAY_NOTHING && t.refusing && t.in_force_m == 0.0,
              "NaN refused once while it stays, 0 kept in force");
        memcpy(t.last_inverse, level, sizeof level);
        said[5] = hg_tool_offset_take(&t, &p->geo, 0.05, 1);           /* G43 with the head level (C only) */
        said[6] = hg_tool_offset_take(&t, &p->geo, NAN, 1);
        said[7] = hg_tool_offset_take(&t, &p->geo, 1e300, 1);
        CHECK(said[5] == HG_FK_SAY_NOTHING && said[6] == HG_FK_SAY_REFUSED && said[7] == HG_FK_SAY_REFUSED &&
                  t.in_force_m == 0.05,
              "with the head level a new offset is taken unsaid; a refusal after a valid value is said again");
        memcpy(t.last_inverse, tilted, sizeof tilted);
        said[0] = hg_tool_offset_take(&t, &p->geo, 0.02, 0);         /* G43 tilted, under identity */
        CHECK(said[0] == HG_FK_SAY_NOTHING && t.jump_m == 0.0 && t.in_force_m == 0.02,
              "kinematics that apply no offset (identity): a new offset with the head tilted is taken unsaid");
    }
    CHECK(hg_tool_offset_check(&p->geo, 0.0) == HG_OK && hg_tool_offset_check(&p->geo, -0.2) == HG_OK &&
              hg_tool_offset_check(&p->geo, HG_MAX_ABS_POSITION_BARS * p->geo.l_m) == HG_OK,
          "tool offsets 0, -0.2 m and 100 bar lengths are taken");
    for (k = 0; k < (int)(sizeof bad / sizeof bad[0]); k++)
        refused &= hg_tool_offset_check(&p->geo, bad[k]) == HG_ERR_BAD_PARAM;
    CHECK(refused && hg_tool_offset_check(&p->geo, HG_MAX_ABS_POSITION_BARS * p->geo.l_m * 1.0001) == HG_ERR_BAD_PARAM,
          "NaN, +-inf, 1e300 m and beyond 100 bar lengths are refused");
    {
        double last = 0.0;
        CHECK(hg_say_refused_once(&last, NAN, 0) == HG_FK_SAY_REFUSED &&
                  hg_say_refused_once(&last, NAN, 0) == HG_FK_SAY_NOTHING &&
                  hg_say_refused_once(&last, 0.05, 1) == HG_FK_SAY_NOTHING &&
                  hg_say_refused_once(&last, NAN, 0) == HG_FK_SAY_REFUSED,
              "a refusal is said once while it stays, again after a valid value");
    }
}

/* LinuxCNC's switchable kinematics: types 0 and 1 are taken, any other
 * refused with the type in force kept; coming back to the Hexaglide's from
 * identity (only then) restarts its forward solve from the tracked pose;
 * the coordinates parameter is XYZABC in any case or nothing. */
static void test_kins_switch(void)
{
    hg_kins_switch s;
    const int bad[] = {2, 3, -1, 1000};
    int k, kept = 1;
    hg_kins_switch_init(&s);
    CHECK(s.type == HG_KINS_HEXAGLIDE && !s.restart, "starts with the Hexaglide's kinematics (type 0)");
    CHECK(hg_kins_switch_to(&s, 0) == HG_OK && !s.restart, "type 0 again: no restart");
    CHECK(hg_kins_switch_to(&s, 1) == HG_OK && s.type == HG_KINS_IDENTITY && !s.restart, "type 1: identity");
    for (k = 0; k < 4; k++)
        kept &= hg_kins_switch_to(&s, bad[k]) == HG_ERR_BAD_PARAM && s.type == HG_KINS_IDENTITY;
    CHECK(kept, "types 2, 3, -1, 1000 refused, identity kept");
    CHECK(hg_kins_switch_to(&s, 0) == HG_OK && s.type == HG_KINS_HEXAGLIDE && s.restart == 2,
          "back to type 0 from identity: the next 2 forward calls (motion's commanded and feedback joints) "
          "restart from the tracked pose");
    k = hg_kins_switch_restart(&s);
    k = k * 10 + hg_kins_switch_restart(&s);
    k = k * 10 + hg_kins_switch_restart(&s);
    CHECK(k == 110 && s.restart == 0, "hg_kins_switch_restart: 1, 1, then 0 (%03d)", k);
    {
        const double in[6] = {1, -2, 3.5, 4, -5, 6e-300};
        double out[6] = {9, 9, 9, 9, 9, 9}, bad[6] = {1, 2, NAN, 4, 5, 6};
        CHECK(hg_identity_kinematics(in, out) == HG_OK && memcmp(in, out, sizeof in) == 0,
              "identity: the six values as given");
        CHECK(hg_identity_kinematics(bad, out) == HG_ERR_NONFINITE_INPUT && memcmp(in, out, sizeof in) == 0,
              "identity: a NaN refused, the output untouched");
        bad[2] = -INFINITY;
        CHECK(hg_identity_kinematics(bad, out) == HG_ERR_NONFINITE_INPUT, "identity: -inf refused");
    }
    CHECK(hg_kins_coordinates_ok(0) && hg_kins_coordinates_ok("") && hg_kins_coordinates_ok("XYZABC") &&
              hg_kins_coordinates_ok("xyzabc") && hg_kins_coordinates_ok("XyZaBc"),
          "coordinates: left out, XYZABC in any case");
    CHECK(!hg_kins_coordinates_ok("XYZAB") && !hg_kins_coordinates_ok("XYZABCU") &&
              !hg_kins_coordinates_ok("YXZABC") && !hg_kins_coordinates_ok("XYZ"),
          "coordinates: fewer, more or other letters refused");
}

int main(void)
{
    hg_params p, wide;
    hg_params_default(&p);
    /* Newton's convergence is a property of the bar equations: these two
     * also visit poses beyond the real joints' ranges (which FK refuses) */
    wide = p;
    wide.geo.cone_carriage_rad = 1.5;
    wide.geo.cone_head_rad = 1.1;
    wide.geo.d_bar_m = 1e-3;
    test_home(&p);
    test_rotation_convention();
    test_ik_bar_lengths(&p);
    test_round_trip(&wide);
    test_far_poses_from_home(&wide);
    test_fk_tolerance_floor(&wide);
    test_fk_guard(&p);
    test_jacobian_fd(&p);
    test_refusals(&p);
    test_geometry_mismatch(&p);
    test_ik_guarded(&p);
    test_fk_session();
    test_fk_session_solve(&p);
    test_machine_units();
    test_tool_offset(&p);
    test_kins_switch();
    return hg_test_exit();
}
