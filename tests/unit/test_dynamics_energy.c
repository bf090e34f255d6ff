/* test_dynamics_energy.c - energy conservation without friction and
 * drives (error shrinking with dt) and constraint drift under the
 * one-iteration stabilization over 60 s of motion. The bar-length error is
 * measured here with hg_constraints, independently of the step's report. */
#include <math.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_errors.h"

#define PI 3.14159265358979323846

/* Kick the machine with asymmetric volts (no friction), then coast with the
 * drives off: max |E(t) - E(coast start)| over the coast, relative to the
 * kinetic energy at its start. */
static double energy_error(hg_model_kind kind, double dt, double *e_kin)
{
    static const double kick[6] = {0.25, -0.2, 0.15, -0.25, 0.2, -0.1};
    static const double off[6] = {0, 0, 0, 0, 0, 0};
    hg_params p;
    hg_model m;
    hg_data d;
    double t, v, e0, worst = 0;
    long s, n_kick = (long)(0.1 / dt + 0.5), n_coast = (long)(0.3 / dt + 0.5);
    hg_test_rigid_defaults(&p);
    if (hg_test_frictionless(&p) || hg_model_init(&m, &p, kind, 0, 0) || hg_data_reset(&m, &d))
        return INFINITY;
    for (s = 0; s < n_kick; s++)
        if (hg_step(&m, &d, kick, dt))
            return INFINITY;
    d.amp_enabled = 0;                /* drives off: no current, no back-EMF braking */
    hg_energy(&m, &d, &t, &v);
    e0 = t + v;
    *e_kin = t;
    for (s = 0; s < n_coast; s++) {
        if (hg_step(&m, &d, off, dt))
            return INFINITY;
        hg_energy(&m, &d, &t, &v);
        worst = fmax(worst, fabs(t + v - e0));
    }
    return worst / *e_kin;
}

static void test_energy(hg_model_kind kind)
{
    double ek, e3 = energy_error(kind, 1e-3, &ek), e4, e5;
    e4 = energy_error(kind, 1e-4, &ek);
    e5 = energy_error(kind, 1e-5, &ek);
    CHECK(e3 < 1e-2 && e4 < e3 / 5 && e5 < e4 / 5,
          "%s: coasting without friction, max |dE|/T0 = %.2e (dt 1 ms), %.2e (0.1 ms), %.2e (0.01 ms); "
          "T0 = %.3f J", hg_model_name(kind), e3, e4, e5, ek);
}

/* 60 s of sinusoidal volts about the holding voltage at dt = 1 ms. */
static void test_drift(hg_model_kind kind)
{
    hg_params p;
    hg_model m;
    hg_data d;
    double worst = 0, reported = 0, travel = 0, hold;
    long s, n = 60000;
    int rc = 0, k;
    hg_test_rigid_defaults(&p);
    /* uncoordinated volts tilt the head beyond the real joints' ranges:
     * widen them, this test is about the constraint drift alone */
    p.geo.cone_carriage_rad = 1.5;
    p.geo.cone_head_rad = 1.1;
    p.geo.d_bar_m = 1e-3;
    hg_model_init(&m, &p, kind, 0, 0);
    hg_data_reset(&m, &d);
    hold = 9.81 * (p.m_head_kg + 6 * p.m_bar_kg + 6 * p.m_carriage_kg) / 6 / m.force_per_volt_n;
    for (s = 0; s < n && rc == 0; s++) {
        double v[6], phi[6], t = s * 1e-3;
        for (k = 0; k < 6; k++)
            v[k] = hold + 2.0 * sin(2 * PI * (0.3 + 0.07 * k) * t + k);
        rc = hg_step(&m, &d, v, 1e-3);
        hg_constraints(&p.geo, d.z_m, d.pose, phi);
        for (k = 0; k < 6; k++) {
            worst = fmax(worst, fabs(phi[k]) / (2 * p.geo.l_m));
            travel = fmax(travel, fabs(d.z_m[k]));
        }
        reported = fmax(reported, d.residual_m);
    }
    CHECK(rc == 0 && worst < 1e-9,
          "%s: 60 s of motion (carriages up to %.0f mm from HOME): max bar-length error %.2e m "
          "(reported %.2e m)", hg_model_name(kind), travel * 1e3, worst, reported);
    if (kind == HG_MODEL_STANDARD) {
        /* the bar directions must stay consistent with the joints too */
        double B[6][3], A[6][3], wb = 0;
        hg_joint_points(&p.geo, d.z_m, d.pose, B, A);
        for (k = 0; k < 6; k++) {
            double ph = d.bar_rad[2 * k], th = d.bar_rad[2 * k + 1];
            double u[3] = {-sin(th), sin(ph) * cos(th), -cos(ph) * cos(th)};
            int r;
            for (r = 0; r < 3; r++)
                wb = fmax(wb, fabs(B[k][r] + p.geo.l_m * u[r] - A[k][r]));
        }
        CHECK(wb < 1e-9, "standard: bar ends meet the head joints after 60 s (%.2e m)", wb);
    }
}

int main(void)
{
    int kind;
    for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
        test_energy((hg_model_kind)kind);
        test_drift((hg_model_kind)kind);
    }
    return hg_test_exit();
}
