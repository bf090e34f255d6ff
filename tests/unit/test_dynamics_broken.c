/* test_dynamics_broken.c - the broken-bar step (hg_broken_dae, full
 * coordinates, KKT accelerations, projections). With every bar intact it
 * must follow the ordinary reduced step (a second formulation of the same
 * machine) to integration-error level; with bar 0 broken the head must
 * come down, the energy must not grow beyond the work of the drives, the
 * five intact bars must keep their length (measured with hg_constraints,
 * not the step's own report), and a failure must be a code, never NaN. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_integrate.h"
#include "hg_step_broken.h"
#include "hg_forces.h"
#include "hg_drive.h"
#include "hg_errors.h"
#include "hg_guard_text.h"

/* Largest |z| and head-pose difference (m or rad) between the ordinary
 * Reduced Joints step and the KKT step with no bar broken, 0.2 s of
 * asymmetric volts at time step dt; INFINITY on a failed step. */
static double intact_difference(double dt)
{
    static const double volts[6] = {0.9, 0.5, 0.8, 0.4, 0.7, 0.95};
    hg_params p;
    static hg_model m;
    static hg_data d, ctx;
    double q[12], qd[12], q1[12], qd1[12], qdd[12], fz[6], drive_n[6], res, worst = 0;
    hg_drive_out drv;
    long s, n = (long)(0.2 / dt + 0.5);
    int k;
    hg_test_rigid_defaults(&p);
    p.f_coulomb_n = p.f_static_n = 0.0;   /* two formulations of the same smooth ODE */
    if (hg_model_init(&m, &p, HG_MODEL_REDUCED_JOINTS, 0, 0) || hg_data_reset(&m, &d))
        return INFINITY;
    memset(qd, 0, sizeof qd);
    memcpy(q, d.z_m, sizeof d.z_m);
    memcpy(q + 6, d.pose, sizeof d.pose);
    for (s = 0; s < n; s++) {
        hg_drive_step(m.drive, 6, volts, d.current_a, d.zd_mps, d.vloop_int_m, d.amp_enabled, dt, 0,
                      &drv);                        /* the same drive currents as hg_step's */
        for (k = 0; k < 6; k++)
            drive_n[k] = drv.i_mean[k] * m.drive[k].force_per_amp_n;
        hg_carriage_forces(&m, q, qd, drive_n, fz);
        ctx.broken_bars = 0u;
        if (hg_integrate(&m, m.integrator, &hg_broken_dae, &ctx, q, qd, drive_n, fz, dt,
                         q1, qd1, qdd, &res) || hg_step(&m, &d, volts, dt))
            return INFINITY;
        memcpy(q, q1, sizeof q);
        memcpy(qd, qd1, sizeof qd);
        for (k = 0; k < 6; k++)
            worst = fmax(worst, fmax(fabs(q[k] - d.z_m[k]), fabs(q[6 + k] - d.pose[k])));
    }
    return worst;
}

static void test_intact(void)
{
    double e3 = intact_difference(1e-3), e4 = intact_difference(1e-4);
    CHECK(e3 < 1e-8 && e4 < e3 / 20,
          "no bar broken: KKT step follows the Reduced Joints step over 0.2 s (both with the default "
          "scheme), max difference %.2e (dt 1 ms), %.2e (dt 0.1 ms): integration-error level, shrinking "
          "at second order with dt", e3, e4);
}

/* Bar 0 breaks at HOME while a PD loop on the volts holds the carriages;
 * run up to 3 s or until the step fails. The head hangs on five bars and
 * swings (one degree of freedom): it must strike a limit (a joint's range,
 * two bars touching, or the region the model represents) with a code. */
static void test_bar0(hg_model_kind kind)
{
    const double dt = 1e-3;
    hg_params p;
    hg_model m;
    hg_data d, before;
    double hold, t0, v0, e0, work = 0, worst_gain = 0, worst_len = 0, zmin = 0, t, v, rot = 0;
    long s;
    int k, rc = 0, finite = 1, frozen = 1;
    hg_test_rigid_defaults(&p);
    hg_model_init(&m, &p, kind, 0, 0);
    hg_data_reset(&m, &d);
    hold = p.g_mps2 * (p.m_head_kg + 6 * p.m_bar_kg + 6 * p.m_carriage_kg) / 6 / m.force_per_volt_n;
    d.broken_bars = 1u;
    hg_energy(&m, &d, &t0, &v0);
    e0 = t0 + v0;
    for (s = 0; s < 3000; s++) {
        double volts[6], phi[6], zold[6];
        for (k = 0; k < 6; k++)
            volts[k] = hold - 200.0 * d.z_m[k] - 5.0 * d.zd_mps[k];
        memcpy(zold, d.z_m, sizeof zold);
        before = d;
        rc = hg_step(&m, &d, volts, dt);
        if (rc) {
            before.last_error = d.last_error;
            before.guard = d.guard;
            frozen = memcmp(&before, &d, HG_DATA_STATE_BYTES) == 0;
            break;
        }
        for (k = 0; k < 6; k++)       /* work of drive, friction and stops */
            work += d.force_n[k] * (d.z_m[k] - zold[k]);
        finite = finite && isfinite(d.pose[2]) && isfinite(d.posed[2]) && isfinite(d.z_m[0]);
        hg_energy(&m, &d, &t, &v);
        worst_gain = fmax(worst_gain, t + v - e0 - work);
        hg_constraints(&p.geo, d.z_m, d.pose, phi);
        for (k = 1; k < 6; k++)
            worst_len = fmax(worst_len, fabs(phi[k]) / (2 * p.geo.l_m));
        zmin = fmin(zmin, d.pose[2]);
    }
    printf("# %s, bar 0 broken: %ld steps (%.3f s), %s; head Z min %.2f mm, now X %.1f Y %.1f "
           "Z %.1f mm A %.1f B %.1f C %.1f deg\n", hg_model_name(kind), s, d.t_s,
           rc ? hg_strerror(rc) : "still running", zmin * 1e3, d.pose[0] * 1e3, d.pose[1] * 1e3,
           d.pose[2] * 1e3, d.pose[3] * 57.2958, d.pose[4] * 57.2958, d.pose[5] * 57.2958);
    for (k = 3; k < 6; k++)
        rot = fmax(rot, fabs(d.pose[k]));
    CHECK(zmin < -1e-4, "%s, bar 0 broken: the head comes down (lowest Z %.2f mm)",
          hg_model_name(kind), zmin * 1e3);
    CHECK(worst_gain < 0.01, "%s, bar 0 broken: E - E0 - work of the carriage forces <= %.2e J "
          "(no energy from nowhere; E0 = %.2f J)", hg_model_name(kind), worst_gain, e0);
    CHECK(worst_len < 1e-9, "%s, bar 0 broken: the five intact bars keep their length "
          "(max error %.2e m)", hg_model_name(kind), worst_len);
    {
        char what[HG_GUARD_TEXT_LEN];
        hg_guard_describe(&d.guard, 0, what);
        CHECK(finite && (rc == HG_ERR_OUT_OF_VOLUME || rc == HG_ERR_JOINT_RANGE || rc == HG_ERR_BAR_CLEARANCE) &&
              frozen && d.last_error == rc && d.guard.kind != HG_GUARD_NONE &&
              (d.guard.kind == HG_GUARD_REGION ? fabs(d.guard.value) > d.guard.limit
               : d.guard.kind == HG_GUARD_BARS ? d.guard.value < d.guard.limit : d.guard.value > d.guard.limit) &&
              rot <= HG_BROKEN_ROT_MAX_RAD,
              "%s, bar 0 broken: no NaN; at t = %.3f s the swing strikes a limit (code %d, %s: %s), "
              "state left at the last good step (largest head angle %.2f deg)", hg_model_name(kind),
              d.t_s, rc, hg_strerror(rc), what, rot * 57.29578);
    }
}

/* Every bar broken: the head drops out of the volume; a code, not NaN. */
static void test_all_broken(void)
{
    static const double off[6] = {0, 0, 0, 0, 0, 0};
    hg_params p;
    hg_model m;
    hg_data d;
    long s;
    int rc = 0;
    hg_test_rigid_defaults(&p);
    hg_model_init(&m, &p, HG_MODEL_REDUCED_CARTESIAN, 0, 0);
    hg_data_reset(&m, &d);
    d.broken_bars = HG_BARS_ALL;
    for (s = 0; s < 5000 && rc == 0; s++)
        rc = hg_step(&m, &d, off, 1e-3);
    CHECK(rc == HG_ERR_OUT_OF_VOLUME && d.last_error == rc && isfinite(d.pose[2]) &&
          d.pose[2] >= HG_BROKEN_HEAD_Z_MIN_M && d.pose[2] < HG_BROKEN_HEAD_Z_MIN_M + 0.05,
          "all bars broken: the head falls to Z = %.3f m at t = %.3f s, then %s (code %d)",
          d.pose[2], d.t_s, hg_strerror(rc), rc);
}

int main(void)
{
    int kind;
    test_intact();
    for (kind = 0; kind < HG_MODEL_COUNT; kind++)
        test_bar0((hg_model_kind)kind);
    test_all_broken();
    return hg_test_exit();
}
