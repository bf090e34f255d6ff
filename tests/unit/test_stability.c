/* test_stability.c - hg_stability's bound against the machine itself: the
 * linear test systems predict the longest stable step for a stiff
 * parameter; the full nonlinear step (hg_step on all six carriages, head
 * and bars made light so that each carriage's inertia is the test
 * system's, m_carriage + j_rotor (2 pi / lead)^2) must settle a little
 * below that step and not settle a little above it. Also: the defaults
 * need one step per 1 ms period with every scheme, an undamped hard stop
 * is refused for improved Euler and Heun, and the board runs the substeps
 * the check asks for and says so. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_board.h"
#include "hg_dynamics.h"
#include "hg_plant_hexaglide.h"
#include "hg_errors.h"

/* The spec's machine with head and bars of almost no mass. */
static void light(hg_params *p)
{
    hg_test_rigid_defaults(p);
    p->m_head_kg = 1e-3;
    p->i_head_xx_kgm2 = p->i_head_yy_kgm2 = p->i_head_zz_kgm2 = 1e-6;
    p->m_bar_kg = 1e-3;
    p->i_bar_kgm2 = 0.3 * p->m_bar_kg * p->geo.l_m * p->geo.l_m;
    p->f_coulomb_n = p->f_static_n = 0.0;
}

/* How the carriage speed's swing (largest minus smallest) changes from the
 * 50 ms after t_s / 2 to the last 50 ms of t_s, six equal volts from
 * HOME, stepping dt: well below 1 it settles, near or above 1 it does not
 * (a limit cycle where the drive or the stop clips it; INFINITY when the
 * step fails; 0 once the swing is below 1 nm/s). */
static double swing_ratio(const hg_params *p, hg_integrator scheme, double volts, double dt, double t_s)
{
    static hg_model m;
    static hg_data d;
    double v[6], lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, early, late;
    long s, n = lround(t_s / dt), mid = n / 2, w = lround(0.05 / dt);
    int k;
    if (hg_model_init(&m, p, HG_MODEL_REDUCED_JOINTS, 0, 0) || hg_model_set_integrator(&m, scheme) ||
        hg_data_reset(&m, &d))
        return INFINITY;
    for (k = 0; k < 6; k++)
        v[k] = volts;
    for (s = 0; s < n; s++) {
        if (hg_step(&m, &d, v, dt))
            return INFINITY;
        k = s >= mid && s < mid + w ? 0 : s >= n - w ? 1 : -1;
        if (k >= 0) {
            lo[k] = fmin(lo[k], d.zd_mps[0]);
            hi[k] = fmax(hi[k], d.zd_mps[0]);
        }
    }
    early = hi[0] - lo[0];
    late = hi[1] - lo[1];
    return late < 1e-9 ? 0.0 : late / early;
}

/* The bound for p at 1 ms, and the machine a little below and above it. */
static void check_bound(const char *what, const hg_params *p, hg_integrator scheme, double volts, double t_s)
{
    hg_stability st;
    int rc = hg_stability_check(p, scheme, 1e-3, 1, 1, &st);
    double below, above;
    if (!(rc == HG_ERR_STIFF && st.dt_max_s > 0.0)) {
        CHECK(0, "%s with %s: expected a bound below 1 ms (rc %d)", what, hg_integrator_name(scheme), rc);
        return;
    }
    below = swing_ratio(p, scheme, volts, 0.9 * st.dt_max_s, t_s);
    above = swing_ratio(p, scheme, volts, 1.1 * st.dt_max_s, t_s);
    CHECK(below < 0.5 && !(above < 0.8),
          "%s with %s: bound %.4f ms (%s); at 0.9 of it the machine's speed swing dies out (late/early %.2g), "
          "at 1.1 it does not (%.2g)", what, hg_integrator_name(scheme), st.dt_max_s * 1e3, st.param,
          below, above);
}

static void test_bounds(void)
{
    hg_params p;
    int s;
    for (s = 0; s < HG_INTEGRATOR_COUNT; s++) {
        hg_stability st;
        hg_test_rigid_defaults(&p);
        CHECK(hg_stability_check(&p, (hg_integrator)s, 1e-3, 1, HG_SUBSTEPS_MAX, &st) == 0 && st.substeps == 1,
              "defaults at 1 ms with %s: one step per period (%u)", hg_integrator_name((hg_integrator)s),
              st.substeps);
    }
    /* a stiff hard stop: pushed into a near one at full volts */
    light(&p);
    p.stop_max_m = 0.004;
    p.limit_max_m = 0.003;
    p.home_switch_m = 0.001;
    for (s = 0; s < HG_INTEGRATOR_COUNT; s++) {
        p.k_stop_n_per_m = s == HG_INTEGRATOR_RK4 ? 9e8 : 2e8;
        check_bound(s == HG_INTEGRATOR_RK4 ? "k_stop 9e8 N/m, in the stop" : "k_stop 2e8 N/m, in the stop",
                    &p, (hg_integrator)s, 10.0, 0.6);
    }
    /* a drive whose back-EMF damping is strong (small winding resistance and
     * inductance), at its bus-limited top speed */
    light(&p);
    p.r_winding_ohm = 0.1;
    p.l_winding_h = 1e-6;
    for (s = 0; s < HG_INTEGRATOR_COUNT; s++)
        check_bound("r_winding 0.1 ohm, l_winding 1 uH, top speed", &p, (hg_integrator)s, 10.0, 0.6);
}

static void test_refused_and_board(void)
{
    static hg_board b;
    hg_board_params bp;
    hg_board_inputs in;
    hg_board_outputs out;
    hg_stability st;
    int rc, i;
    hg_params p;
    hg_test_rigid_defaults(&p);
    p.c_visc_ns_per_m = p.c_stop_ns_per_m = 0.0;
    rc = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, HG_SUBSTEPS_MAX, &st);
    CHECK(rc == HG_ERR_STIFF && st.param && strcmp(st.param, "c_stop") == 0,
          "an undamped hard stop with heun: refused at any step, naming %s", st.param ? st.param : "nothing");
    rc = hg_stability_check(&p, HG_INTEGRATOR_RK4, 1e-3, 1, HG_SUBSTEPS_MAX, &st);
    CHECK(rc == 0 && st.substeps == 1, "... rk4 integrates it (|R| < 1 on the imaginary axis up to 2.8)");
    /* the board: k_stop 5e8 needs more substeps with improved Euler at 1 ms */
    hg_test_rigid_defaults(&p);
    p.k_stop_n_per_m = 5e8;
    hg_test_block(&bp, &p, 1, HG_INTEGRATOR_IMPROVED_EULER);
    rc = hg_stability_check(&p, HG_INTEGRATOR_IMPROVED_EULER, 1e-3, 1, HG_SUBSTEPS_MAX, &st);
    hg_board_init(&b, 0, HG_MODEL_REDUCED_CARTESIAN, &bp);
    hg_board_inputs_default(&b, &in);
    in.dout_values = 1u << 7;
    hg_board_step(&b, &in, &out, 1000000L);
    CHECK(rc == 0 && st.substeps > 1 && out.substeps_run == st.substeps && (out.events & HG_EV_SUBSTEPS_AUTO) &&
              out.stiff_param >= 0 && strcmp(hg_params_table(0)[out.stiff_param].name, "k_stop") == 0 &&
              out.params.substeps == 1,
          "board, k_stop 5e8 with improved Euler at 1 ms: runs %u substeps (%u asked), says so once, names k_stop",
          out.substeps_run, out.params.substeps);
    hg_board_step(&b, &in, &out, 1000000L);
    CHECK(!(out.events & HG_EV_SUBSTEPS_AUTO) && out.substeps_run == st.substeps, "... and keeps them without a new event");
    /* a period the parameters cannot be integrated at even with 64 substeps: fault STIFF */
    for (i = 0; i < 2; i++)
        hg_board_step(&b, &in, &out, 10000000L);
    CHECK(out.fault && out.fault_code == HG_ERR_STIFF, "10 ms period with k_stop 5e8: fault %d (%s)", out.fault_code,
          hg_strerror(out.fault_code));
    /* hg_board_integrable, the check before a run: 0 for the k_stop 5e8 block at 1 ms (substeps
     * enough), HG_ERR_STIFF naming k_stop at 10 ms as the check of the linear bound says */
    rc = hg_stability_check(&p, HG_INTEGRATOR_IMPROVED_EULER, 1e-2, 1, HG_SUBSTEPS_MAX, &st);
    i = hg_board_integrable(&b, &in, 0, HG_MODEL_REDUCED_CARTESIAN, &bp, 1000000L, &out);
    CHECK(i == 0 && !out.fault, "hg_board_integrable: k_stop 5e8, improved Euler at 1 ms: 0 (%d)", i);
    i = hg_board_integrable(&b, &in, 0, HG_MODEL_REDUCED_CARTESIAN, &bp, 10000000L, &out);
    CHECK(rc == HG_ERR_STIFF && i == HG_ERR_STIFF && out.stiff_param >= 0 &&
              strcmp(hg_params_table(0)[out.stiff_param].name, "k_stop") == 0 && out.stiff_dt_max_s == st.dt_max_s,
          "... at 10 ms: %d as hg_stability_check's %d, naming k_stop, its longest step %g s (%g)", i, rc,
          out.stiff_dt_max_s, st.dt_max_s);
    {   /* what to change: a shorter step helps (the bound is a step), in the caller's words */
        char remedy[HG_BOARD_TEXT_LEN];
        hg_board_stiff_remedy(&out, "--integrator", "--dt", remedy);
        CHECK(strcmp(remedy, "a softer value, another --integrator or a shorter --dt") == 0, "remedy: \"%s\"", remedy);
        hg_board_stiff_remedy(&out, "integrator", 0, remedy);       /* a period the caller cannot change */
        CHECK(strcmp(remedy, "a softer value or another integrator") == 0, "remedy, no period: \"%s\"", remedy);
        out.stiff_dt_max_s = 0.0;                                     /* no step is short enough */
        hg_board_stiff_remedy(&out, "integrator", "period", remedy);
        CHECK(strcmp(remedy, "the mode damping or another integrator (no step is short enough)") == 0,
              "remedy of an undamped mode names no period: \"%s\"", remedy);
    }
    *hg_test_pv(&bp, "m_head") = -1.0;
    i = hg_board_integrable(&b, &in, 0, HG_MODEL_REDUCED_CARTESIAN, &bp, 1000000L, &out);
    CHECK(i == HG_ERR_BAD_PARAM && !out.fault, "... a block the checks refuse (m_head -1): %d, not built", i);
    /* a change the running period cannot integrate is refused, naming it */
    hg_board_init(&b, 0, HG_MODEL_REDUCED_CARTESIAN, 0);
    hg_board_inputs_default(&b, &in);
    hg_board_step(&b, &in, &out, 1000000L);
    *hg_test_pv(&in.params, "c_visc") = *hg_test_pv(&in.params, "c_stop") = 0.0;
    hg_board_step(&b, &in, &out, 1000000L);
    CHECK((out.events & HG_EV_PARAM_REFUSED) && out.param_rc == HG_ERR_STIFF && out.stiff_param >= 0 &&
              strcmp(hg_params_table(0)[out.stiff_param].name, "c_stop") == 0 &&
              *hg_test_pv(&out.params, "c_stop") > 0.0,
          "c_visc = c_stop = 0 at 1 ms with heun: refused (code %d), naming c_stop, the set in force kept", out.param_rc);
}

/* Short periods are stable (the check must not cancel to rounding as the
 * eigenvalues approach 1); the parameter named is the one that sets the
 * substep count: its longest step lies between period/k and period/(k-1). */
static void test_short_periods_and_naming(void)
{
    static const double periods[] = {1e-3, 1e-4, 1e-5, 1e-6, 3e-7, 1e-8};
    hg_params p;
    hg_stability st;
    int s, i, bad = 0;
    hg_test_rigid_defaults(&p);
    for (s = 0; s < HG_INTEGRATOR_COUNT; s++)
        for (i = 0; i < (int)(sizeof periods / sizeof periods[0]); i++)
            if (hg_stability_check(&p, (hg_integrator)s, periods[i], 1, 1, &st) || st.substeps != 1) {
                printf("# %s at %g s: substeps %u, %s\n", hg_integrator_name((hg_integrator)s), periods[i],
                       st.substeps, st.param ? st.param : "-");
                bad++;
            }
    CHECK(bad == 0, "the defaults are stable with every scheme at 1 ms down to 10 ns periods (%d refused)", bad);
    for (s = 0; s < HG_INTEGRATOR_COUNT; s++) {
        int rc = hg_stability_check(&p, (hg_integrator)s, 10e-3, 1, 64, &st);
        unsigned k = st.substeps;
        CHECK(rc == 0 && k > 1 && st.param && st.dt_max_s >= 10e-3 / k && st.dt_max_s < 10e-3 / (k - 1),
              "%s at 10 ms: %u substeps, named %s whose longest step %.4f ms lies in [period/%u, period/%u)",
              hg_integrator_name((hg_integrator)s), k, st.param ? st.param : "-", st.dt_max_s * 1e3, k, k - 1);
    }
}

/* A state the step leaves as it is (eigenvalue exactly 1) is neutral, not
 * unstable: a velocity loop without integral gain, a damping too weak to
 * change a speed's last bit. Just above zero the answer is the same as at
 * zero. A spring's damping that cannot be integrated alone names the
 * bound, and a refused set is described by its own values. */
static void test_neutral_and_damping_names(void)
{
    static hg_board b;
    hg_board_inputs in;
    hg_board_outputs out;
    hg_stability st, st0;
    hg_params p;
    char why[HG_BOARD_TEXT_LEN];
    int rc, rc0;
    hg_test_rigid_defaults(&p);
    p.amp_mode = 1.0;
    p.ki_vel_a_per_m = 0.0;
    rc0 = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, HG_SUBSTEPS_MAX, &st0);
    p.ki_vel_a_per_m = 1e-300;
    rc = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, HG_SUBSTEPS_MAX, &st);
    CHECK(rc0 == 0 && rc == 0 && st0.substeps == st.substeps,
          "velocity mode, ki_vel 0 (a P-only loop) integrates as ki_vel 1e-300: rc %d / %d, %u / %u substeps",
          rc0, rc, st0.substeps, st.substeps);
    hg_test_rigid_defaults(&p);
    p.c_visc_ns_per_m = 0.0;
    rc0 = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, HG_SUBSTEPS_MAX, &st0);
    p.c_visc_ns_per_m = 1e-300;
    rc = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, HG_SUBSTEPS_MAX, &st);
    CHECK(rc0 == 0 && rc == 0 && st0.substeps == st.substeps, "c_visc 1e-300 integrates as c_visc 0: rc %d / %d",
          rc0, rc);
    /* c_stop 1e6 on the rigid carriage: c dt / m = 1e6 * 1e-3 / (m_carriage + rotor), far above
     * the 2 any explicit scheme allows for a damping alone; the spring k_stop is the default */
    hg_test_rigid_defaults(&p);
    p.c_stop_ns_per_m = 1e6;
    rc = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, 1, &st);
    CHECK(rc == HG_ERR_STIFF && st.param && strcmp(st.param, "c_stop") == 0,
          "c_stop 1e6 at 1 ms, one step: refused, naming %s (c_stop)", st.param ? st.param : "nothing");
    /* the velocity loop: force fpa (-kp_vel v - ki_vel x), a damping and a spring; ki_vel 1e7 A/m with
     * kp_vel 1 A s/m: kp_vel alone integrates (fpa kp dt / m far below 2), so ki_vel names the bound
     * (softer kp_vel makes the loop worse: it is the loop's only damping) */
    hg_test_rigid_defaults(&p);
    p.amp_mode = 1.0;
    p.kp_vel_as_per_m = 1.0;
    p.ki_vel_a_per_m = 1e7;
    rc = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, 1, &st);
    CHECK(rc == HG_ERR_STIFF && st.param && strcmp(st.param, "ki_vel") == 0,
          "velocity loop, ki_vel 1e7 with kp_vel 1 at 1 ms, one step: refused, naming %s (ki_vel)",
          st.param ? st.param : "nothing");
    p.kp_vel_as_per_m = 1e5;
    p.ki_vel_a_per_m = 0.0;
    rc = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, 1, &st);
    CHECK(rc == HG_ERR_STIFF && st.param && strcmp(st.param, "kp_vel") == 0,
          "... kp_vel 1e5 without ki_vel: refused, naming %s (kp_vel)", st.param ? st.param : "nothing");
    hg_params_default(&p);
    p.c_axial_ns_per_m = 1e8;
    rc = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, 1, &st);
    CHECK(rc == HG_ERR_STIFF && st.param && strcmp(st.param, "c_axial") == 0,
          "flexible train, c_axial 1e8 at 1 ms, one step: refused, naming %s (c_axial)", st.param ? st.param : "nothing");
    /* Heun on an undamped oscillator grows at any step (|1 + z + z^2/2|^2 = 1 + (w h)^4 / 4 for z = i w h):
     * a train with no damping to speak of is refused at any substep count, naming the damping it
     * lacks (it named k_axial) */
    p.c_axial_ns_per_m = 1e-300;
    rc = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, 64, &st);
    CHECK(rc == HG_ERR_STIFF && st.param && strcmp(st.param, "c_axial") == 0 && st.dt_max_s == 0.0,
          "flexible train, c_axial 1e-300 (undamped): refused at 64 steps, naming %s (c_axial), no stable step (%g s)",
          st.param ? st.param : "nothing", st.dt_max_s);
    /* the refused set's value and integrator, not the set in force's */
    hg_board_init(&b, 0, HG_MODEL_REDUCED_CARTESIAN, 0);
    hg_board_inputs_default(&b, &in);
    hg_board_step(&b, &in, &out, 1000000L);
    *hg_test_pv(&in.params, "c_visc") = *hg_test_pv(&in.params, "c_stop") = 0.0;
    in.params.integrator = HG_INTEGRATOR_IMPROVED_EULER;
    hg_board_step(&b, &in, &out, 1000000L);
    hg_board_describe_stiffness(&b, &out, 1000000L, 0, why);
    CHECK((out.events & HG_EV_PARAM_REFUSED) && out.param_rc == HG_ERR_STIFF && out.stiff_value == 0.0 &&
              out.stiff_integrator == HG_INTEGRATOR_IMPROVED_EULER && strstr(why, "c_stop = 0 ") &&
              strstr(why, "improved-euler") && out.params.integrator == HG_INTEGRATOR_DEFAULT,
          "refused set described by its own values: \"%s\"", why);
}

int main(void)
{
    test_short_periods_and_naming();
    test_bounds();
    test_refused_and_board();
    test_neutral_and_damping_names();
    return hg_test_exit();
}
