/* test_guard.c - the machine's mechanical limits (hg_guard.h) against a
 * geometry written here: the segment distance by a second method (interior
 * stationary point and the four edge minima of the convex quadratic), the
 * joint angles from the spec's formulas, and the board driven open loop
 * until it strikes: the step at which it faults must be the first step of
 * the simulated path at which this file's own geometry crosses a limit. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_board.h"
#include "hg_plant_hexaglide.h"
#include "hg_guard.h"
#include "hg_dynamics.h"
#include "hg_kinematics.h"
#include "hg_errors.h"

#define DEG (3.14159265358979323846 / 180.0)

/* |a - b|^2 */
static double dist2(const double a[3], const double b[3])
{
    return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

/* f(s, t) = |p1 + s d1 - p2 - t d2|^2 */
static double f_st(const double p1[3], const double q1[3], const double p2[3], const double q2[3],
                   double s, double t)
{
    double a[3], b[3];
    int r;
    for (r = 0; r < 3; r++) {
        a[r] = p1[r] + s * (q1[r] - p1[r]);
        b[r] = p2[r] + t * (q2[r] - p2[r]);
    }
    return dist2(a, b);
}

/* Distance of point x to segment p-q (parameter clamped to [0, 1]). */
static double point_segment2(const double x[3], const double p[3], const double q[3])
{
    double d[3], w[3], u;
    int r;
    for (r = 0; r < 3; r++) {
        d[r] = q[r] - p[r];
        w[r] = x[r] - p[r];
    }
    u = (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    u = u < 0 ? 0 : u > 1 ? 1 : u;
    for (r = 0; r < 3; r++)
        w[r] = p[r] + u * d[r];
    return dist2(x, w);
}

/* Segment distance, second method: the minimum of the convex quadratic f
 * over the unit square is its stationary point when that lies inside, else
 * on an edge, where it is a point-to-segment distance. */
static double segment_distance_ref(const double p1[3], const double q1[3], const double p2[3],
                                   const double q2[3])
{
    double best = point_segment2(p1, p2, q2);
    double a = 0, b = 0, c = 0, d = 0, e = 0, det;
    int r;
    best = fmin(best, point_segment2(q1, p2, q2));
    best = fmin(best, point_segment2(p2, p1, q1));
    best = fmin(best, point_segment2(q2, p1, q1));
    for (r = 0; r < 3; r++) {      /* grad f = 0: [a -b; -b c] [s; t] = [-d; e] */
        double d1 = q1[r] - p1[r], d2 = q2[r] - p2[r], w = p1[r] - p2[r];
        a += d1 * d1;
        b += d1 * d2;
        c += d2 * d2;
        d += d1 * w;
        e += d2 * w;
    }
    det = a * c - b * b;
    if (det > 1e-300) {
        double s = (-d * c + b * e) / det, t = (a * e - b * d) / det;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1)
            best = fmin(best, f_st(p1, q1, p2, q2, s, t));
    }
    return sqrt(best);
}

static void test_segment_distance(void)
{
    double worst = 0;
    int n;
    for (n = 0; n < 20000; n++) {
        double p1[3], q1[3], p2[3], q2[3], a, b;
        int r;
        for (r = 0; r < 3; r++) {
            p1[r] = hg_test_uniform(-1, 1);
            q1[r] = hg_test_uniform(-1, 1);
            p2[r] = hg_test_uniform(-1, 1);
            q2[r] = n % 4 == 0 ? p2[r] + 0.7 * (q1[r] - p1[r]) : hg_test_uniform(-1, 1); /* parallels too */
        }
        a = hg_segment_distance(p1, q1, p2, q2);
        b = segment_distance_ref(p1, q1, p2, q2);
        worst = fmax(worst, fabs(a - b));
    }
    CHECK(worst < 1e-9, "segment distance agrees with the second method on 20000 random pairs "
          "(a quarter parallel): max difference %.2e m", worst);
}

/* The spec's joints: B_k = Rz(alpha_i)(lb, s e, 0) + (0, 0, h + z_k),
 * A_k = P + R Rz(alpha_i)(lp, s e, 0), R = Rz(C) Ry(B) Rx(A). */
static void spec_joints(const hg_geometry *g, const double z[6], const double c[6], int k,
                        double B[3], double A[3])
{
    double al = (k / 2 == 0 ? 0.0 : k / 2 == 1 ? 120.0 : -120.0) * DEG, s = k % 2 ? -1.0 : 1.0;
    double h = sqrt(g->l_m * g->l_m - (g->lb_m - g->lp_m) * (g->lb_m - g->lp_m));
    double v[3] = {cos(al) * g->lp_m - sin(al) * s * g->e_m, sin(al) * g->lp_m + cos(al) * s * g->e_m, 0};
    double ca = cos(c[3]), sa = sin(c[3]), cb = cos(c[4]), sb = sin(c[4]), cc = cos(c[5]), sc = sin(c[5]);
    double x1[3], x2[3];
    B[0] = cos(al) * g->lb_m - sin(al) * s * g->e_m;
    B[1] = sin(al) * g->lb_m + cos(al) * s * g->e_m;
    B[2] = h + z[k];
    x1[0] = v[0], x1[1] = ca * v[1] - sa * v[2], x1[2] = sa * v[1] + ca * v[2];     /* Rx */
    x2[0] = cb * x1[0] + sb * x1[2], x2[1] = x1[1], x2[2] = -sb * x1[0] + cb * x1[2]; /* Ry */
    A[0] = c[0] + cc * x2[0] - sc * x2[1];                                             /* Rz */
    A[1] = c[1] + sc * x2[0] + cc * x2[1];
    A[2] = c[2] + x2[2];
}

/* Largest joint angle over bars (rad, world for the carriage joint, head
 * axes R^T u for the head joint) and the smallest bar-axis distance (m). */
static void spec_limits(const hg_geometry *g, const double z[6], const double c[6], double *carriage,
                        double *head, double *clearance)
{
    static const double zero[6] = {0, 0, 0, 0, 0, 0};
    double ca = cos(c[3]), sa = sin(c[3]), cb = cos(c[4]), sb = sin(c[4]), cc = cos(c[5]), sc = sin(c[5]);
    double R[9] = {cc * cb, cc * sb * sa - sc * ca, cc * sb * ca + sc * sa,
                   sc * cb, sc * sb * sa + cc * ca, sc * sb * ca - cc * sa,
                   -sb, cb * sa, cb * ca};
    double B[6][3], A[6][3];
    int k, j, r;
    *carriage = *head = 0;
    *clearance = INFINITY;
    for (k = 0; k < 6; k++) {
        double B0[3], A0[3], u[3], u0[3], uh[3], n = 0, n0 = 0, dc = 0, dh = 0;
        spec_joints(g, z, c, k, B[k], A[k]);
        spec_joints(g, zero, zero, k, B0, A0);
        for (r = 0; r < 3; r++) {
            u[r] = A[k][r] - B[k][r];
            u0[r] = A0[r] - B0[r];
        }
        for (r = 0; r < 3; r++)
            uh[r] = R[r] * u[0] + R[3 + r] * u[1] + R[6 + r] * u[2];
        for (r = 0; r < 3; r++) {
            n += u[r] * u[r];
            n0 += u0[r] * u0[r];
            dc += u[r] * u0[r];
            dh += uh[r] * u0[r];
        }
        *carriage = fmax(*carriage, acos(fmin(1.0, dc / sqrt(n * n0))));
        *head = fmax(*head, acos(fmin(1.0, dh / sqrt(n * n0))));
    }
    for (j = 0; j < 6; j++)
        for (k = j + 1; k < 6; k++)
            *clearance = fmin(*clearance, segment_distance_ref(B[j], A[j], B[k], A[k]));
}

static void test_home_and_defaults(void)
{
    static const double zero[6] = {0, 0, 0, 0, 0, 0};
    hg_params p;
    double cj, hj, cl;
    hg_params_default(&p);
    spec_limits(&p.geo, zero, zero, &cj, &hj, &cl);
    CHECK(hg_guard_check(&p.geo, zero, zero, 0, 0) == 0 && cj < 1e-7 && hj < 1e-7 &&
              fabs(hg_guard_home_clearance(&p.geo) - cl) < 1e-12,
          "HOME is inside every limit; closest bar axes at HOME %.3f mm (second method %.3f mm)",
          hg_guard_home_clearance(&p.geo) * 1e3, cl * 1e3);
}

/* Open loop, the volts of issue 16 held: the board must fault at the first
 * step whose state (this file's geometry) crosses a limit, freeze the
 * state before it and name the limit; the head never tilts 60 deg. */
static void test_open_loop_strike(const double volts[6], const char *what)
{
    static hg_board b;
    hg_board_inputs in;
    hg_board_outputs out;
    double cj = 0, hj = 0, cl = 0, prev_t = 0, tilt = 0;
    long s, crossing = -1, fault_at = -1;
    int k;
    const hg_geometry *g;
    hg_board_init(&b, 0, HG_MODEL_REDUCED_CARTESIAN, 0);
    g = &hg_hexaglide_model(&b.m)->p.geo;
    hg_board_inputs_default(&b, &in);
    in.dout_values = 1u << 7;
    for (k = 0; k < 6; k++)
        in.dac_v[k] = volts[k];
    for (s = 0; s < 10000; s++) {
        hg_board_step(&b, &in, &out, 1000000L);
        if (out.fault) {
            fault_at = s;
            break;
        }
        prev_t = out.sim_time_s;
        tilt = fmax(tilt, acos(cos(out.extra[3]) * cos(out.extra[4])));
        spec_limits(g, out.pos, out.extra, &cj, &hj, &cl);   /* extra[0..5]: the head pose */
        if (crossing < 0 && (cj > g->cone_carriage_rad || hj > g->cone_head_rad || cl < g->d_bar_m))
            crossing = s;
    }
    /* the state frozen at the fault is the last one inside; step it once more
     * with hg_step alone and this file's geometry must find it outside */
    {
        hg_data d = *hg_hexaglide_data(&b.d);
        hg_model m = *hg_hexaglide_model(&b.m);
        double v[6];
        int rc;
        for (k = 0; k < 6; k++)
            v[k] = out.fault ? hg_dac_output(volts[k]) : 0;
        rc = hg_step(&m, &d, v, 1e-3);
        memcpy(&d, hg_hexaglide_data(&b.d), HG_DATA_STATE_BYTES);
        d.broken_bars = 0;
        /* hg_step refused it; integrate with the limits opened to see where it would be */
        m.p.geo.cone_carriage_rad = m.p.geo.cone_head_rad = 3.1;
        m.p.geo.d_bar_m = 0;
        hg_guard_prepare(&m.p.geo, &m.guard);   /* the model's guard constants follow its geometry */
        if (rc == out.fault_code && hg_step(&m, &d, v, 1e-3) == 0)
            spec_limits(g, d.z_m, d.pose, &cj, &hj, &cl);
        else
            cj = hj = -1;
    }
    {
        char text[HG_PLANT_TEXT_LEN];
        hg_plant_hexaglide.describe(&out.fault_report, 0, text);
        CHECK(fault_at > 0 && crossing < 0 &&
                  (out.fault_code == HG_ERR_JOINT_RANGE || out.fault_code == HG_ERR_BAR_CLEARANCE) &&
                  (cj > g->cone_carriage_rad || hj > g->cone_head_rad || cl < g->d_bar_m) &&
                  out.sim_time_s == prev_t && tilt < 60 * DEG,
              "open loop %s: faults at t = %.3f s (%s: %s); every earlier state inside the limits by the "
              "spec's geometry, the next one outside (carriage %.2f deg, head %.2f deg, clearance %.2f mm); "
              "state frozen; largest head tilt %.1f deg (< 60)", what, (fault_at + 1) * 1e-3,
              hg_strerror(out.fault_code), text, cj / DEG, hj / DEG, cl * 1e3, tilt / DEG);
    }
}

/* A head rotation C(t) computed here: the limit found by the guard along
 * the path is where this file's geometry crosses it. With open joint
 * ranges (open = 1) the bars themselves touch. */
static void test_rotation_path(int open)
{
    hg_params p;
    double c[6] = {0, 0, -0.05, 0, 0, 0}, z[6], cross_ref = -1, cross_guard = -1;
    int i, rc = 0;
    hg_guard_report r;
    hg_params_default(&p);
    if (open)
        p.geo.cone_carriage_rad = p.geo.cone_head_rad = 3.1;
    for (i = 0; i <= 18000; i++) {
        double cj, hj, cl;
        c[5] = i * 0.01 * DEG;
        if (hg_inverse_kinematics(&p.geo, c, z))
            break;
        spec_limits(&p.geo, z, c, &cj, &hj, &cl);
        if (cross_ref < 0 && (cj > p.geo.cone_carriage_rad || hj > p.geo.cone_head_rad || cl < p.geo.d_bar_m))
            cross_ref = c[5];
        if (cross_guard < 0 && (rc = hg_guard_check(&p.geo, z, c, 0, &r)) != 0)
            cross_guard = c[5];
    }
    CHECK(cross_ref > 0 && cross_guard == cross_ref &&
              (open ? rc == HG_ERR_BAR_CLEARANCE && r.kind == HG_GUARD_BARS : rc == HG_ERR_JOINT_RANGE),
          "head turning about Z from Z = -50 mm%s: the guard stops at C = %.2f deg (code %d, kind %d, bars %d %d, "
          "%.3f %s), the spec's geometry crosses at %.2f deg", open ? ", joint ranges open" : "",
          cross_guard / DEG, rc, r.kind, r.bar, r.other, open ? r.value * 1e3 : r.value / DEG,
          open ? "mm" : "deg", cross_ref / DEG);
}

/* The clearance memo's bound (hg_guard_memo): on random reachable states
 * near a reference state whose memo was written (moved 0.1 mm to 5 cm,
 * 0.006 to 3 deg; head turned up to 140 deg with the joint ranges open,
 * and from up to 12 deg before the turn where two bars touch to 10 deg
 * beyond), and with random broken bars, the check with the
 * memo gives the code and report (bit for bit) of the check without; and
 * every pair the bound (recomputed here from the memo's points) clears is
 * at least d_bar apart by the second method. */
static void test_clearance_memo(void)
{
    hg_params p;
    hg_guard_geo gg;
    long states = 0, same = 0, cleared = 0, wrong = 0, touching = 0, rewritten = 0;
    int n;
    hg_params_default(&p);
    p.geo.cone_carriage_rad = p.geo.cone_head_rad = 3.1;   /* let the bars reach each other */
    hg_guard_prepare(&p.geo, &gg);
    for (n = 0; n < 20000; n++) {
        static const double size[4] = {1e-4, 1e-3, 1e-2, 5e-2};
        double c0[6], c[6], z0[6], z[6], sc0[6], sc[6], B[6][3], A[6][3], moved[6];
        hg_guard_memo memo, m2;
        hg_guard_report rf, rm;
        unsigned broken = n % 5 == 0 ? (unsigned)(n / 5) % 64u : 0u;
        int k, j, pr, rc_full, rc_memo;
        double s = size[n % 4];
        c0[0] = hg_test_uniform(-0.15, 0.15);
        c0[1] = hg_test_uniform(-0.15, 0.15);
        c0[2] = hg_test_uniform(-0.3, 0.2);
        c0[3] = hg_test_uniform(-25, 25) * DEG;
        c0[4] = hg_test_uniform(-25, 25) * DEG;
        c0[5] = hg_test_uniform(-140, 140) * DEG;
        for (k = 0; k < 6; k++)
            c[k] = c0[k] + hg_test_uniform(-s, s);
        if (n % 3 == 0) {                  /* across the limit: bars 0 and 2 touch at C = 132.2 deg */
            for (k = 0; k < 6; k++)
                c0[k] = k == 2 ? -0.05 : 0.0;
            c0[5] = hg_test_uniform(120, 132.2) * DEG;
            for (k = 0; k < 6; k++)
                c[k] = c0[k] + hg_test_uniform(-1e-3, 1e-3);
            c[5] = c0[5] + hg_test_uniform(0, 10) * DEG;
        }
        if (hg_inverse_kinematics(&p.geo, c0, z0) || hg_inverse_kinematics(&p.geo, c, z))
            continue;
        memset(&memo, 0, sizeof memo);
        hg_head_trig(c0, sc0);
        if (hg_guard_check_sc(&gg, z0, c0, sc0, broken, &memo, 0) != 0 || !memo.valid)
            continue;                      /* the reference must pass to be written */
        states++;
        m2 = memo;
        hg_head_trig(c, sc);
        rc_full = hg_guard_check(&p.geo, z, c, broken, &rf);
        rc_memo = hg_guard_check_sc(&gg, z, c, sc, broken, &m2, &rm);
        same += rc_full == rc_memo && rf.kind == rm.kind && rf.bar == rm.bar && rf.other == rm.other &&
                memcmp(&rf.value, &rm.value, sizeof rf.value) == 0 && memcmp(&rf.limit, &rm.limit, sizeof rf.limit) == 0;
        touching += rc_full == HG_ERR_BAR_CLEARANCE;
        rewritten += m2.refreshed > memo.refreshed;
        for (k = 0; k < 6; k++) {
            double mb = 0, ma = 0;
            spec_joints(&p.geo, z, c, k, B[k], A[k]);
            for (j = 0; j < 3; j++) {
                mb += (B[k][j] - memo.B[k][j]) * (B[k][j] - memo.B[k][j]);
                ma += (A[k][j] - memo.A[k][j]) * (A[k][j] - memo.A[k][j]);
            }
            moved[k] = sqrt(fmax(mb, ma));
        }
        for (j = 0, pr = 0; j < 6; j++)
            for (k = j + 1; k < 6; k++, pr++)
                if (!((broken >> j) & 1u) && !((broken >> k) & 1u) &&
                    memo.dist[pr] - moved[j] - moved[k] >= p.geo.d_bar_m + HG_GUARD_SLACK_M) {
                    cleared++;
                    wrong += segment_distance_ref(B[j], A[j], B[k], A[k]) < p.geo.d_bar_m;
                }
    }
    CHECK(states > 10000 && same == states && cleared > 100000 && wrong == 0 && touching > 1000 &&
              rewritten > 1000 && rewritten < states,
          "clearance memo: %ld random states near a reference, the check with the memo as without "
          "(code and report) in %ld, %ld with bars touching; %ld pairs cleared by the bound, %ld of them "
          "closer than d_bar by the second method; memo rewritten after %ld", states, same, touching,
          cleared, wrong, rewritten);
}

/* The memo's bounds alone (hg_guard_memo: no joint points): on random
 * states near reference states that passed, many of them close to the
 * joint cones (head tilted up to 45 deg, the cones 40 deg, or moved
 * sideways up to 0.45 m, the carriages' cone 25 deg) or to a bar
 * touching another (the memo's clearance test above), moved 0.1 mm to 5 cm
 * and 0.006 to 3 deg, the check with the memo gives the code and report
 * (bit for bit) of the check without; and every state the bounds alone
 * clear is inside both cones and the clearance by this file's geometry
 * (the spec's formulas). */
static void test_bounds_alone(void)
{
    hg_params p;
    hg_guard_geo gg;
    long states = 0, same = 0, cleared = 0, wrong = 0, crossing = 0, near = 0;
    double worst_c = 0, worst_h = 0;
    int n;
    hg_params_default(&p);
    hg_guard_prepare(&p.geo, &gg);
    for (n = 0; n < 40000; n++) {
        static const double size[4] = {1e-4, 1e-3, 1e-2, 5e-2};
        double c0[6], c[6], z0[6], z[6], sc0[6], sc[6], cj, hj, cl;
        hg_guard_memo memo, m2;
        hg_guard_report rf, rm;
        int k, rc_full, rc_memo;
        double s = size[n % 4];
        const double reach = n % 2 ? 0.1 : 0.45, tilt = n % 2 ? 45 : 5;   /* near the head's or the carriages' cones */
        c0[0] = hg_test_uniform(-reach, reach);
        c0[1] = hg_test_uniform(-reach, reach);
        c0[2] = hg_test_uniform(-0.2, 0.1);
        for (k = 3; k < 6; k++)
            c0[k] = hg_test_uniform(-tilt, tilt) * DEG;
        for (k = 0; k < 6; k++)
            c[k] = c0[k] + hg_test_uniform(-s, s);
        if (hg_inverse_kinematics(&p.geo, c0, z0) || hg_inverse_kinematics(&p.geo, c, z))
            continue;
        memset(&memo, 0, sizeof memo);
        hg_head_trig(c0, sc0);
        if (hg_guard_check_sc(&gg, z0, c0, sc0, 0, &memo, 0) != 0 || !memo.cones_valid)
            continue;                      /* the reference must pass to be written */
        states++;
        spec_limits(&p.geo, z0, c0, &cj, &hj, &cl);
        near += hj > p.geo.cone_head_rad - 5 * DEG || cj > p.geo.cone_carriage_rad - 5 * DEG;
        m2 = memo;
        hg_head_trig(c, sc);
        rc_full = hg_guard_check(&p.geo, z, c, 0, &rf);
        rc_memo = hg_guard_check_sc(&gg, z, c, sc, 0, &m2, &rm);
        same += rc_full == rc_memo && rf.kind == rm.kind && rf.bar == rm.bar && rf.other == rm.other &&
                memcmp(&rf.value, &rm.value, sizeof rf.value) == 0 && memcmp(&rf.limit, &rm.limit, sizeof rf.limit) == 0;
        crossing += rc_full == HG_ERR_JOINT_RANGE;
        if (m2.cleared > memo.cleared) {   /* passed on the bounds alone */
            cleared++;
            spec_limits(&p.geo, z, c, &cj, &hj, &cl);
            wrong += !(cj <= p.geo.cone_carriage_rad && hj <= p.geo.cone_head_rad && cl >= p.geo.d_bar_m);
            worst_c = fmax(worst_c, cj);
            worst_h = fmax(worst_h, hj);
        }
    }
    CHECK(states > 10000 && same == states && cleared > 5000 && wrong == 0 && crossing > 200 && near > 1000,
          "the memo's bounds alone: %ld random states near a reference (%ld references within 5 deg of a cone), "
          "the check with the memo as without (code and report) in %ld, %ld beyond a joint's cone; %ld passed on "
          "the bounds alone, %ld of them outside a limit by the second method (largest carriage-joint angle "
          "%.2f deg, head-joint %.2f deg, cones %.0f and %.0f deg)", states, near, same, crossing, cleared, wrong,
          worst_c / DEG, worst_h / DEG, p.geo.cone_carriage_rad / DEG, p.geo.cone_head_rad / DEG);
}

int main(void)
{
    static const double issue16[6] = {1.5, -2, 0.7, 2.5, -1.2, 0.3};
    static const double twist[6] = {2, -2, 2, -2, 2, -2};
    test_segment_distance();
    test_home_and_defaults();
    test_rotation_path(0);
    test_rotation_path(1);
    test_clearance_memo();
    test_bounds_alone();
    test_open_loop_strike(issue16, "1.5,-2,0.7,2.5,-1.2,0.3 V");
    test_open_loop_strike(twist, "+-2 V alternating (the head turns)");
    return hg_test_exit();
}
