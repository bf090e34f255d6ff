/* test_dynamics.c - closed-form facts of docs/model.md, the
 * agreement of the parametrizations, the hard stop and refused inputs.
 * Expected values are computed here from the spec's numbers, never taken
 * from the code under test. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_errors.h"
#include "hg_linalg.h"

/* the spec's tables (docs/model.md) */
#define SPEC_G 9.81
#define SPEC_M_HEAD 6.697
#define SPEC_M_BAR 2.9369
#define SPEC_M_CARRIAGE 2.867
#define SPEC_LEAD 0.010
#define SPEC_J_ROTOR 1.3168e-4
#define SPEC_KA 0.8
#define SPEC_KT 0.51
#define SPEC_C_VISC 5665.6
#define SPEC_PI 3.14159265358979323846

static const double spec_weight = SPEC_G * (SPEC_M_HEAD + 6 * SPEC_M_BAR + 6 * SPEC_M_CARRIAGE);

static int run(const hg_model *m, hg_data *d, const double volts[6], double dt, double t_end)
{
    long n = (long)floor(t_end / dt + 0.5), s;
    for (s = 0; s < n; s++) {
        int rc = hg_step(m, d, volts, dt);
        if (rc)
            return rc;
    }
    return 0;
}

static void test_sinking(hg_model_kind kind)
{
    hg_params p;
    hg_model m;
    hg_data d;
    double v0[6] = {0, 0, 0, 0, 0, 0}, expect = -spec_weight / (6 * SPEC_C_VISC), worst = 0;
    int rc, k;
    hg_test_rigid_defaults(&p);
    hg_params_set(&p, "f_coulomb", 0.0);   /* W / (6 c_visc) is viscous friction alone */
    hg_params_set(&p, "f_static", 0.0);
    hg_model_init(&m, &p, kind, 0, 0);
    hg_data_reset(&m, &d);
    rc = run(&m, &d, v0, 1e-3, 0.3);
    for (k = 0; k < 6; k++)
        worst = fmax(worst, fabs(d.zd_mps[k] - expect));
    CHECK(rc == 0 && worst < 1e-6 * fabs(expect),
          "%s: drives off, sinking speed %.9f m/s = W/(6 c_visc) = %.9f (max dev %.2e)",
          hg_model_name(kind), d.zd_mps[0], expect, worst);
    CHECK(fabs(d.pose[0]) + fabs(d.pose[1]) + fabs(d.pose[3]) + fabs(d.pose[4]) + fabs(d.pose[5]) < 1e-12,
          "%s: sinking is a pure vertical translation", hg_model_name(kind));
}

/* Sliding and static friction at 0 V from HOME (closed forms of issue 16):
 * with breakaway below W/6 the machine sinks at exactly (W/6 - f_c)/c_visc;
 * with breakaway above W/6 it stays exactly where it is. */
static void test_friction(hg_model_kind kind)
{
    hg_params p;
    hg_model m;
    hg_data d;
    double v0[6] = {0, 0, 0, 0, 0, 0}, fc = 30.0, expect, worst = 0;
    int rc, k;
    hg_test_rigid_defaults(&p);
    p.f_coulomb_n = fc;
    p.f_static_n = 45.0;                    /* below W/6 = 67.9 N: breaks away */
    p.v_stribeck_mps = 0.0005;              /* the Stribeck part is gone at the sinking speed */
    expect = -(spec_weight / 6 - fc) / SPEC_C_VISC;
    hg_model_init(&m, &p, kind, 0, 0);
    hg_data_reset(&m, &d);
    rc = run(&m, &d, v0, 1e-3, 1.0);
    for (k = 0; k < 6; k++)
        worst = fmax(worst, fabs(d.zd_mps[k] - expect));
    CHECK(rc == 0 && worst < 1e-6 * fabs(expect) && d.stuck == 0,
          "%s: 0 V, breakaway 45 N < W/6: sinks at %.6f mm/s = -(W/6 - f_c)/c_visc = %.6f mm/s (dev %.1e)",
          hg_model_name(kind), d.zd_mps[0] * 1e3, expect * 1e3, worst);
    p.f_coulomb_n = 60.0;
    p.f_static_n = 70.0;                    /* above W/6 = 67.886 N: holds */
    hg_model_init(&m, &p, kind, 0, 0);
    hg_data_reset(&m, &d);
    rc = run(&m, &d, v0, 1e-3, 1.0);
    worst = 0;
    for (k = 0; k < 6; k++)
        worst = fmax(worst, fabs(d.z_m[k]) + fabs(d.zd_mps[k]));
    CHECK(rc == 0 && worst < 1e-15 && d.stuck == HG_BARS_ALL,
          "%s: 0 V, breakaway 70 N > W/6: after 1 s every carriage at HOME, at rest, to rounding "
          "(|z|+|z'| = %.1e m; no creep)",
          hg_model_name(kind), worst);
}

static void test_holding(hg_model_kind kind)
{
    hg_params p;
    hg_model m;
    hg_data d;
    double hold = (spec_weight / 6) / (SPEC_KA * SPEC_KT * 2 * SPEC_PI / SPEC_LEAD), v[6], worst = 0;
    int rc, k;
    for (k = 0; k < 6; k++)
        v[k] = hold;
    hg_test_rigid_defaults(&p);
    hg_params_set(&p, "f_coulomb", 0.0);   /* viscous friction only: any imbalance moves it */
    hg_params_set(&p, "f_static", 0.0);
    hg_model_init(&m, &p, kind, 0, 0);
    hg_data_reset(&m, &d);
    for (k = 0; k < 6; k++)            /* the windings already carry the holding current */
        d.current_a[k] = SPEC_KA * hold;
    rc = run(&m, &d, v, 1e-3, 1.0);
    for (k = 0; k < 6; k++)
        worst = fmax(worst, fabs(d.z_m[k]) + fabs(d.zd_mps[k]));
    CHECK(rc == 0 && worst < 1e-9, "%s: %.6f V on every drive holds HOME for 1 s (|z|+|z'| <= %.2e)",
          hg_model_name(kind), hold, worst);
    /* and 1% less sinks */
    for (k = 0; k < 6; k++)
        v[k] = 0.99 * hold;
    hg_data_reset(&m, &d);
    rc = run(&m, &d, v, 1e-3, 0.2);
    CHECK(rc == 0 && d.zd_mps[0] < -1e-4, "%s: 1%% below the holding voltage sinks (z' = %.3g m/s)",
          hg_model_name(kind), d.zd_mps[0]);
}

static void test_free_fall(hg_model_kind kind)
{
    hg_params p;
    hg_model m;
    hg_data d;
    double v0[6] = {0, 0, 0, 0, 0, 0};
    double rotor = SPEC_J_ROTOR * (2 * SPEC_PI / SPEC_LEAD) * (2 * SPEC_PI / SPEC_LEAD);
    double mass = SPEC_M_HEAD + 6 * SPEC_M_BAR + 6 * SPEC_M_CARRIAGE + 6 * rotor;
    double a = -spec_weight / mass, t = 0.2, worst = 0;
    int rc, k;
    hg_test_rigid_defaults(&p);
    rc = hg_test_frictionless(&p);
    hg_model_init(&m, &p, kind, 0, 0);
    hg_data_reset(&m, &d);
    rc = rc ? rc : run(&m, &d, v0, 1e-3, t);
    for (k = 0; k < 6; k++)
        worst = fmax(worst, fabs(d.zdd_mps2[k] - a) / fabs(a));
    CHECK(rc == 0 && worst < 1e-9, "%s: frictionless free fall z'' = %.9f = -W/M = %.9f m/s^2",
          hg_model_name(kind), d.zdd_mps2[0], a);
    CHECK(fabs(d.z_m[0] - 0.5 * a * t * t) < 1e-9 && fabs(d.pose[2] - 0.5 * a * t * t) < 1e-9,
          "%s: after %.1f s z = %.9f m = a t^2/2 = %.9f m (head Z %.9f)", hg_model_name(kind), t,
          d.z_m[0], 0.5 * a * t * t, d.pose[2]);
}

/* Same asymmetric voltages for 0.5 s at dt 1e-4 s: joints agree within 1e-3 mm. */
static void test_agreement(void)
{
    static const double v[6] = {1.5, -2.0, 0.7, 2.5, -1.2, 0.3};
    hg_params p;
    hg_data d[HG_MODEL_COUNT];
    int kind, k, ok = 1;
    double worst = 0, worst_pose = 0;
    hg_test_rigid_defaults(&p);
    for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
        hg_model m;
        ok &= hg_model_init(&m, &p, kind, 0, 0) == 0;
        ok &= hg_data_reset(&m, &d[kind]) == 0;
        ok &= run(&m, &d[kind], v, 1e-4, 0.5) == 0;
    }
    for (kind = 1; kind < HG_MODEL_COUNT; kind++)
        for (k = 0; k < 6; k++) {
            worst = fmax(worst, fabs(d[kind].z_m[k] - d[0].z_m[k]));
            worst_pose = fmax(worst_pose, fabs(d[kind].pose[k] - d[0].pose[k]));
        }
    CHECK(ok && worst < 1e-6, "all parametrizations agree after 0.5 s: max joint difference %.3e mm "
          "(limit 1e-3 mm), pose %.3e m/rad; joint 0 moved %.3f mm", worst * 1e3, worst_pose,
          d[0].z_m[0] * 1e3);
    {
        double diff_sj = 0;
        for (k = 0; k < 6; k++)
            diff_sj = fmax(diff_sj, fabs(d[HG_MODEL_REDUCED_JOINTS].z_m[k] - d[0].z_m[k]));
        printf("# standard vs reduced-joints %.3e mm, standard vs reduced-cartesian %.3e mm, "
               "reduced-cartesian vs fused %.3e mm\n", diff_sj * 1e3,
               fabs(d[HG_MODEL_REDUCED_CARTESIAN].z_m[0] - d[0].z_m[0]) * 1e3,
               fabs(d[HG_MODEL_REDUCED_CARTESIAN].z_m[0] - d[HG_MODEL_FUSED_CARTESIAN].z_m[0]) * 1e3);
    }
}

static void test_stop(hg_model_kind kind)
{
    hg_params p;
    hg_model m;
    hg_data d;
    double v[6] = {10, 10, 10, 10, 10, 10}, worst = 0;
    int rc, k, s, finite = 1;
    hg_test_rigid_defaults(&p);
    hg_model_init(&m, &p, kind, 0, 0);
    hg_data_reset(&m, &d);
    rc = 0;
    for (s = 0; s < 2000 && rc == 0; s++) {
        rc = hg_step(&m, &d, v, 1e-3);
        for (k = 0; k < 6; k++)
            finite &= isfinite(d.z_m[k]) && isfinite(d.zd_mps[k]);
    }
    for (k = 0; k < 6; k++)
        worst = fmax(worst, fabs(d.z_m[k] - p.stop_max_m));
    CHECK(rc == 0 && finite && worst < 1e-3,
          "%s: +10 V for 2 s ends at the top stop: z = %.4f mm, stop %.1f mm (max distance %.3f mm)",
          hg_model_name(kind), d.z_m[0] * 1e3, p.stop_max_m * 1e3, worst * 1e3);
}

/* A step that fails for real (dt = 10 ms into the hard stops makes the
 * explicit step unstable) reports it and leaves the state as it was. */
static void test_failure_leaves_state(hg_model_kind kind)
{
    hg_params p;
    hg_model m;
    hg_data d, before;
    double v[6] = {10, -10, 10, -10, 10, -10};
    int rc = 0, s, finite = 1;
    hg_test_rigid_defaults(&p);
    hg_model_init(&m, &p, kind, 0, 0);
    hg_data_reset(&m, &d);
    for (s = 0; s < 5000 && rc == 0; s++) {
        before = d;
        rc = hg_step(&m, &d, v, 0.01);
        finite &= hg_all_finite(6, d.z_m) && hg_all_finite(6, d.pose) && hg_all_finite(6, d.zd_mps);
    }
    d.last_error = before.last_error;
    d.guard = before.guard;           /* the diagnosis of the failure: may change */
    CHECK(rc < 0 && finite && memcmp(&d, &before, HG_DATA_STATE_BYTES) == 0,
          "%s: unstable run fails at t = %.2f s with '%s', state untouched and finite",
          hg_model_name(kind), before.t_s, hg_strerror(rc));
}

static void test_refused(void)
{
    hg_params p;
    hg_model m;
    hg_data d, before;
    const char *bad = 0, *why = 0;
    double v[6] = {1, 1, 1, 1, 1, 1};
    int rc;
    hg_test_rigid_defaults(&p);
    p.m_head_kg = 0;
    rc = hg_model_init(&m, &p, HG_MODEL_REDUCED_CARTESIAN, &bad, &why);
    CHECK(rc == HG_ERR_BAD_PARAM && bad && strcmp(bad, "m_head") == 0,
          "m_head = 0 refused naming m_head (%s)", why ? why : "-");
    hg_test_rigid_defaults(&p);
    p.m_carriage_kg = -1;
    rc = hg_model_init(&m, &p, HG_MODEL_STANDARD, &bad, &why);
    CHECK(rc == HG_ERR_BAD_PARAM && bad && strcmp(bad, "m_carriage") == 0, "m_carriage < 0 refused");
    hg_test_rigid_defaults(&p);
    p.geo.l_m = 0.3;
    rc = hg_model_init(&m, &p, HG_MODEL_REDUCED_JOINTS, &bad, &why);
    CHECK(rc == HG_ERR_BAD_PARAM && bad && strcmp(bad, "l") == 0, "bars too short refused naming l (%s)",
          why ? why : "-");
    hg_test_rigid_defaults(&p);
    rc = hg_model_init(&m, &p, (hg_model_kind)7, &bad, &why);
    CHECK(rc == HG_ERR_BAD_PARAM, "unknown parametrization refused");
    hg_model_init(&m, &p, HG_MODEL_REDUCED_CARTESIAN, 0, 0);
    hg_data_reset(&m, &d);
    run(&m, &d, v, 1e-3, 0.05);
    before = d;
    rc = hg_step(&m, &d, v, 0.0);
    d.last_error = before.last_error;
    CHECK(rc == HG_ERR_BAD_DT && memcmp(&d, &before, HG_DATA_STATE_BYTES) == 0, "dt = 0 refused, state untouched");
    rc = hg_step(&m, &d, v, -1e-3);
    CHECK(rc == HG_ERR_BAD_DT && d.last_error == HG_ERR_BAD_DT, "dt < 0 refused and latched");
    rc = hg_step(&m, &d, v, NAN);
    CHECK(rc == HG_ERR_BAD_DT, "dt = NaN refused");
    {
        double vn[6] = {NAN, INFINITY, 0, 0, 0, 0};
        rc = hg_step(&m, &d, vn, 1e-3);
        CHECK(rc == 0 && d.current_a[0] == 0 && d.current_a[1] == 0,
              "non-finite volts count as 0 V (current %.1f A)", d.current_a[1]);
    }
    CHECK(hg_model_from_name("reduced-cartesian") == HG_MODEL_REDUCED_CARTESIAN &&
          hg_model_from_name("standard") == HG_MODEL_STANDARD && hg_model_from_name("nope") == -1 &&
          hg_model_name((hg_model_kind)9) == 0, "model names round-trip, unknown names refused");
}

int main(void)
{
    int kind;
    for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
        test_sinking((hg_model_kind)kind);
        test_holding((hg_model_kind)kind);
        test_friction((hg_model_kind)kind);
        test_free_fall((hg_model_kind)kind);
        test_stop((hg_model_kind)kind);
        test_failure_leaves_state((hg_model_kind)kind);
    }
    test_agreement();
    test_refused();
    return hg_test_exit();
}
