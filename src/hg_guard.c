/* hg_guard.c - joint ranges, bar clearances and the broken machine's
 * region (hg_guard.h). */
#include "hg_math.h"
#include "hg_guard.h"
#include "hg_kinematics.h"
#include "hg_errors.h"
#include "hg_linalg.h"
#include "hg_string.h"
#include "hg_units.h"

/* a.b for 3-vectors */
static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Unit direction of every bar at HOME, from carriage joint to head joint. */
static void home_directions(const hg_geometry *g, double u0[6][3])
{
    static const double zero[6] = {0, 0, 0, 0, 0, 0};
    double B[6][3], A[6][3];
    int k, r;
    hg_joint_points(g, zero, zero, B, A);
    for (k = 0; k < 6; k++)
        for (r = 0; r < 3; r++)
            u0[k][r] = (A[k][r] - B[k][r]) / g->l_m;
}

/* Cosines of every bar's angle in its carriage joint (cc) and head joint (ch). */
static void joint_cosines(const hg_geometry *g, const double B[6][3], const double A[6][3],
                          const double pose[6], double cc[6], double ch[6])
{
    double u0[6][3], R[9];
    int k, r;
    home_directions(g, u0);
    hg_rotation(pose[3], pose[4], pose[5], R);
    for (k = 0; k < 6; k++) {
        double u[3], uh[3], n;
        for (r = 0; r < 3; r++)
            u[r] = A[k][r] - B[k][r];
        n = sqrt(dot3(u, u));
        for (r = 0; r < 3; r++)
            u[r] /= n;
        for (r = 0; r < 3; r++)      /* R^T u: the bar in head axes */
            uh[r] = R[r] * u[0] + R[3 + r] * u[1] + R[6 + r] * u[2];
        cc[k] = dot3(u, u0[k]);
        ch[k] = dot3(uh, u0[k]);
    }
}

/* Angle (rad) whose cosine is c, c clamped to [-1, 1]. */
static double angle_of(double c)
{
    return acos(fmax(-1.0, fmin(1.0, c)));
}

void hg_guard_joint_angles(const hg_geometry *g, const double z[6], const double pose[6],
                           double carriage_rad[6], double head_rad[6])
{
    double B[6][3], A[6][3], cc[6], ch[6];
    int k;
    hg_joint_points(g, z, pose, B, A);
    joint_cosines(g, B, A, pose, cc, ch);
    for (k = 0; k < 6; k++) {
        carriage_rad[k] = angle_of(cc[k]);
        head_rad[k] = angle_of(ch[k]);
    }
}

double hg_segment_distance(const double p1[3], const double q1[3], const double p2[3],
                           const double q2[3])
{
    /* closest points p1 + s d1, p2 + t d2 (Ericson, Real-Time Collision
     * Detection, 5.1.9), both segments of nonzero length here */
    double d1[3], d2[3], w[3], a, e, b, c, f, den, s = 0.0, t, dx[3];
    int r;
    for (r = 0; r < 3; r++) {
        d1[r] = q1[r] - p1[r];
        d2[r] = q2[r] - p2[r];
        w[r] = p1[r] - p2[r];
    }
    a = dot3(d1, d1);
    e = dot3(d2, d2);
    b = dot3(d1, d2);
    c = dot3(d1, w);
    f = dot3(d2, w);
    if (!(a > 0.0 && e > 0.0))
        return NAN;
    den = a * e - b * b;
    if (den > 1e-12 * a * e)          /* not parallel: closest points of the lines, s clamped */
        s = fmin(1.0, fmax(0.0, (b * f - c * e) / den));
    t = (b * s + f) / e;
    if (t < 0.0) {
        t = 0.0;
        s = fmin(1.0, fmax(0.0, -c / a));
    } else if (t > 1.0) {
        t = 1.0;
        s = fmin(1.0, fmax(0.0, (b - c) / a));
    }
    for (r = 0; r < 3; r++)
        dx[r] = w[r] + s * d1[r] - t * d2[r];
    return sqrt(dot3(dx, dx));
}

/* Fill r (may be 0) with a finding. */
static void report(hg_guard_report *r, int kind, int bar, int other, double value, double limit)
{
    if (!r)
        return;
    r->kind = kind;
    r->bar = bar;
    r->other = other;
    r->value = value;
    r->limit = limit;
}

/* 0, or OUT_OF_VOLUME when a broken machine's state leaves the modelled region. */
static int region_check(const double z[6], const double pose[6], hg_guard_report *r)
{
    int k;
    if (!(pose[2] >= HG_BROKEN_HEAD_Z_MIN_M)) {
        report(r, HG_GUARD_REGION, -1, 2, pose[2], HG_BROKEN_HEAD_Z_MIN_M);
        return HG_ERR_OUT_OF_VOLUME;
    }
    for (k = 0; k < 2; k++)
        if (!(fabs(pose[k]) <= HG_BROKEN_REACH_M)) {
            report(r, HG_GUARD_REGION, -1, k, pose[k], HG_BROKEN_REACH_M);
            return HG_ERR_OUT_OF_VOLUME;
        }
    for (k = 0; k < 6; k++)
        if (!(fabs(z[k]) <= HG_BROKEN_REACH_M)) {
            report(r, HG_GUARD_REGION, k, -1, z[k], HG_BROKEN_REACH_M);
            return HG_ERR_OUT_OF_VOLUME;
        }
    for (k = 3; k < 6; k++)
        if (!(fabs(pose[k]) <= HG_BROKEN_ROT_MAX_RAD)) {
            report(r, HG_GUARD_REGION, -1, k, pose[k], HG_BROKEN_ROT_MAX_RAD);
            return HG_ERR_OUT_OF_VOLUME;
        }
    return 0;
}

int hg_guard_check(const hg_geometry *g, const double z[6], const double pose[6],
                   unsigned broken, hg_guard_report *r)
{
    const double cos_c = cos(g->cone_carriage_rad), cos_h = cos(g->cone_head_rad);
    double B[6][3], A[6][3], cc[6], ch[6];
    int j, k, rc;
    report(r, HG_GUARD_NONE, -1, -1, 0.0, 0.0);
    if (!(hg_all_finite(6, z) && hg_all_finite(6, pose))) {
        report(r, HG_GUARD_REGION, -1, -1, NAN, 0.0);
        return HG_ERR_OUT_OF_VOLUME;
    }
    if (broken & 0x3fu) {
        rc = region_check(z, pose, r);
        if (rc)
            return rc;
    }
    hg_joint_points(g, z, pose, B, A);
    joint_cosines(g, B, A, pose, cc, ch);
    for (k = 0; k < 6; k++) {
        if (broken & (1u << k))
            continue;
        if (!(cc[k] >= cos_c)) {
            report(r, HG_GUARD_CARRIAGE_JOINT, k, -1, angle_of(cc[k]), g->cone_carriage_rad);
            return HG_ERR_JOINT_RANGE;
        }
        if (!(ch[k] >= cos_h)) {
            report(r, HG_GUARD_HEAD_JOINT, k, -1, angle_of(ch[k]), g->cone_head_rad);
            return HG_ERR_JOINT_RANGE;
        }
    }
    for (j = 0; j < 6; j++)
        for (k = j + 1; k < 6; k++) {
            double dist;
            if ((broken >> j) & 1u || (broken >> k) & 1u)
                continue;
            dist = hg_segment_distance(B[j], A[j], B[k], A[k]);
            if (!(dist >= g->d_bar_m)) {
                report(r, HG_GUARD_BARS, j, k, dist, g->d_bar_m);
                return HG_ERR_BAR_CLEARANCE;
            }
        }
    return 0;
}

double hg_guard_home_clearance(const hg_geometry *g)
{
    static const double zero[6] = {0, 0, 0, 0, 0, 0};
    double B[6][3], A[6][3], best = INFINITY;
    int j, k;
    hg_joint_points(g, zero, zero, B, A);
    for (j = 0; j < 6; j++)
        for (k = j + 1; k < 6; k++)
            best = fmin(best, hg_segment_distance(B[j], A[j], B[k], A[k]));
    return best;
}
