/* test_drive.c - the amplifiers and windings (hg_drive.h) against closed
 * forms worked out here from the spec's numbers and the assumed amplifier:
 * the bus-voltage-limited top speed in torque mode at full command,
 * v = (V kt k / R - W/6) / (c + ke kt k^2 / R), k = 2 pi / lead, in pure
 * vertical motion (no sliding friction in that check); the current at
 * standstill is ka V up to i_max; the velocity mode's speed follows the
 * command v_rated V / 10 under load; the winding's current rise has the
 * time constant L / R when the bus limits it; the log the drive uses;
 * and the bad amplifier and friction parameters the check refuses. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_drive.h"
#include "hg_errors.h"

#define PI 3.14159265358979323846

/* The spec's weight per carriage (N): head, six bars, six carriages. */
static double weight6(void)
{
    return 9.81 * (6.697 + 6 * 2.9369 + 6 * 2.867) / 6.0;
}

/* Six equal volts for t_s at dt from HOME; d holds the end state. 0 or a code. */
static int run(const hg_params *p, double volts, double t_s, hg_data *d)
{
    static hg_model m;
    double v[6];
    long s, n = lround(t_s / 1e-3);
    int k, rc = hg_model_init(&m, p, HG_MODEL_REDUCED_CARTESIAN, 0, 0);
    if (rc || (rc = hg_data_reset(&m, d)))
        return rc;
    for (k = 0; k < 6; k++)
        v[k] = volts;
    for (s = 0; s < n && rc == 0; s++)
        rc = hg_step(&m, d, v, 1e-3);
    return rc;
}

static void test_top_speed(void)
{
    const double V = 80.0, R = 2.0, kt = 0.51, k = 2 * PI / 0.010, c = 5665.6;
    const double v_top = (V * kt * k / R - weight6()) / (c + kt * kt * k * k / R);
    hg_params p;
    hg_data d;
    double worst = 0.0, cur;
    int rc, j;
    hg_test_rigid_defaults(&p);
    p.f_coulomb_n = p.f_static_n = 0.0;
    p.stop_max_m = 0.9;                       /* room to reach it */
    p.limit_max_m = 0.85;
    rc = run(&p, 10.0, 1.5, &d);
    for (j = 0; j < 6; j++)
        worst = fmax(worst, fabs(d.zd_mps[j] - v_top));
    cur = (V - kt * k * v_top) / R;
    CHECK(rc == 0 && worst < 1e-9 && fabs(d.current_a[0] - cur) < 1e-9 && cur < p.i_max_a,
          "torque mode, +10 V: bus-limited top speed %.6f mm/s = (V kt k/R - W/6)/(c + ke kt k^2/R) = %.6f mm/s; "
          "current %.6f A = (V - ke k v)/R = %.6f A, below i_max", d.zd_mps[0] * 1e3, v_top * 1e3,
          d.current_a[0], cur);
    /* with the default friction: the sliding force joins the load */
    hg_test_rigid_defaults(&p);
    p.stop_max_m = 0.9;
    p.limit_max_m = 0.85;
    p.v_stribeck_mps = 1e-5;
    rc = run(&p, 10.0, 1.5, &d);
    worst = fabs(d.zd_mps[0] - (V * kt * k / R - weight6() - p.f_coulomb_n) / (c + kt * kt * k * k / R));
    CHECK(rc == 0 && worst < 1e-9, "... with 40 N of sliding friction: %.6f mm/s = (V kt k/R - W/6 - f_c)/(...) "
          "(dev %.1e)", d.zd_mps[0] * 1e3, worst);
}

static void test_standstill_current(void)
{
    hg_params p;
    hg_data d;
    int rc;
    hg_test_rigid_defaults(&p);
    p.f_static_n = 1e4;                        /* held: the current is what the command asks */
    p.f_coulomb_n = 1e4;
    rc = run(&p, 2.5, 0.05, &d);
    CHECK(rc == 0 && d.current_a[0] == 0.8 * 2.5 && fabs(d.zd_mps[0]) < 1e-12,
          "at standstill 2.5 V give ka V = %.6f A", d.current_a[0]);
    rc = run(&p, 10.0, 0.05, &d);
    CHECK(rc == 0 && d.current_a[0] == 8.0, "10 V: the 8 A of i_max (%.6f A)", d.current_a[0]);
}

/* The winding alone: a current step at standstill rises at the bus voltage
 * through L/R; by hg_drive_step on a state at rest. */
static void test_winding(void)
{
    static hg_model m;
    static hg_data d;
    hg_params p;
    hg_drive_out o;
    double v[6] = {10, 0, 0, 0, 0, 0}, tau, is, t_reach, mean_ref;
    hg_test_rigid_defaults(&p);
    hg_model_init(&m, &p, HG_MODEL_REDUCED_CARTESIAN, 0, 0);
    hg_data_reset(&m, &d);
    tau = p.l_winding_h / p.r_winding_ohm;
    is = p.v_bus_v / p.r_winding_ohm;          /* where +V alone would take the current */
    t_reach = -tau * log(1.0 - p.i_max_a / is);  /* 0 -> 8 A at full bus voltage */
    hg_drive_step(m.drive, 6, v, d.current_a, d.zd_mps, d.vloop_int_m, d.amp_enabled, 1e-5, 0, &o);
    CHECK(fabs(o.i_end[0] - is * (1.0 - exp(-1e-5 / tau))) < 1e-12,
          "after 10 us from 0 A towards 8 A: i = (V/R)(1 - exp(-t R/L)) = %.6f A (%.6f)",
          is * (1.0 - exp(-1e-5 / tau)), o.i_end[0]);
    hg_drive_step(m.drive, 6, v, d.current_a, d.zd_mps, d.vloop_int_m, d.amp_enabled, 1e-3, 0, &o);
    /* the exponential part's integral, then 8 A held */
    mean_ref = (is * t_reach - is * tau * (1.0 - exp(-t_reach / tau)) + p.i_max_a * (1e-3 - t_reach)) / 1e-3;
    CHECK(o.i_end[0] == p.i_max_a && fabs(o.i_mean[0] - mean_ref) < 1e-9,
          "over 1 ms: reaches 8 A after %.1f us = -L/R ln(1 - i_max R/V), then holds: mean %.9f A (%.9f)",
          t_reach * 1e6, o.i_mean[0], mean_ref);
    CHECK(fabs(hg_drive_log(1.0001) - log(1.0001)) < 1e-15 && fabs(hg_drive_log(123.0) / log(123.0) - 1) < 1e-12 &&
              fabs(hg_drive_log(1e300) / log(1e300) - 1) < 1e-12,
          "the drive's own ln x matches libm's (x = 1.0001, 123, 1e300)");
}

static void test_velocity_mode(void)
{
    hg_params p;
    hg_data d;
    double want;
    int rc;
    hg_test_rigid_defaults(&p);
    p.amp_mode = 1.0;
    rc = run(&p, 2.0, 1.0, &d);
    want = 2.0 / 10.0 * p.v_rated_mps;
    CHECK(rc == 0 && fabs(d.zd_mps[0] - want) < 1e-9 && fabs(d.zd_mps[5] - want) < 1e-9,
          "velocity mode, 2 V: the carriages move at 2/10 of v_rated = %.6f mm/s (%.9f mm/s), the loop's "
          "integral carrying weight and friction", want * 1e3, d.zd_mps[0] * 1e3);
    rc = run(&p, 0.0, 1.0, &d);
    CHECK(rc == 0 && fabs(d.zd_mps[0]) < 1e-9 && fabs(d.z_m[0]) < 2e-4,
          "velocity mode, 0 V: the amplifier holds the carriages (z' = %.1e m/s, z %.3f mm)", d.zd_mps[0],
          d.z_m[0] * 1e3);
}

/* One bad field: refused naming it. */
static void refused(const char *what, const char *field, hg_params *p)
{
    const char *f = 0, *why = 0;
    int rc = hg_params_check(p, &f, &why);
    CHECK(rc == HG_ERR_BAD_PARAM && f && strcmp(f, field) == 0, "%s: refused, naming %s (%s)", what,
          f ? f : "nothing", why ? why : "");
}

static void test_bad_params(void)
{
    hg_params p;
    hg_test_rigid_defaults(&p);
    p.r_winding_ohm = -1;
    refused("a negative winding resistance", "r_winding", &p);
    hg_test_rigid_defaults(&p);
    p.l_winding_h = -0.001;
    refused("a negative winding inductance", "l_winding", &p);
    hg_test_rigid_defaults(&p);
    p.v_bus_v = 0.9 * p.r_winding_ohm * weight6() / (p.kt_nm_per_a * 2 * PI / p.lead_m);
    refused("a bus voltage below what holds the head (0.9 R I_hold)", "v_bus", &p);
    hg_test_rigid_defaults(&p);
    p.v_bus_v = 1.1 * p.r_winding_ohm * weight6() / (p.kt_nm_per_a * 2 * PI / p.lead_m);
    CHECK(hg_params_check(&p, 0, 0) == 0, "... 1.1 R I_hold is accepted");
    hg_test_rigid_defaults(&p);
    p.f_static_n = 30.0;                       /* below the 40 N of f_coulomb */
    refused("a breakaway force below the sliding force", "f_static", &p);
    hg_test_rigid_defaults(&p);
    p.amp_mode = 2.0;
    refused("amplifier mode 2", "amp_mode", &p);
    hg_test_rigid_defaults(&p);
    p.geo.d_bar_m = 0.059;                     /* the bars are 58.3 mm apart at HOME */
    refused("a bar diameter HOME cannot hold", "d_bar", &p);
    hg_test_rigid_defaults(&p);
    p.geo.cone_carriage_rad = 0.0;
    refused("a carriage joint without range", "cone_carriage", &p);
    hg_test_rigid_defaults(&p);
    p.geo.cone_head_rad = 70.0 * PI / 180.0;   /* with the 24.3 deg tilt at HOME past the head plane */
    refused("a head joint range that lets a bar under the head", "cone_head", &p);
}

int main(void)
{
    test_top_speed();
    test_standstill_current();
    test_winding();
    test_velocity_mode();
    test_bad_params();
    return hg_test_exit();
}
