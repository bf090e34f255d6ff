/* test_friction.c - the velocity-level stick/slip solve (src/hg_friction.c)
 * against facts worked out by hand for one carriage, and against the
 * complementarity conditions on random coupled machines:
 *  - one carriage (W = 1/m): a load below breakaway is held with the exact
 *    impulse -v* m, above it the carriage slides with the Stribeck force;
 *    a moving carriage that friction would reverse stops at the fraction
 *    v0 / (v0 - v_rev) of the step a constant deceleration gives;
 *  - coupled (random SPD W): stuck carriages end at speed 0 with at most
 *    f_static dt, sliding ones get -sign f dt with f between f_coulomb and
 *    f_static, none reverses; the same for 1, 3 and 8 axes whose channels
 *    each have their own parameters (a serial-axis plant);
 *  - the shortcut hg_friction_all_sliding, whenever it claims a case,
 *    gives bit for bit the impulses of the full solve;
 *  - the Stribeck curve is f_static at rest and f_coulomb on its flat. */
#include <string.h>
#include "hg_test.h"
#include "hg_friction.h"

#define DT 1e-3

static hg_params p;
static hg_friction_channel ch[6];       /* the default carriages' channels */

/* Random SPD W (n x n) = Q diag Q^T with eigenvalues in [lo, hi] (1/kg). */
static void random_wn(int n, double *W, double lo, double hi)
{
    double a[64], q[64];
    int i, j, k;
    for (i = 0; i < n * n; i++)
        a[i] = hg_test_uniform(-1.0, 1.0);
    for (j = 0; j < n; j++) {                 /* Gram-Schmidt: orthonormal columns of a */
        for (i = 0; i < n; i++)
            q[n * i + j] = a[n * i + j];
        for (k = 0; k < j; k++) {
            double d = 0.0;
            for (i = 0; i < n; i++)
                d += q[n * i + k] * a[n * i + j];
            for (i = 0; i < n; i++)
                q[n * i + j] -= d * q[n * i + k];
        }
        {
            double nn = 0.0;
            for (i = 0; i < n; i++)
                nn += q[n * i + j] * q[n * i + j];
            nn = sqrt(nn);
            for (i = 0; i < n; i++)
                q[n * i + j] /= nn;
        }
    }
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++) {
            double s = 0.0;
            for (k = 0; k < n; k++)
                s += q[n * i + k] * q[n * j + k] * (lo + (hi - lo) * k / (n > 1 ? n - 1.0 : 1.0));
            W[n * i + j] = s;
        }
}

/* The same for the Hexaglide's six. */
static void random_w(double W[36], double lo, double hi)
{
    random_wn(6, W, lo, hi);
}

/* One carriage of mass m in slot 0, the others far away and at rest with no load. */
static void single(double m, double W[36])
{
    int i;
    memset(W, 0, 36 * sizeof W[0]);
    for (i = 0; i < 6; i++)
        W[7 * i] = 1.0 / m;
}

static void test_one_carriage(void)
{
    const double m = 50.0;
    double W[36], vstar[6] = {0}, v0[6] = {0};
    hg_friction_out o;
    single(m, W);
    /* at rest, a net 30 N down over the step: v* = -30 dt / m; f_static 50 N holds it */
    vstar[0] = -30.0 * DT / m;
    CHECK(hg_friction_solve(ch, 6, W, vstar, v0, 0x3f, DT, &o) == 0 && (o.stuck & 1u) &&
              fabs(o.impulse[0] - 30.0 * DT) <= 1e-15,
          "30 N against 50 N breakaway: stuck, impulse %.6g N s = 30 N x dt", o.impulse[0]);
    /* 60 N down: breaks away, slides down with the Stribeck force near rest (about f_static) */
    vstar[0] = -60.0 * DT / m;
    CHECK(hg_friction_solve(ch, 6, W, vstar, v0, 0x3f, DT, &o) == 0 && !(o.stuck & 1u) &&
              o.impulse[0] > 0.0 && o.impulse[0] / DT <= p.f_static_n + 1e-9 &&
              o.impulse[0] / DT >= p.f_coulomb_n - 1e-9,
          "60 N against 50 N breakaway: slides, friction %.3f N within [f_coulomb, f_static]",
          o.impulse[0] / DT);
    /* moving up at 0.5 mm/s with no load: friction near f_static would take
     * f dt / m = 1 mm/s off, so it stops within the step and ends at rest */
    v0[0] = 0.0005;
    vstar[0] = 0.0005;
    CHECK(hg_friction_solve(ch, 6, W, vstar, v0, 0x3e, DT, &o) == 0 && (o.stuck & 1u),
          "0.5 mm/s without load: friction stops it within the step");
    CHECK(fabs(o.impulse[0] + m * 0.0005) <= 1e-15, "stopped: impulse %.6g N s = -m v0", o.impulse[0]);
    /* constant deceleration by a force between f_coulomb and f_static */
    CHECK(o.stop[0] >= m * 0.0005 / (p.f_static_n * DT) - 1e-12 &&
              o.stop[0] <= m * 0.0005 / (p.f_coulomb_n * DT) + 1e-12,
          "stop fraction %.4f = m v0 / (f dt) with f in [f_coulomb, f_static]", o.stop[0]);
    /* fast (100 mm/s) sliding: f_coulomb exactly, shortcut and solve agree */
    v0[0] = -0.1;
    vstar[0] = -0.1;
    CHECK(hg_friction_solve(ch, 6, W, vstar, v0, 0x3e, DT, &o) == 0 && !(o.stuck & 1u) &&
              o.impulse[0] == p.f_coulomb_n * DT,
          "100 mm/s: the sliding impulse is f_coulomb dt to the last bit (%.17g)", o.impulse[0]);
}

/* Random coupled cases of n axes, each channel with its own parameters
 * (n = 6 with the default carriages' when chans is 0): stuck axes end at
 * speed 0 with at most their own f_static dt, sliding ones get -sign f dt
 * with f between their f_coulomb and f_static, none reverses. */
static void test_coupled(int n, int own, const char *what)
{
    int trial, worst_v = 0, worst_p = 0, worst_rev = 0, n_stuck = 0, n_slide = 0;
    for (trial = 0; trial < 2000; trial++) {
        hg_friction_channel c[HG_FRICTION_MAX_N];
        double W[64], vstar[8], v0[8];
        unsigned rest = 0;
        hg_friction_out o;
        int i, j;
        for (i = 0; i < n; i++) {
            c[i] = ch[0];
            if (own) {
                c[i].f_coulomb_n = hg_test_uniform(5.0, 60.0);
                c[i].f_static_n = c[i].f_coulomb_n * hg_test_uniform(1.0, 1.6);
                c[i].v_stribeck_mps = hg_test_uniform(5e-4, 5e-3);
            }
        }
        random_wn(n, W, 1.0 / 400.0, 1.0 / 55.0);
        for (i = 0; i < n; i++) {
            int kind = (int)hg_test_uniform(0.0, 3.0);
            v0[i] = kind == 0 ? 0.0 : hg_test_uniform(-0.01, 0.01);
            if (kind == 0)
                rest |= 1u << i;
            vstar[i] = v0[i] + hg_test_uniform(-2.0, 2.0) * DT;   /* loads of up to ~+-100 N */
        }
        if (hg_friction_solve(c, n, W, vstar, v0, rest, DT, &o)) {
            worst_v++;
            continue;
        }
        for (i = 0; i < n; i++) {
            double v = vstar[i];
            for (j = 0; j < n; j++)
                v += W[n * i + j] * o.impulse[j];
            if ((o.stuck >> i) & 1u) {
                n_stuck++;
                worst_v += !(fabs(v) <= 1e-12);
                worst_p += !(fabs(o.impulse[i]) <= c[i].f_static_n * DT * (1 + 1e-12));
            } else {
                double f = fabs(o.impulse[i]) / DT;
                n_slide++;
                worst_p += !(f >= c[i].f_coulomb_n - 1e-9 && f <= c[i].f_static_n + 1e-9);
                worst_rev += v * o.impulse[i] > 1e-15;    /* friction opposes the end speed */
            }
        }
    }
    CHECK(worst_v == 0 && n_stuck > 20 && n_slide > 100,
          "2000 coupled cases, %s: every stuck axis ends at speed 0 (%d stuck)", what, n_stuck);
    CHECK(worst_p == 0, "... stuck impulses within f_static dt, sliding forces within [f_c, f_s] (%d sliding)",
          n_slide);
    CHECK(worst_rev == 0, "... no sliding axis is pushed along its end speed by friction");
}

static void test_shortcut(void)
{
    int trial, claimed = 0, differ = 0;
    const double m_min = 55.0;
    for (trial = 0; trial < 5000; trial++) {
        double W[36], vstar[6], v0[6], est[6], vpred[6];
        hg_friction_out fast, full;
        int i, j;
        random_w(W, 1.0 / 500.0, 1.0 / m_min);
        for (i = 0; i < 6; i++) {
            v0[i] = hg_test_uniform(0.008, 0.05) * (hg_test_uniform(0, 1) < 0.5 ? -1 : 1);
            vpred[i] = v0[i] + hg_test_uniform(-5e-3, 5e-3);
            est[i] = -(v0[i] < 0 ? -1 : 1) * p.f_coulomb_n * DT * hg_test_uniform(0.8, 1.2);
        }
        for (i = 0; i < 6; i++) {           /* the speeds without friction, as hg_integrate forms them */
            vstar[i] = vpred[i];
            for (j = 0; j < 6; j++)
                vstar[i] -= W[6 * i + j] * est[j];
        }
        if (!hg_friction_all_sliding(ch, 6, vpred, v0, 0, est, m_min, DT, &fast))
            continue;
        claimed++;
        if (hg_friction_solve(ch, 6, W, vstar, v0, 0, DT, &full) || full.stuck != 0 ||
            memcmp(fast.impulse, full.impulse, 6 * sizeof fast.impulse[0]) != 0)
            differ++;
    }
    CHECK(claimed > 500 && differ == 0,
          "all-sliding shortcut: %d of 5000 random cases claimed, %d differ from the full solve", claimed,
          differ);
}

int main(void)
{
    double vs;
    int k;
    hg_params_default(&p);
    for (k = 0; k < 6; k++) {
        ch[k].f_static_n = p.f_static_n;
        ch[k].f_coulomb_n = p.f_coulomb_n;
        ch[k].v_stribeck_mps = p.v_stribeck_mps;
    }
    vs = p.v_stribeck_mps;
    CHECK(hg_friction_curve(&ch[0], 0.0) == p.f_static_n, "Stribeck curve at rest: f_static");
    CHECK(hg_friction_curve(&ch[0], 6.01 * vs) == p.f_coulomb_n &&
              hg_friction_curve(&ch[0], 5.9 * vs) > p.f_coulomb_n,
          "Stribeck curve: f_coulomb on its flat beyond 6 v_stribeck, above it just before");
    CHECK(fabs(hg_friction_curve(&ch[0], vs) - (p.f_coulomb_n + (p.f_static_n - p.f_coulomb_n) * exp(-1.0))) < 1e-12,
          "Stribeck curve at v_stribeck: f_c + (f_s - f_c) / e");
    test_one_carriage();
    test_coupled(6, 0, "six default carriages");
    test_coupled(1, 1, "one axis of its own");
    test_coupled(3, 1, "three axes, each its own parameters");
    test_coupled(8, 1, "eight axes, each its own parameters");
    test_shortcut();
    return hg_test_exit();
}
