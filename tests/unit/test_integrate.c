/* test_integrate.c - the integration schemes (hg_integrate.h). Each
 * scheme's measured convergence order must be its theoretical order
 * (improved Euler 1: first order in the velocity, which drives the
 * position; Heun 2; RK4 4), on every parametrization: the error of the
 * carriage velocities after 0.25 s of asymmetric drive voltages against
 * RK4 at 10 us, at dt = 2, 1 and 0.5 ms, order = log2 of the error ratio.
 * (Velocities: with z independent, Heun's position error has a
 * higher-order part that still dominates at these steps, 1.8 instead of
 * 2; the velocity shows the scheme's order from 2 ms on.)
 * The orders are measured on the smooth machine (sliding and static
 * friction off: stick-slip events are first order for any fixed step).
 * Every run starts at HOME at rest with the windings carrying the
 * commanded currents (the current's rise within the first step, with
 * friction a cascade of stick-slip events inside it, is an event too).
 * Also: the default is Heun, a bad scheme number is
 * refused and changes nothing, the fused kind's generated accelerations
 * agree with the Reduced Cartesian algebra under Heun and RK4, and Heun and RK4 meet
 * the 1 um goal at the 1 ms servo period with the default friction on. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_errors.h"

#define T_END 0.25

static const double volts[6] = {1.7, -0.9, 0.4, 1.1, -0.6, 0.8};
static const int theory[HG_INTEGRATOR_COUNT] = {1, 2, 4};

/* z, z' (z[6..11]) and pose at T_END with `scheme` at step dt, with the
 * default friction or (smooth = 1) without sliding and static friction
 * (the ODE of the schemes' orders); 0 or a code. */
static int run(hg_model_kind kind, int scheme, double dt, double z[12], double pose[6], int smooth)
{
    static hg_model m;
    static hg_data d;
    hg_params p;
    long s, n = lround(T_END / dt);
    int rc;
    hg_test_rigid_defaults(&p);
    if (smooth) {
        hg_params_set(&p, "f_coulomb", 0.0);
        hg_params_set(&p, "f_static", 0.0);
    }
    if ((rc = hg_model_init(&m, &p, kind, 0, 0)) || (rc = hg_model_set_integrator(&m, scheme)) ||
        (rc = hg_data_reset(&m, &d)))
        return rc;
    for (s = 0; s < 6; s++)           /* the windings already carry the commanded currents: no */
        d.current_a[s] = p.ka_a_per_v * volts[s]; /* sub-step rise at t = 0, which is an event */
    for (s = 0; s < n; s++)
        if ((rc = hg_step(&m, &d, volts, dt)))
            return rc;
    memcpy(z, d.z_m, sizeof d.z_m);
    memcpy(z + 6, d.zd_mps, sizeof d.zd_mps);
    if (pose)
        memcpy(pose, d.pose, sizeof d.pose);
    return 0;
}

static double maxdiff(const double *a, const double *b, int n)
{
    double e = 0;
    int k;
    for (k = 0; k < n; k++)
        e = fmax(e, fabs(a[k] - b[k]));
    return e;
}

static void test_orders(hg_model_kind kind)
{
    static const double dts[3] = {2e-3, 1e-3, 5e-4};
    double zref[12], zfric[12], z[12], e[3], ez = 0;
    int s, i, rc = run(kind, HG_INTEGRATOR_RK4, 1e-5, zref, 0, 1);
    rc = rc ? rc : run(kind, HG_INTEGRATOR_RK4, 1e-5, zfric, 0, 0);
    for (s = 0; s < HG_INTEGRATOR_COUNT; s++) {
        double o1, o2;
        for (i = 0; i < 3; i++) {
            int r = run(kind, s, dts[i], z, 0, 1);
            e[i] = (rc || r) ? NAN : maxdiff(z + 6, zref + 6, 6);
        }
        /* the 1 ms servo period with the defaults: friction, stick-slip included */
        i = run(kind, s, 1e-3, z, 0, 0);
        ez = (rc || i) ? NAN : maxdiff(z, zfric, 6);
        o1 = log2(e[0] / e[1]);
        o2 = log2(e[1] / e[2]);
        CHECK(fabs(o1 - theory[s]) < 0.25 && fabs(o2 - theory[s]) < 0.25,
              "%s, %s: measured order %.2f (2 -> 1 ms), %.2f (1 -> 0.5 ms), theory %d "
              "(z' errors %.2e %.2e %.2e m/s)", hg_model_name(kind), hg_integrator_name((hg_integrator)s),
              o1, o2, theory[s], e[0], e[1], e[2]);
        if (s != HG_INTEGRATOR_IMPROVED_EULER)
            CHECK(ez < 1e-6, "%s, %s at the 1 ms servo period, default friction: z %.2e m from the "
                  "converged answer (goal: 1 um, one encoder count)", hg_model_name(kind),
                  hg_integrator_name((hg_integrator)s), ez);
    }
}

static void test_contract(void)
{
    static hg_model m;
    hg_params p;
    double za[12], zb[12], pa[6], pb[6];
    int s, rc;
    hg_test_rigid_defaults(&p);
    hg_model_init(&m, &p, HG_MODEL_REDUCED_CARTESIAN, 0, 0);
    CHECK(m.integrator == HG_INTEGRATOR_HEUN, "hg_model_init chooses Heun");
    rc = hg_model_set_integrator(&m, HG_INTEGRATOR_COUNT);
    CHECK(rc == HG_ERR_BAD_PARAM && m.integrator == HG_INTEGRATOR_HEUN,
          "integrator %d refused (%s), the scheme in force kept", HG_INTEGRATOR_COUNT, hg_strerror(rc));
    rc = hg_model_set_integrator(&m, -1);
    CHECK(rc == HG_ERR_BAD_PARAM && m.integrator == HG_INTEGRATOR_HEUN, "integrator -1 refused");
    for (s = HG_INTEGRATOR_HEUN; s < HG_INTEGRATOR_COUNT; s++) {
        int r1 = run(HG_MODEL_FUSED_CARTESIAN, s, 1e-3, za, pa, 0);
        int r2 = run(HG_MODEL_REDUCED_CARTESIAN, s, 1e-3, zb, pb, 0);
        double dz = fmax(maxdiff(za, zb, 6), maxdiff(pa, pb, 3));
        CHECK(r1 == 0 && r2 == 0 && dz < 1e-12,
              "fused-cartesian with %s (generated accelerations) = reduced-cartesian with %s "
              "(hand-written algebra) after 0.25 s: %.1e m apart",
              hg_integrator_name((hg_integrator)s), hg_integrator_name((hg_integrator)s), dz);
    }
}

int main(void)
{
    int kind;
    test_contract();
    for (kind = 0; kind < HG_MODEL_COUNT; kind++)
        test_orders((hg_model_kind)kind);
    return hg_test_exit();
}
