/* bench_integrators.c - accuracy against cost of the integration schemes
 * (hg_integrate.h). The run: from HOME at rest, the asymmetric drive
 * voltages (1.7, -0.9, 0.4, 1.1, -0.6, 0.8) V held for 0.25 s (issue 11).
 * The reference is RK4 at 1 us (its own difference to RK4 at 2 us is
 * printed: the reference's error). Prints
 *  1. error vs dt per scheme (largest |z| difference at t = 0.25 s, m) and
 *     the measured convergence order log2(e(2 dt)/e(dt)), Reduced Cartesian;
 *  2. at the 1 ms servo period, for each (scheme, substeps): the error and
 *     the wall time of one servo period (substeps hg_step calls of
 *     1 ms/substeps), median over 20,000 periods of a smooth servo motion,
 *     each period timed alone, hot in cache.
 *  3. the flexible drive train (the default since issue 22): at 1 ms, each
 *     scheme with the substeps the stability check asks for (the board runs
 *     them) and twice as many, the carriages' and the motors' error against
 *     RK4 at 1 us on the same flexible machine, and the period's cost
 *     against the rigid train's default period (Heun, one step).
 * Sections 1 and 2 run the rigid train (k_axial = 0), as before issue 22.
 * Machine lines: BENCH integ_<scheme>_x<substeps> median_us=<x> p99_us=<y> err_m=<e>
 *                BENCH train_<scheme>_x<substeps> median_us=<x> err_m=<e> motor_err_m=<e> over_rigid=<r> */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "hg_dynamics.h"
#include "hg_plant_hexaglide.h"
#include "hg_stability.h"
#include "bench_timing.h"

#define T_END 0.25
#define PERIOD_S 1e-3
#define PERIODS 20000

static const double volts[6] = {1.7, -0.9, 0.4, 1.1, -0.6, 0.8};
static int flexible;                   /* 1: the default flexible trains, 0: rigid (k_axial 0) */

/* The machine of this section: the defaults, rigid trains unless flexible. */
static void bench_params(hg_params *p)
{
    hg_params_default(p);
    if (!flexible)
        p->k_axial_n_per_m = 0.0;
}

/* z (and the motors zr) at T_END with `scheme` at step dt (T_END/dt steps); 0 or a code. */
static int run2(hg_model_kind kind, int scheme, double dt, double z[6], double zr[6])
{
    static hg_model m;
    static hg_data d;
    hg_params p;
    long s, n = lround(T_END / dt);
    int rc;
    bench_params(&p);
    if ((rc = hg_model_init(&m, &p, kind, 0, 0)) || (rc = hg_model_set_integrator(&m, scheme)) ||
        (rc = hg_data_reset(&m, &d)))
        return rc;
    for (s = 0; s < n; s++)
        if ((rc = hg_step(&m, &d, volts, dt)))
            return rc;
    memcpy(z, d.z_m, sizeof d.z_m);
    if (zr)
        memcpy(zr, m.flexible ? d.zr_m : d.z_m, sizeof d.z_m);
    return 0;
}

/* z at T_END (run2 without the motors). */
static int run(hg_model_kind kind, int scheme, double dt, double z[6])
{
    return run2(kind, scheme, dt, z, 0);
}

static double maxdiff(const double a[6], const double b[6])
{
    double e = 0;
    int k;
    for (k = 0; k < 6; k++)
        e = fmax(e, fabs(a[k] - b[k]));
    return e;
}

/* Median and p99 wall time (us) of one servo period of `sub` steps. */
static int cost(hg_model_kind kind, int scheme, int sub, double *us, double *med, double *p99)
{
    static hg_model m;
    static hg_data d;
    hg_params p;
    double hold;
    int i, j, k, rc;
    bench_params(&p);
    if ((rc = hg_model_init(&m, &p, kind, 0, 0)) || (rc = hg_model_set_integrator(&m, scheme)) ||
        (rc = hg_data_reset(&m, &d)))
        return rc;
    hold = p.g_mps2 * (p.m_head_kg + 6 * (p.m_bar_kg + p.m_carriage_kg)) / 6 / m.force_per_volt_n;
    for (i = 0; i < PERIODS + 1000; i++) {
        double v[6], t0, t1;
        for (k = 0; k < 6; k++)
            v[k] = fmax(-10, fmin(10, hold + 300 * (0.02 * sin(M_PI * d.t_s + k * M_PI / 3) - d.z_m[k])));
        t0 = bench_now_us();
        for (j = 0; j < sub; j++)
            if ((rc = hg_step(&m, &d, v, PERIOD_S / sub)))
                return rc;
        t1 = bench_now_us();
        if (i >= 1000)
            us[i - 1000] = t1 - t0;
    }
    bench_percentiles(us, PERIODS, med, p99);
    return 0;
}

/* Section 3: the flexible trains at 1 ms against RK4 at 1 us, cost over the rigid default period. */
static int drivetrain(hg_model_kind kind, double *us)
{
    double zref[6], zrref[6], z[6], zr[6], rigid_med, rigid_p99, med, p99;
    hg_params p;
    int s, twice;
    flexible = 0;
    if (cost(kind, HG_INTEGRATOR_HEUN, 1, us, &rigid_med, &rigid_p99))
        return 1;
    flexible = 1;
    bench_params(&p);
    if (run2(kind, HG_INTEGRATOR_RK4, 1e-6, zref, zrref)) {
        printf("flexible reference run failed\n");
        return 1;
    }
    printf("\nflexible drive trains (k_axial %.3g N/m, c_axial %.3g N s/m), %s, 1 ms period: errors at %.2f s "
           "against RK4 at 1 us on the same machine; cost per period over the rigid train's default "
           "(heun, 1 step: %.3f us)\n", p.k_axial_n_per_m, p.c_axial_ns_per_m, hg_model_name(kind), T_END,
           rigid_med);
    printf("%-15s %8s %14s %14s %10s %10s %8s\n", "scheme", "substeps", "carriage err m", "motor err m",
           "median us", "p99 us", "x rigid");
    for (s = 0; s < HG_INTEGRATOR_COUNT; s++) {
        hg_stability st;
        if (hg_stability_check(&p, (hg_integrator)s, PERIOD_S, 1, 64, &st) || !st.substeps) {
            printf("%-15s: not stable with up to 64 substeps\n", hg_integrator_name((hg_integrator)s));
            continue;
        }
        for (twice = 1; twice <= 2; twice++) {
            int sub = (int)st.substeps * twice;
            double e = NAN, em = NAN;
            if (run2(kind, s, PERIOD_S / sub, z, zr) == 0)
                e = maxdiff(z, zref), em = maxdiff(zr, zrref);
            if (cost(kind, s, sub, us, &med, &p99))
                return 1;
            printf("%-15s %8d %14.3e %14.3e %10.3f %10.3f %8.2f\n", hg_integrator_name((hg_integrator)s), sub, e,
                   em, med, p99, med / rigid_med);
            printf("BENCH train_%s_x%d median_us=%.3f err_m=%.3g motor_err_m=%.3g over_rigid=%.2f\n",
                   hg_integrator_name((hg_integrator)s), sub, med, e, em, med / rigid_med);
        }
    }
    return 0;
}

int main(void)
{
    static const double dts[] = {2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5};
    static const int subs[] = {1, 2, 4, 8};
    static double us[PERIODS];
    const int nd = sizeof dts / sizeof dts[0];
    hg_model_kind kind = HG_MODEL_REDUCED_CARTESIAN;
    double zref[6], zref2[6], z[6], e[HG_INTEGRATOR_COUNT][8];
    int s, i, j, kk;
    if (run(kind, HG_INTEGRATOR_RK4, 1e-6, zref) || run(kind, HG_INTEGRATOR_RK4, 2e-6, zref2)) {
        printf("reference run failed\n");
        return 1;
    }
    printf("convergence: volts (1.7 -0.9 0.4 1.1 -0.6 0.8) V for %.2f s from HOME, %s;\n"
           "error = largest |z - z_ref| at the end, z_ref = RK4 at 1 us (RK4 at 2 us is %.1e m "
           "from it)\n\n", T_END, hg_model_name(kind), maxdiff(zref, zref2));
    printf("%-10s", "dt (s)");
    for (s = 0; s < HG_INTEGRATOR_COUNT; s++)
        printf(" %16s %5s", hg_integrator_name((hg_integrator)s), "order");
    printf("\n");
    for (i = 0; i < nd; i++) {
        printf("%-10.3g", dts[i]);
        for (s = 0; s < HG_INTEGRATOR_COUNT; s++) {
            e[s][i] = run(kind, s, dts[i], z) ? NAN : maxdiff(z, zref);
            if (i)
                printf(" %16.3e %5.2f", e[s][i], log2(e[s][i - 1] / e[s][i]));
            else
                printf(" %16.3e %5s", e[s][i], "");
        }
        printf("\n");
    }
    printf("\nservo period 1 ms: error at %.2f s and wall time per period (%d periods, each timed "
           "alone)\n", T_END, PERIODS);
    for (kk = 0; kk < HG_MODEL_COUNT; kk++) {
        if (kk == HG_MODEL_STANDARD)
            continue;                  /* keep the bench short: the reduced kinds */
        printf("\n%-18s %-15s %8s %12s %10s %10s\n", hg_model_name((hg_model_kind)kk), "scheme",
               "substeps", "error m", "median us", "p99 us");
        for (s = 0; s < HG_INTEGRATOR_COUNT; s++)
            for (j = 0; j < (int)(sizeof subs / sizeof subs[0]); j++) {
                double med, p99, err;
                err = run((hg_model_kind)kk, s, PERIOD_S / subs[j], z) ? NAN : maxdiff(z, zref);
                if (cost((hg_model_kind)kk, s, subs[j], us, &med, &p99)) {
                    printf("failed\n");
                    return 1;
                }
                printf("%-18s %-15s %8d %12.3e %10.3f %10.3f\n", "", hg_integrator_name((hg_integrator)s),
                       subs[j], err, med, p99);
                if (kk == HG_MODEL_FUSED_CARTESIAN)
                    printf("BENCH integ_%s_x%d median_us=%.3f p99_us=%.3f err_m=%.3g\n",
                           hg_integrator_name((hg_integrator)s), subs[j], med, p99, err);
            }
    }
    return drivetrain(kind, us);
}
