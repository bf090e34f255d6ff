/* test_loop.c - the offline closed loop (hg_loop) against independent facts:
 * the integrator settles at the volts that hold the machine's weight (W/6 per
 * carriage at HOME, within one DAC step), f-error is motion's (previous
 * command minus the encoder position), a vertical move keeps the six joints
 * identical (symmetry), gains that make the loop unstable trip it, and a
 * pid disabled through hg_loop_step_io drives 0 V (its carriage sinks). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "hg_errors.h"
#include "hg_loop.h"
#include "hg_scheme.h"
#include "hg_params.h"
#include "hg_test.h"

int main(void)
{
    hg_loop *L = malloc(sizeof *L);
    hg_loop_config c;
    hg_loop_sample s;
    hg_loop_summary sum;
    hg_params p;
    double cmd[6] = {0}, w, hold, fpv, dac_step = 20.0 / 8191.0, *traj, fe3[18], out3[18];
    hg_board_params bp;
    int k, i, rc;
    long n = 3000;

    hg_params_default(&p);
    w = (p.m_head_kg + 6 * (p.m_bar_kg + p.m_carriage_kg)) * p.g_mps2;
    fpv = p.ka_a_per_v * p.kt_nm_per_a * 2 * 3.14159265358979323846 / p.lead_m;
    hold = w / 6 / fpv;

    hg_loop_config_default(&c);
    for (k = 0; k < 6; k++) {   /* the hand-tuned gains of docs/linuxcnc.md */
        c.pid[k].pgain = 5.0;
        c.pid[k].igain = 100.0;
        c.pid[k].dgain = 0.04;
        c.pid[k].ff1 = 0.0221;
        c.pid[k].ff2 = 0.00023;
        c.pid[k].maxoutput = 10.0;
    }
    /* without sliding and static friction the integrator settles at the
     * voltage that balances W/6; with them anywhere the breakaway allows */
    {
        hg_params q = p;
        q.f_coulomb_n = q.f_static_n = 0.0;
        hg_test_block(&bp, &q, 1, HG_INTEGRATOR_HEUN);
    }
    rc = hg_loop_init(L, &c, &bp);
    CHECK(rc == 0, "init at HOME: %d", rc);
    for (i = 0; i < 3000 && rc == 0; i++)
        rc = hg_loop_step(L, cmd, &s);
    CHECK(rc == 0, "3 s holding HOME");
    for (k = 0; k < 6; k++)
        CHECK(fabs(s.output_v[k] - hold) < 1.5 * dac_step,
              "joint %d, no sliding or static friction: integrator holds the weight: %.5f V vs "
              "W/6/(ka kt 2pi/lead) = %.5f V", k, s.output_v[k], hold);
    rc = hg_loop_init(L, &c, 0);
    for (i = 0; i < 3000 && rc == 0; i++)
        rc = hg_loop_step(L, cmd, &s);
    for (k = 0; k < 6; k++)
        CHECK(rc == 0 && fabs(s.output_v[k] - hold) <= p.f_static_n / fpv + 1.5 * dac_step,
              "joint %d, default friction: holds at %.5f V, within the breakaway band %.5f +- %.5f V "
              "(f_static / (ka kt 2pi/lead))", k, s.output_v[k], hold, p.f_static_n / fpv);
    CHECK(fabs(s.ferror_mm[0]) <= 0.0011, "at rest the f-error is within a count: %.4f mm", s.ferror_mm[0]);

    /* f-error is the previous command minus the position read this period */
    cmd[0] = 0.5;
    hg_loop_step(L, cmd, &s);
    hg_loop_step(L, cmd, &s);
    CHECK(fabs(s.ferror_mm[0] - (0.5 - s.fb_mm[0])) < 1e-12, "f-error = previous command - encoder position");

    /* vertical move at HOME: all six joints the same (the rigid train: with
     * springs, a stick-slip decision at the threshold may fall differently
     * on one post by rounding, and the runs part) */
    traj = malloc(sizeof(double) * 6 * n);
    for (i = 0; i < n; i++)
        for (k = 0; k < 6; k++)
            traj[6 * i + k] = 20.0 * (1 - cos(3.14159265358979323846 * i / n)) / 2;
    {
        hg_params q = p;
        q.k_axial_n_per_m = 0.0;
        hg_test_block(&bp, &q, 1, HG_INTEGRATOR_HEUN);
        hg_loop_init(L, &c, &bp);
    }
    rc = hg_loop_run(L, traj, n, 0, 0, 0, &sum);
    CHECK(rc == 0 && sum.periods == n, "20 mm vertical move runs");
    for (k = 1; k < 6; k++)
        CHECK(fabs(sum.peak_ferror_mm[k] - sum.peak_ferror_mm[0]) < 1e-9, "joint %d peak f-error = joint 0's (%.5f mm)",
              k, sum.peak_ferror_mm[k]);

    /* hg_loop_step_io: pid.N.enable off gives 0 V on that drive every period
     * (pid.c's output when disabled): its carriage sinks, the others hold */
    {
        static const int en[6] = {1, 1, 0, 1, 1, 1};
        double z0[6] = {0}, vmax = 0;
        hg_loop_init(L, &c, 0);
        for (i = 0; i < 500; i++) {
            hg_loop_step_io(L, z0, en, c.period_ns, &s);
            if (fabs(s.output_v[2]) > vmax)
                vmax = fabs(s.output_v[2]);
        }
        CHECK(vmax == 0.0, "step_io: disabled pid.2 outputs 0 V (max %.3g)", vmax);
        CHECK(L->out.pos[2] < L->out.pos[0] - 1e-4 && fabs(L->out.pos[0]) < 1e-4,
              "step_io: joint 2 sinks (%.4f mm), joint 0 holds (%.4f mm)", L->out.pos[2] * 1e3, L->out.pos[0] * 1e3);
    }

    /* far too much gain: the loop oscillates and trips at the f-error limit */
    for (k = 0; k < 6; k++)
        c.pid[k].dgain = -0.5;   /* negative damping */
    c.ferror_limit_mm = 2.0;
    hg_loop_init(L, &c, 0);
    rc = hg_loop_run(L, traj, n, 0, 0, 0, &sum);
    CHECK(sum.tripped_at >= 0 || rc != 0, "D = -0.5 V/(mm/s) is unstable: tripped at period %ld (rc %d)", sum.tripped_at, rc);

    /* bad inputs */
    cmd[0] = NAN;
    c.ferror_limit_mm = 0;
    hg_loop_init(L, &c, 0);
    CHECK(hg_loop_step(L, cmd, &s) == HG_ERR_NONFINITE_INPUT, "NaN command refused");
    {
        hg_loop_config b = c;
        hg_loop_check_report r;
        long before;
        b.ferror_limit_mm = 0;
        b.pid[3].pgain = NAN;
        rc = hg_loop_config_check(&b, &r);
        CHECK(rc == HG_ERR_BAD_PARAM && r.joint == 3 && strcmp(r.component, "pid") == 0 &&
              strcmp(r.field, "Pgain") == 0 && r.ini_key && strcmp(r.ini_key, "P") == 0 && isnan(r.value) &&
              hg_loop_init(L, &b, 0) == HG_ERR_BAD_PARAM,
              "config check: a NaN Pgain of joint 3 is refused, named (joint %d, %s %s, INI %s), init refuses it",
              r.joint, r.component, r.field, r.ini_key ? r.ini_key : "-");
        b = c;
        b.ferror_limit_mm = 0;
        b.pid[1].ff1 = 2e9;
        rc = hg_loop_config_check(&b, &r);
        CHECK(rc == HG_ERR_BAD_PARAM && r.joint == 1 && strcmp(r.field, "FF1") == 0,
              "config check: FF1 2e9 (beyond HG_PID_MAX_ABS) refused (%d, %s)", rc, r.field);
        b = c;
        b.ferror_limit_mm = 0;
        b.pid[5].maxoutput = -1;
        rc = hg_loop_config_check(&b, &r);
        CHECK(rc == HG_ERR_BAD_PARAM && r.joint == 5 && strcmp(r.field, "maxoutput") == 0,
              "config check: a negative maxoutput refused (%s)", r.field);
        b = c;
        b.pid[2].dgain = -0.5;                   /* a negative gain is a gain (the loop above runs it) */
        b.ferror_limit_mm = -1;
        rc = hg_loop_config_check(&b, &r);
        CHECK(rc == HG_ERR_BAD_PARAM && r.joint == -1 && strcmp(r.field, "ferror_limit_mm") == 0,
              "config check: ferror_limit_mm -1 refused, named (%s), negative D taken", r.field);
        b.ferror_limit_mm = NAN;
        CHECK(hg_loop_config_check(&b, &r) == HG_ERR_BAD_PARAM && strcmp(r.field, "ferror_limit_mm") == 0,
              "config check: ferror_limit_mm NaN refused");
        b = c;
        b.ferror_limit_mm = 0;
        b.input_scale[4] = 1e-30;
        CHECK(hg_loop_config_check(&b, &r) == HG_ERR_BAD_PARAM && r.joint == 4 &&
              strcmp(r.ini_key, "INPUT_SCALE") == 0,
              "config check: INPUT_SCALE 1e-30 refused (the board's encoder would read it as 1)");
        b = c;
        b.ferror_limit_mm = 0;
        hg_biquad_notch(&b.biquad[0], 100.0, 3.0);
        CHECK(hg_loop_config_check(&b, &r) == HG_ERR_BAD_PARAM && r.joint == 0 &&
              strcmp(r.component, "biquad") == 0 && strcmp(r.field, "Q") == 0,
              "config check: a notch biquad.comp refuses (Q 3) is refused, not run unfiltered");
        hg_biquad_notch(&b.biquad[0], 100.0, 1.0);
        CHECK(hg_loop_config_check(&b, &r) == 0, "config check: a notch of Q 1 at 100 Hz taken");

        /* a command pid.c's derivatives would overflow (1e300 / (1 ms)^3 = inf, inf * FF3 0 = NaN) is
         * refused, nothing run; one at the bound runs with finite outputs and trips */
        b = c;
        b.ferror_limit_mm = 2.0;
        hg_loop_init(L, &b, 0);
        for (k = 0; k < 6; k++)
            cmd[k] = 0;
        cmd[2] = 1e300;
        before = L->periods;
        CHECK(hg_loop_step(L, cmd, &s) == HG_ERR_OUT_OF_RANGE && L->periods == before,
              "a 1e300 mm command refused (HG_ERR_OUT_OF_RANGE), nothing run");
        for (k = 0; k < 6; k++) {
            b.pid[k].pgain = b.pid[k].ff1 = b.pid[k].ff2 = b.pid[k].ff3 = HG_PID_MAX_ABS;
            b.pid[k].maxoutput = 0;
        }
        hg_loop_init(L, &b, 0);
        for (i = 0; i < 3 * 6; i++)
            traj[i] = i >= 6 ? HG_PID_MAX_ABS : 0.0;
        rc = hg_loop_run(L, traj, 3, 0, fe3, out3, &sum);
        {
            int finite = 1;
            for (i = 0; i < 6 * sum.periods; i++)
                finite &= isfinite(fe3[i]) && isfinite(out3[i]);
            CHECK((rc != 0 || sum.tripped_at == 2) && finite && sum.periods >= 1,
                  "a 1e9 mm step at period 1 with every gain at 1e9: finite f-errors and outputs (%ld periods), "
                  "then the trip at period 2 (motion's f-error is the previous command's: %ld) or a fault (%d)",
                  sum.periods, sum.tripped_at, rc);
        }
    }
    c.period_ns = 0;
    CHECK(hg_loop_init(L, &c, 0) == HG_ERR_BAD_DT, "period 0 refused");
    free(traj);
    free(L);
    return hg_test_exit();
}
