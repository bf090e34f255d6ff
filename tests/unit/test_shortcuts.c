/* test_shortcuts.c - every shortcut of the step's speed work (issue 23)
 * against the reference path it replaces, bit for bit, on random cases:
 * the reference is the code the step ran before (kept as the general
 * path), so the check is that the fast path gives the same bits:
 *  - hg_rotation_sc of hg_head_trig's sin/cos and hg_rotation;
 *  - hg_spd6_apply6 (six columns, two at a time) and hg_spd6_apply;
 *  - hg_mass_response_matrix and hg_mass_response against d20d9e5's
 *    scalar mass response, copied here (a full T, the identity, broken
 *    bars' KKT factors, a T with an inf);
 *  - hg_drive_step with its memo of exp(-dt / tau) (kept over calls of
 *    changing step lengths and channels) and without;
 *  - hg_lu_factor and hg_lu_solve (constant bounds for 6x6, unrolled
 *    loops, a scan without a branch per entry) against their generic
 *    loops, copied here;
 *  - hg_forward_solve's Newton terms (one sin/cos, rotation and frame
 *    for phi and its Jacobian) against hg_constraints +
 *    hg_constraint_jacobian, the iterations it replaces;
 * (the guard's clearance bound: test_guard; golden states: test_golden). */
#include <string.h>
#include "hg_test.h"
#include "hg_integrate.h"
#include "hg_spd6.h"
#include "hg_linalg.h"
#include "hg_kinematics.h"
#include "hg_guard.h"
#include "hg_drive.h"
#include "hg_errors.h"
#include "hg_params.h"

/* 1 when the n doubles are bit for bit equal. */
static int same_bits(const double *a, const double *b, int n)
{
    return memcmp(a, b, (size_t)n * sizeof *a) == 0;
}

/* A random symmetric positive definite 6x6 matrix, factored (hg_spd6_factor). */
static void random_factored(double M[36], double inv_d[6])
{
    double X[36];
    int i, j, k;
    for (i = 0; i < 36; i++)
        X[i] = hg_test_uniform(-1, 1) * (i % 7 == 0 ? 30.0 : 1.0);
    for (i = 0; i < 6; i++)
        for (j = 0; j < 6; j++) {
            double v = i == j ? 0.1 : 0.0;
            for (k = 0; k < 6; k++)
                v += X[6 * i + k] * X[6 * j + k];
            M[6 * i + j] = v;
        }
    hg_spd6_factor(M, inv_d);
}

static void test_rotation(void)
{
    int n, same = 0;
    for (n = 0; n < 10000; n++) {
        double c[6] = {0, 0, 0, hg_test_uniform(-3, 3), hg_test_uniform(-1.5, 1.5), hg_test_uniform(-7, 7)};
        double sc[6], R1[9], R2[9];
        hg_head_trig(c, sc);
        hg_rotation_sc(sc, R1);
        hg_rotation(c[3], c[4], c[5], R2);
        same += same_bits(R1, R2, 9);
    }
    CHECK(same == 10000, "hg_rotation_sc of hg_head_trig: hg_rotation's bits on %d of 10000 random angles", same);
}

static void test_apply6(void)
{
    int n, same = 0;
    for (n = 0; n < 2000; n++) {
        double M[36], inv_d[6], B0[36], B[36], col[6];
        int i, c, ok = 1;
        random_factored(M, inv_d);
        for (i = 0; i < 36; i++)
            B[i] = B0[i] = hg_test_uniform(-5, 5);
        hg_spd6_apply6(M, inv_d, B);
        for (c = 0; c < 6 && ok; c++) {
            double want[6];
            for (i = 0; i < 6; i++)
                want[i] = B0[6 * i + c];
            hg_spd6_apply(M, inv_d, want);
            for (i = 0; i < 6; i++)
                col[i] = B[6 * i + c];
            ok = same_bits(col, want, 6);
        }
        same += ok;
    }
    CHECK(same == 2000, "hg_spd6_apply6: hg_spd6_apply's bits in every column on %d of 2000 random systems", same);
}

/* hg_mass_response as commit d20d9e5 wrote it (scalar loops, kind 1 and
 * 2), the reference of the vectorized one. */
static void response_d20d9e5(const hg_mass_snapshot *s, const double p[6], double *dv, double dz[6])
{
    int i, j;
    if (s->kind == 1) {
        double g[6];
        for (i = 0; i < 6; i++) {
            double v = 0.0;
            if (s->t_identity)
                v = p[i];
            else
                for (j = 0; j < 6; j++)
                    v += s->T[6 * j + i] * p[j];
            g[i] = v;
        }
        hg_spd6_apply(s->ldl, s->inv_d, g);
        for (i = 0; i < 6; i++) {
            double v = 0.0;
            dv[i] = g[i];
            if (s->t_identity)
                v = g[i];
            else
                for (j = 0; j < 6; j++)
                    v += s->T[6 * i + j] * g[j];
            dz[i] = v;
        }
    } else {
        double b[HG_KKT_MAX];
        for (i = 0; i < s->nkkt; i++)
            b[i] = i < 6 ? p[i] : 0.0;
        hg_lu_solve(s->nkkt, s->kkt, s->piv, 1, b);
        for (i = 0; i < 12; i++)
            dv[i] = b[i];
        for (i = 0; i < 6; i++)
            dz[i] = b[i];
    }
}

/* W column by column with d20d9e5's mass response, the reference. */
static void w_reference(const hg_mass_snapshot *s, double W[36])
{
    double e[6] = {0, 0, 0, 0, 0, 0}, dv[12], dz[6];
    int i, k;
    for (k = 0; k < 6; k++) {
        e[k] = 1.0;
        response_d20d9e5(s, e, dv, dz);
        for (i = 0; i < 6; i++)
            W[6 * i + k] = dz[i];
        e[k] = 0.0;
    }
}

static void test_response_matrix(void)
{
    static hg_mass_snapshot s;
    int n, same[4] = {0, 0, 0, 0};
    for (n = 0; n < 4000; n++) {
        double M[36], inv_d[6], T[36], W1[36], W2[36];
        int i, kind = n % 4;
        memset(&s, 0, sizeof s);
        random_factored(M, inv_d);
        for (i = 0; i < 36; i++)
            T[i] = i % 5 == 0 ? 0.0 : hg_test_uniform(-2, 2);   /* zeros: their sign must not change */
        if (kind == 3)
            T[7] = INFINITY;
        if (kind == 2) {                   /* broken bars: LU of a KKT-shaped 13 x 13 */
            double a[13 * 13];
            int piv[13];
            for (i = 0; i < 13 * 13; i++)
                a[i] = hg_test_uniform(-1, 1) + (i % 14 == 0 ? 5.0 : 0.0);
            hg_lu_factor(13, a, piv);
            hg_mass_save_kkt(&s, 13, a, piv);
        } else {
            hg_mass_save_reduced(&s, M, inv_d, kind == 1 ? 0 : T);
        }
        w_reference(&s, W1);
        hg_mass_response_matrix(&s, W2);
        {                                  /* and one random impulse through hg_mass_response */
            double pimp[6], dv1[12], dv2[12], dz1[6], dz2[6];
            for (i = 0; i < 6; i++)
                pimp[i] = hg_test_uniform(-0.1, 0.1);
            response_d20d9e5(&s, pimp, dv1, dz1);
            hg_mass_response(&s, pimp, dv2, dz2);
            same[kind] += same_bits(W1, W2, 36) && same_bits(dv1, dv2, 6) && same_bits(dz1, dz2, 6);
        }
    }
    CHECK(same[0] == 1000 && same[1] == 1000 && same[2] == 1000 && same[3] == 1000,
          "hg_mass_response_matrix and hg_mass_response: d20d9e5's scalar response's bits on %d (a full T), %d (identity), "
          "%d (broken bars' KKT), %d (a T with an inf) of 1000 random cases each", same[0], same[1],
          same[2], same[3]);
}

/* Random drive channels (either mode, a bus that limits or not). */
static void random_channel(hg_drive_channel *c, int k)
{
    hg_drive_params p;
    p.kt_nm_per_a = hg_test_uniform(0.1, 1.0);
    p.lead_m = hg_test_uniform(0.005, 0.02);
    p.r_winding_ohm = hg_test_uniform(0.5, 4.0);
    p.l_winding_h = k % 3 == 0 ? 1e-9 : hg_test_uniform(1e-3, 1e-2);
    p.amp_mode = k % 2;
    p.ka_a_per_v = hg_test_uniform(0.2, 1.5);
    p.i_max_a = hg_test_uniform(2, 10);
    p.v_bus_v = hg_test_uniform(20, 200);
    p.v_rated_mps = hg_test_uniform(0.05, 0.3);
    p.kp_vel_as_per_m = hg_test_uniform(10, 500);
    p.ki_vel_a_per_m = hg_test_uniform(0, 1e4);
    hg_drive_init(c, &p);
}

static void test_drive_memo(void)
{
    static hg_drive_memo memo;           /* empty: zeros */
    hg_drive_channel c[HG_DRIVE_MAX];
    int n, k, same = 0;
    for (k = 0; k < HG_DRIVE_MAX; k++)
        random_channel(&c[k], k);
    for (n = 0; n < 20000; n++) {
        static const double dts[3] = {1e-3, 2.5e-4, 1e-3 / 3.0};
        double v[HG_DRIVE_MAX], i0[HG_DRIVE_MAX], zd[HG_DRIVE_MAX], xi[HG_DRIVE_MAX];
        hg_drive_out a, b;
        double dt = dts[(n / 50) % 3];     /* runs of one step length, then another */
        int ch = 1 + n % HG_DRIVE_MAX;
        if (n % 997 == 0)                  /* new parameters now and then: the memo must notice */
            random_channel(&c[n % HG_DRIVE_MAX], n);
        for (k = 0; k < HG_DRIVE_MAX; k++) {
            v[k] = n % 7 == 0 ? 10.0 : hg_test_uniform(-12, 12);
            i0[k] = hg_test_uniform(-10, 10);
            zd[k] = hg_test_uniform(-0.3, 0.3);
            xi[k] = hg_test_uniform(-1e-3, 1e-3);
        }
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        hg_drive_step(c, ch, v, i0, zd, xi, 0xffu, dt, &memo, &a);
        hg_drive_step(c, ch, v, i0, zd, xi, 0xffu, dt, 0, &b);
        same += memcmp(&a, &b, sizeof a) == 0;
    }
    CHECK(same == 20000, "hg_drive_step with its exp memo (step lengths and parameters changing): the "
          "bits without it on %d of 20000 random calls of 1..8 channels", same);
}

/* hg_lu_factor as it was before its 6x6 path (the generic loop). */
static int lu_reference(int n, double *a, int *piv)
{
    int i, j, k;
    double amax = 0.0;
    for (i = 0; i < n * n; i++) {
        if (!isfinite(a[i]))
            return HG_ERR_SINGULAR_JACOBIAN;
        if (fabs(a[i]) > amax)
            amax = fabs(a[i]);
    }
    if (amax == 0.0)
        return HG_ERR_SINGULAR_JACOBIAN;
    for (i = 0; i < n; i++)
        piv[i] = i;
    for (k = 0; k < n; k++) {
        int p = k;
        double best = fabs(a[k * n + k]);
        for (i = k + 1; i < n; i++)
            if (fabs(a[i * n + k]) > best) {
                best = fabs(a[i * n + k]);
                p = i;
            }
        if (best <= 1e-13 * amax)
            return HG_ERR_SINGULAR_JACOBIAN;
        if (p != k) {
            int t = piv[k];
            piv[k] = piv[p];
            piv[p] = t;
            for (j = 0; j < n; j++) {
                double s = a[k * n + j];
                a[k * n + j] = a[p * n + j];
                a[p * n + j] = s;
            }
        }
        for (i = k + 1; i < n; i++) {
            double f = a[i * n + k] / a[k * n + k];
            a[i * n + k] = f;
            for (j = k + 1; j < n; j++)
                a[i * n + j] -= f * a[k * n + j];
        }
    }
    return 0;
}

/* hg_lu_solve as it was before its unrolled loops. */
static void lu_solve_reference(int n, const double *lu, const int *piv, int nrhs, double *b)
{
    double x[HG_LINALG_MAX_N];
    int i, j, r;
    for (r = 0; r < nrhs; r++) {
        for (i = 0; i < n; i++)
            x[i] = b[piv[i] * nrhs + r];
        for (i = 1; i < n; i++)
            for (j = 0; j < i; j++)
                x[i] -= lu[i * n + j] * x[j];
        for (i = n - 1; i >= 0; i--) {
            for (j = i + 1; j < n; j++)
                x[i] -= lu[i * n + j] * x[j];
            x[i] /= lu[i * n + i];
        }
        for (i = 0; i < n; i++)
            b[i * nrhs + r] = x[i];
    }
}

/* hg_lu_factor and hg_lu_solve against the loops above, n = 6 (constant
 * bounds) and other sizes, with singular, zero, Inf and NaN matrices. */
static void test_lu6(void)
{
    static const int sizes[] = {6, 6, 6, 1, 4, 9, 13};
    int t, i, same = 1, singular = 0, solved = 0;
    for (t = 0; t < 4000; t++) {
        const int n = sizes[t % 7], nrhs = 1 + t % 3;
        double a[HG_LINALG_MAX_N * HG_LINALG_MAX_N], b[HG_LINALG_MAX_N * HG_LINALG_MAX_N];
        double x[3 * HG_LINALG_MAX_N], y[3 * HG_LINALG_MAX_N];
        int pa[HG_LINALG_MAX_N], pb[HG_LINALG_MAX_N], ra, rb;
        for (i = 0; i < n * n; i++)
            a[i] = hg_test_uniform(-1, 1) * (i % 5 == 0 ? 1e3 : 1.0);
        if (t % 50 == 1 && n > 1)              /* a repeated row: singular */
            for (i = 0; i < n; i++)
                a[n + i] = a[i];
        if (t % 97 == 2)
            a[n * n - 1] = t % 2 ? INFINITY : -INFINITY;
        if (t % 89 == 3)
            a[n * n / 2] = NAN;
        if (t % 211 == 4)
            memset(a, 0, sizeof a);
        memcpy(b, a, sizeof a);
        ra = hg_lu_factor(n, a, pa);
        rb = lu_reference(n, b, pb);
        singular += rb != 0;
        same &= ra == rb && (ra != 0 || (same_bits(a, b, n * n) && memcmp(pa, pb, n * sizeof(int)) == 0));
        if (ra != 0 || rb != 0)
            continue;
        for (i = 0; i < n * nrhs; i++)
            x[i] = y[i] = hg_test_uniform(-1, 1);
        hg_lu_solve(n, a, pa, nrhs, x);
        lu_solve_reference(n, b, pb, nrhs, y);
        same &= same_bits(x, y, n * nrhs);
        solved++;
    }
    CHECK(same && singular >= 80 && solved > 3000,
          "hg_lu_factor and hg_lu_solve = the generic loops bit for bit on 4000 matrices of 1..13 "
          "(%d refused alike: singular, zero, Inf, NaN; %d solves of 1..3 columns)", singular, solved);
}

/* hg_forward_solve's Newton iteration as it was: hg_constraints and
 * hg_constraint_jacobian at each iterate; the iterations run, or -1. */
static int fk_reference(const hg_geometry *g, const double z[6], double c[6], int max_it)
{
    int it, k, piv[6];
    for (it = 1; it <= max_it; it++) {
        double phi[6], jac[36], step = 0.0;
        hg_constraints(g, z, c, phi);
        hg_constraint_jacobian(g, z, c, jac, 0);
        if (lu_reference(6, jac, piv))
            return -1;
        hg_lu_solve(6, jac, piv, 1, phi);
        for (k = 0; k < 6; k++) {
            double sk = fabs(phi[k]) * (k < 3 ? 1.0 : g->l_m);
            c[k] -= phi[k];
            if (!(sk <= step))
                step = sk;
        }
        if (step <= 1e-12)
            return it;
    }
    return -1;
}

static void test_fk_terms(void)
{
    hg_params p;
    hg_fk_options o;
    int t, k, tried = 0, same = 1, its = 0;
    hg_params_default(&p);
    hg_fk_options_default(&o);
    for (t = 0; t < 1500; t++) {
        double target[6], z[6], c[6], pose[6];
        int rc, it, iterations;
        for (k = 0; k < 6; k++)
            target[k] = hg_test_uniform(-1, 1) * (k < 3 ? 0.1 : 0.25);
        if (hg_inverse_kinematics(&p.geo, target, z) != HG_OK)
            continue;
        for (k = 0; k < 6; k++)        /* started up to 5 mm / 1 degree away, as the tool error's */
            c[k] = pose[k] = target[k] + hg_test_uniform(-1, 1) * (k < 3 ? 5e-3 : 0.0175);
        rc = hg_forward_solve(&p.geo, z, pose, &o, &iterations, 0);
        it = fk_reference(&p.geo, z, c, o.max_iterations);
        tried++;
        its += it;
        same &= rc == HG_OK && it == iterations && same_bits(pose, c, 6);
    }
    CHECK(tried > 500 && same, "hg_forward_solve = the Newton iteration on hg_constraints and "
          "hg_constraint_jacobian bit for bit, iterations alike, on %d poses (%.2f iterations each)",
          tried, its / (double)(tried ? tried : 1));
}

int main(void)
{
    test_rotation();
    test_apply6();
    test_response_matrix();
    test_drive_memo();
    test_lu6();
    test_fk_terms();
    return hg_test_exit();
}
