/* hg_guard.c - joint ranges, bar clearances and the broken machine's
 * region (hg_guard.h). */
#include "hg_math.h"
#include "hg_guard.h"
#include "hg_compiler.h"
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

/* Cosines of every bar's angle in its carriage joint (cc) and head joint
 * (ch), R the head's rotation. */
static void joint_cosines(const hg_guard_geo *gg, const double B[6][3], const double A[6][3],
                          const double R[9], double cc[6], double ch[6])
{
    int k, r;
    for (k = 0; k < 6; k++) {
        double u[3], uh[3], n;
        for (r = 0; r < 3; r++)
            u[r] = A[k][r] - B[k][r];
        n = sqrt(dot3(u, u));
        for (r = 0; r < 3; r++)
            u[r] /= n;
        for (r = 0; r < 3; r++)      /* R^T u: the bar in head axes */
            uh[r] = R[r] * u[0] + R[3 + r] * u[1] + R[6 + r] * u[2];
        cc[k] = dot3(u, gg->u0[k]);
        ch[k] = dot3(uh, gg->u0[k]);
    }
}

void hg_guard_prepare(const hg_geometry *g, hg_guard_geo *gg)
{
    int k;
    gg->g = *g;
    hg_frame_of(g, &gg->f);
    gg->cos_carriage = cos(g->cone_carriage_rad);
    gg->cos_head = cos(g->cone_head_rad);
    home_directions(g, gg->u0);
    for (k = 0; k < 6; k++)
        gg->head_r[k] = sqrt(dot3(gg->f.head[k], gg->f.head[k]));
}

/* Angle (rad) whose cosine is c, c clamped to [-1, 1]. */
static double angle_of(double c)
{
    return acos(fmax(-1.0, fmin(1.0, c)));
}

void hg_guard_joint_angles(const hg_geometry *g, const double z[6], const double pose[6],
                           double carriage_rad[6], double head_rad[6])
{
    hg_guard_geo gg;
    double B[6][3], A[6][3], cc[6], ch[6], sc[6], R[9];
    int k;
    hg_guard_prepare(g, &gg);
    hg_head_trig(pose, sc);
    hg_rotation_sc(sc, R);
    hg_joint_points_rot(&gg.f, R, z, pose, B, A);
    joint_cosines(&gg, HG_CONST_ROWS3(B), HG_CONST_ROWS3(A), R, cc, ch);
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

/* Largest displacement of bar k's ends from the memo's reference state (m). */
static double end_moved(const hg_guard_memo *memo, const double B[6][3], const double A[6][3], int k)
{
    double b = 0.0, a = 0.0;
    int r;
    for (r = 0; r < 3; r++) {
        b += (B[k][r] - memo->B[k][r]) * (B[k][r] - memo->B[k][r]);
        a += (A[k][r] - memo->A[k][r]) * (A[k][r] - memo->A[k][r]);
    }
    return sqrt(b > a ? b : a);
}

/* Bar clearances of the joint points B, A, intact bars only: 0 or
 * BAR_CLEARANCE with the first pair (in pair order) closer than d_bar; the
 * memo's bound skips pairs it clears (hg_guard_memo), and the memo takes
 * this state when some pair was measured and none touches. */
static int clearance(const hg_guard_geo *gg, const double z[6], const double pose[6],
                     const double B[6][3], const double A[6][3], unsigned broken,
                     hg_guard_memo *memo, hg_guard_report *r)
{
    const double d_bar = gg->g.d_bar_m, clear = d_bar + HG_GUARD_SLACK_M;
    double moved[6], dist[HG_GUARD_PAIRS], most = 0.0;
    unsigned measured = 0;
    int j, k, p, known = memo && memo->valid;
    for (k = 0; known && k < 6; k++) {
        moved[k] = end_moved(memo, B, A, k);
        most = moved[k] > most ? moved[k] : most;
    }
    if (known && memo->dist_min - 2.0 * most >= clear)
        return 0;                         /* no pair can touch */
    for (j = 0, p = 0; j < 6; j++)
        for (k = j + 1; k < 6; k++, p++) {
            if ((broken >> j) & 1u || (broken >> k) & 1u)
                continue;
            if (known && memo->dist[p] - moved[j] - moved[k] >= clear)
                continue;                 /* cannot touch: not measured */
            dist[p] = hg_segment_distance(B[j], A[j], B[k], A[k]);
            measured |= 1u << p;
            if (!(dist[p] >= d_bar)) {
                report(r, HG_GUARD_BARS, j, k, dist[p], d_bar);
                return HG_ERR_BAR_CLEARANCE;
            }
        }
    if (memo && (!known || measured)) {    /* this state becomes the reference */
        for (j = 0, p = 0; j < 6; j++)
            for (k = j + 1; k < 6; k++, p++)
                if ((broken >> j) & 1u || (broken >> k) & 1u)
                    memo->dist[p] = NAN;
                else
                    memo->dist[p] = (measured >> p) & 1u ? dist[p]
                                    : hg_segment_distance(B[j], A[j], B[k], A[k]);
        memo->dist_min = memo->dist[0];
        for (p = 1; p < HG_GUARD_PAIRS; p++)   /* a NaN (a broken bar's pair) stays: no shortcut */
            if (isnan(memo->dist[p]) || memo->dist[p] < memo->dist_min)
                memo->dist_min = isnan(memo->dist_min) ? memo->dist_min : memo->dist[p];
        memcpy(memo->B, B, sizeof memo->B);
        memcpy(memo->A, A, sizeof memo->A);
        memcpy(memo->z, z, sizeof memo->z);
        memcpy(memo->pose, pose, sizeof memo->pose);
        memo->valid = 1;
        memo->refreshed++;
    }
    return 0;
}

/* How far the head moved from the reference pose ref (hg_guard_memo):
 * *shift the distance of Op (m), returned the bound of its turn (rad). */
static double head_moved(const double pose[6], const double ref[6], double *shift)
{
    const double dx = pose[0] - ref[0], dy = pose[1] - ref[1], dz = pose[2] - ref[2];
    *shift = sqrt(dx * dx + dy * dy + dz * dz);
    return fabs(pose[3] - ref[3]) + fabs(pose[4] - ref[4]) + fabs(pose[5] - ref[5]);
}

/* 1 when the memo's cone reference proves every bar of the state (z,
 * pose) within both of its joints' cones (hg_guard_memo), else 0 (also
 * for a NaN anywhere: every comparison fails). */
static int cones_clear(const hg_guard_geo *gg, const double z[6], const double pose[6],
                       const hg_guard_memo *memo)
{
    const double top_c = gg->g.cone_carriage_rad - HG_GUARD_SLACK_RAD;
    const double top_h = gg->g.cone_head_rad - HG_GUARD_SLACK_RAD;
    double shift, turn;
    int k;
    if (!memo->cones_valid)
        return 0;
    turn = head_moved(pose, memo->cone_pose, &shift);
    for (k = 0; k < 6; k++) {
        const double x = (fabs(z[k] - memo->cone_z[k]) + shift + turn * gg->head_r[k]) / memo->bar_len[k];
        const double alpha = HG_GUARD_ASIN_SLOPE * x;
        if (!(x <= 0.5 && memo->cone_carriage[k] + alpha <= top_c &&
              memo->cone_head[k] + alpha + turn <= top_h))
            return 0;
    }
    return 1;
}

/* 1 when the memo's clearance reference proves every pair of bars of the
 * state (z, pose) apart (hg_guard_memo: its smallest distance against the
 * most any end moved), else 0 (also for a NaN). */
static int pairs_clear(const hg_guard_geo *gg, const double z[6], const double pose[6],
                       const hg_guard_memo *memo)
{
    double shift, turn, most = 0.0;
    int k;
    if (!memo->valid)
        return 0;
    turn = head_moved(pose, memo->pose, &shift);
    for (k = 0; k < 6; k++) {
        const double b = fabs(z[k] - memo->z[k]), a = shift + turn * gg->head_r[k];
        const double m = b > a ? b : a;
        most = m > most ? m : most;
    }
    return memo->dist_min - 2.0 * most >= gg->g.d_bar_m + HG_GUARD_SLACK_M;
}

/* The state (z, pose) with joint points B, A and joint cosines cc, ch
 * becomes the memo's cone reference. */
static void cones_remember(const double z[6], const double pose[6], const double B[6][3],
                           const double A[6][3], const double cc[6], const double ch[6],
                           hg_guard_memo *memo)
{
    int k, r;
    for (k = 0; k < 6; k++) {
        double u[3];
        for (r = 0; r < 3; r++)
            u[r] = A[k][r] - B[k][r];
        memo->bar_len[k] = sqrt(dot3(u, u));
        memo->cone_carriage[k] = angle_of(cc[k]);
        memo->cone_head[k] = angle_of(ch[k]);
    }
    memcpy(memo->cone_z, z, sizeof memo->cone_z);
    memcpy(memo->cone_pose, pose, sizeof memo->cone_pose);
    memo->cones_valid = 1;
}

int hg_guard_check_sc(const hg_guard_geo *gg, const double z[6], const double pose[6],
                      const double sc[6], unsigned broken, hg_guard_memo *memo,
                      hg_guard_report *r)
{
    double B[6][3], A[6][3], cc[6], ch[6], R[9];
    int k, rc, cones_known = 0;
    report(r, HG_GUARD_NONE, -1, -1, 0.0, 0.0);
    if (!(hg_all_finite(6, z) && hg_all_finite(6, pose))) {
        report(r, HG_GUARD_REGION, -1, -1, NAN, 0.0);
        return HG_ERR_OUT_OF_VOLUME;
    }
    if (broken & 0x3fu) {
        rc = region_check(z, pose, r);
        if (rc)
            return rc;
    } else if (memo) {                  /* an intact machine near the memo's references */
        cones_known = cones_clear(gg, z, pose, memo);
        if (cones_known && pairs_clear(gg, z, pose, memo)) {
            memo->cleared++;
            return 0;
        }
    }
    hg_rotation_sc(sc, R);
    hg_joint_points_rot(&gg->f, R, z, pose, B, A);
    joint_cosines(gg, HG_CONST_ROWS3(B), HG_CONST_ROWS3(A), R, cc, ch);
    for (k = 0; k < 6; k++) {
        if (broken & (1u << k))
            continue;
        if (!(cc[k] >= gg->cos_carriage)) {
            report(r, HG_GUARD_CARRIAGE_JOINT, k, -1, angle_of(cc[k]), gg->g.cone_carriage_rad);
            return HG_ERR_JOINT_RANGE;
        }
        if (!(ch[k] >= gg->cos_head)) {
            report(r, HG_GUARD_HEAD_JOINT, k, -1, angle_of(ch[k]), gg->g.cone_head_rad);
            return HG_ERR_JOINT_RANGE;
        }
    }
    if (memo && !(broken & 0x3fu) && !cones_known)
        cones_remember(z, pose, HG_CONST_ROWS3(B), HG_CONST_ROWS3(A), cc, ch, memo);
    return clearance(gg, z, pose, HG_CONST_ROWS3(B), HG_CONST_ROWS3(A), broken, memo, r);
}

int hg_guard_check(const hg_geometry *g, const double z[6], const double pose[6],
                   unsigned broken, hg_guard_report *r)
{
    hg_guard_geo gg;
    double sc[6] = {0, 1, 0, 1, 0, 1};
    hg_guard_prepare(g, &gg);
    if (hg_all_finite(6, pose))       /* else the check refuses the state before using them */
        hg_head_trig(pose, sc);
    return hg_guard_check_sc(&gg, z, pose, sc, broken, 0, r);
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

int hg_inverse_kinematics_guarded(const hg_geometry *g, const double pose[6], double z[6],
                                  hg_guard_report *report)
{
    double out[6];
    int k, rc;
    if (report) {
        report->kind = HG_GUARD_NONE;
        report->bar = report->other = -1;
        report->value = report->limit = 0.0;
    }
    rc = hg_inverse_kinematics(g, pose, out);
    if (rc == HG_OK)                   /* joints exist; can the machine take the pose? */
        rc = hg_guard_check(g, out, pose, 0, report);
    if (rc == HG_OK)
        for (k = 0; k < 6; k++)
            z[k] = out[k];
    return rc;
}

int hg_forward_kinematics(const hg_geometry *g, const double z[6], double pose[6],
                          const hg_fk_options *opt, hg_fk_report *report)
{
    double c[6];
    int k, rc;
    if (report)
        report->guard.kind = HG_GUARD_NONE;
    for (k = 0; k < 6; k++)
        c[k] = pose[k];
    rc = hg_forward_solve(g, z, c, opt, report ? &report->iterations : 0, report ? &report->residual_m : 0);
    if (rc == HG_OK)
        rc = hg_guard_check(g, z, c, 0, report ? &report->guard : 0);
    if (rc == HG_OK)
        for (k = 0; k < 6; k++)
            pose[k] = c[k];
    return rc;
}

void hg_fk_session_hold(const hg_fk_session *s, double pose[6])
{
    int k;
    if (s->have_last)
        for (k = 0; k < 6; k++)
            pose[k] = s->last_pose[k];
}

int hg_fk_session_solve(hg_fk_session *s, const hg_geometry *g, const double z[6], double pose[6],
                        hg_fk_report *report)
{
    int k, rc = hg_forward_kinematics(g, z, pose, &s->in_force, report);
    if (rc != HG_OK && s->have_last) {
        double c[6];
        hg_fk_report again;
        int differs = 0;
        for (k = 0; k < 6; k++) {
            c[k] = s->last_pose[k];
            differs |= (c[k] != pose[k]);
        }
        if (differs && hg_forward_kinematics(g, z, c, &s->in_force, report ? &again : 0) == HG_OK) {
            rc = HG_OK;
            for (k = 0; k < 6; k++)
                pose[k] = c[k];
            if (report)
                *report = again;
        }
    }
    if (rc == HG_OK) {
        for (k = 0; k < 6; k++)
            s->last_pose[k] = pose[k];
        s->have_last = 1;
    } else {
        hg_fk_session_hold(s, pose);
    }
    return rc;
}
