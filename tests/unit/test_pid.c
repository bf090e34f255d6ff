/* test_pid.c - hg_pid against the closed-form behaviour of LinuxCNC's pid
 * component (pid.c's documented formulas): each term alone on a command
 * whose derivatives are known exactly. The sample-by-sample match with
 * LinuxCNC itself is tests/linuxcnc/test_pid_match. */
#include <math.h>
#include <string.h>
#include "hg_errors.h"
#include "hg_pid.h"
#include "hg_test.h"

#define T_NS 1000000L
#define T_S 0.001

static int close_to(double a, double b, double tol) { return fabs(a - b) <= tol; }

int main(void)
{
    hg_pid_gains g;
    hg_pid_state s;
    double out = 0, worst;
    int k;

    hg_pid_defaults(&g);
    CHECK(g.pgain == 1.0 && g.igain == 0 && g.error_previous_target == 1, "defaults as pid.c: Pgain 1, error-previous-target 1");

    /* P only: error is the previous command minus the feedback */
    hg_pid_defaults(&g);
    g.pgain = 5;
    hg_pid_reset(&s);
    hg_pid_calc(&g, &s, 1.0, 0.0, 1, 0, T_NS);
    out = hg_pid_calc(&g, &s, 2.0, 0.25, 1, 0, T_NS);
    CHECK(close_to(out, 5 * (1.0 - 0.25), 1e-12), "P term on previous command - feedback: %.12g V", out);
    g.error_previous_target = 0;
    out = hg_pid_calc(&g, &s, 3.0, 0.25, 1, 0, T_NS);
    CHECK(close_to(out, 5 * (3.0 - 0.25), 1e-12), "error-previous-target 0: command - feedback: %.12g V", out);

    /* I only: constant error e for n periods integrates to e n T */
    hg_pid_defaults(&g);
    g.pgain = 0;
    g.igain = 100;
    hg_pid_reset(&s);
    for (k = 0; k < 500; k++)
        out = hg_pid_calc(&g, &s, 0.0, -0.01, 1, 0, T_NS);
    CHECK(close_to(out, 100 * 0.01 * 500 * T_S, 1e-9), "I term: 100 * 0.01 mm * 0.5 s = %.9g V", out);
    /* disabling resets the integrator and zeroes the output */
    out = hg_pid_calc(&g, &s, 0.0, -0.01, 0, 0, T_NS);
    CHECK(out == 0.0 && s.error_i == 0.0, "disabled: output 0, integrator reset");
    /* maxerrorI */
    g.maxerror_i = 0.001;
    for (k = 0; k < 500; k++)
        out = hg_pid_calc(&g, &s, 0.0, -0.01, 1, 0, T_NS);
    CHECK(close_to(out, 100 * 0.001, 1e-12), "maxerrorI clamps the integral: %.9g V", out);

    /* FF1 and FF2 on a parabola c = a t^2 / 2: rate a t, 2nd derivative a */
    hg_pid_defaults(&g);
    g.pgain = 0;
    g.ff1 = 0.02;
    hg_pid_reset(&s);
    worst = 0;
    for (k = 0; k <= 100; k++) {
        double t = k * T_S, a = 300.0;
        out = hg_pid_calc(&g, &s, a * t * t / 2, 0.0, 1, 0, T_NS);
        if (k > 2)  /* backward difference: rate at mid-period */
            worst = fmax(worst, fabs(out - 0.02 * a * (t - T_S / 2)));
    }
    CHECK(worst < 1e-9, "FF1 * backward-difference command rate (max dev %.3g V)", worst);
    g.ff1 = 0;
    g.ff2 = 0.0002;
    hg_pid_reset(&s);
    worst = 0;
    for (k = 0; k <= 100; k++) {
        double t = k * T_S, a = 300.0;
        out = hg_pid_calc(&g, &s, a * t * t / 2, 0.0, 1, 0, T_NS);
        if (k > 3)
            worst = fmax(worst, fabs(out - 0.0002 * a));
    }
    CHECK(worst < 1e-7, "FF2 * command 2nd derivative = %.6g V (max dev %.3g V)", out, worst);
    g.ff2 = 0;
    g.ff0 = 0.5;
    out = hg_pid_calc(&g, &s, 2.0, 0.0, 1, 0, T_NS);
    CHECK(close_to(out, 1.0, 1e-12), "FF0 * command");

    /* D: rate of the command minus rate of the feedback */
    hg_pid_defaults(&g);
    g.pgain = 0;
    g.dgain = 0.04;
    hg_pid_reset(&s);
    hg_pid_calc(&g, &s, 0.0, 0.0, 1, 0, T_NS);
    out = hg_pid_calc(&g, &s, 0.003, 0.001, 1, 0, T_NS);
    CHECK(close_to(out, 0.04 * (3.0 - 1.0), 1e-9), "D term: 0.04 * (3 - 1) mm/s = %.9g V", out);

    /* deadband and maxerror */
    hg_pid_defaults(&g);
    g.pgain = 10;
    g.deadband = 0.002;
    hg_pid_reset(&s);
    hg_pid_calc(&g, &s, 0.0, 0.0, 1, 0, T_NS);
    out = hg_pid_calc(&g, &s, 0.0, -0.001, 1, 0, T_NS);
    CHECK(out == 0.0, "error inside the deadband: 0 V");
    out = hg_pid_calc(&g, &s, 0.0, -0.005, 1, 0, T_NS);
    CHECK(close_to(out, 10 * 0.003, 1e-12), "error beyond the deadband loses the deadband: %.9g V", out);
    g.deadband = 0;
    g.maxerror = 0.1;
    out = hg_pid_calc(&g, &s, 0.0, -1.0, 1, 0, T_NS);
    CHECK(close_to(out, 1.0, 1e-12), "maxerror clamps the error: %.9g V", out);

    /* maxoutput: clamp, saturated pins, no integrator wind-up in the clamped direction */
    hg_pid_defaults(&g);
    g.pgain = 100;
    g.igain = 1000;
    g.maxoutput = 10;
    hg_pid_reset(&s);
    for (k = 0; k < 100; k++)
        out = hg_pid_calc(&g, &s, 0.0, -1.0, 1, 0, T_NS);
    CHECK(out == 10.0 && s.saturated && s.saturated_count == 100, "maxoutput clamps, saturated for 100 periods");
    CHECK(close_to(s.error_i, 1.0 * T_S, 1e-15), "integrator held while clamped (errorI %.3g mm s)", s.error_i);

    /* index-enable falling: error and rates against this period's command */
    hg_pid_defaults(&g);
    g.pgain = 1;
    g.ff1 = 1;
    hg_pid_reset(&s);
    hg_pid_calc(&g, &s, 5.0, 5.0, 1, 1, T_NS);
    out = hg_pid_calc(&g, &s, 5.0, 0.0, 1, 0, T_NS);  /* counts reset at the index */
    /* ... and the rates keep their last values (5 mm in the first period) */
    CHECK(close_to(out, 5.0 + 5.0 / T_S, 1e-6), "index reset: P (command - feedback) + FF1 * last rate (%.9g V)", out);
    CHECK(close_to(s.error, 5.0, 1e-12), "index reset: error pin 5 mm");

    /* why the offline loop bounds its commands: pid.c on a 1e300 mm step gives NaN (commandDDD
     * 1e300 / (1 ms)^3 overflows to inf, times FF3 = 0); the checks name what they refuse */
    hg_pid_defaults(&g);
    hg_pid_reset(&s);
    out = hg_pid_calc(&g, &s, 1e300, 0.0, 1, 0, T_NS);
    CHECK(isnan(out) && isinf(s.cmd_ddd), "pid.c on a 1e300 mm command step: commandDDD inf, output NaN (%g)", out);
    CHECK(hg_pid_input_check(1e300) == HG_ERR_OUT_OF_RANGE && hg_pid_input_check(NAN) == HG_ERR_NONFINITE_INPUT &&
          hg_pid_input_check(-HG_PID_MAX_ABS) == 0, "hg_pid_input_check: 1e300 out of range, NaN non-finite, -1e9 taken");
    {
        const double v[4] = {0.0, 1.0, -INFINITY, 2e9};
        const hg_pid_setting *bad = 0;
        const char *why = 0;
        int rc = 0;
        long at = hg_pid_inputs_check(v, 4, &rc);
        CHECK(at == 2 && rc == HG_ERR_NONFINITE_INPUT && hg_pid_inputs_check(v, 2, &rc) == -1 && rc == 0,
              "hg_pid_inputs_check: the first refused is index 2 (-inf), none in the first two");
        hg_pid_defaults(&g);
        CHECK(hg_pid_gains_check(&g, &bad, &why) == 0, "the load-time gains pass the check");
        g.deadband = -0.1;
        CHECK(hg_pid_gains_check(&g, &bad, &why) == HG_ERR_BAD_PARAM && strcmp(bad->pin, "deadband") == 0 &&
              strcmp(bad->ini_key, "DEADBAND") == 0 && hg_pid_setting_value(&g, bad) == -0.1,
              "a negative deadband refused, named (pid.N.%s, INI %s): %s", bad->pin, bad->ini_key, why);
        hg_pid_defaults(&g);
        g.igain = -3.0;
        g.ff3 = NAN;
        CHECK(hg_pid_gains_check(&g, &bad, &why) == HG_ERR_BAD_PARAM && strcmp(bad->pin, "FF3") == 0,
              "a negative Igain is a gain; a NaN FF3 is refused (%s)", bad->pin);
    }
    return hg_test_exit();
}
