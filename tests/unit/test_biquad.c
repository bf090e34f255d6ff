/* test_biquad.c - hg_biquad, LinuxCNC's biquad.comp, against closed forms:
 * the notch's steady-state response to sines (run through the filter's own
 * difference equation) and hg_biquad_response both equal the analog notch
 * (s^2 + w0^2) / (s^2 + s w0 / Q + w0^2) under the bilinear transform
 * prewarped at f0 (s = j tan(pi f T), w0 = tan(pi f0 T): the frequency
 * warping biquad.comp's cookbook formulas imply) at frequencies on both
 * sides of f0, within 1e-10 (biquad.comp's PI, 3.141592653589, is 2.5e-13
 * short of pi: that moves the zero by 1e-10 Hz); the low pass's DC gain is 1
 * and its gain at f0 1/sqrt(2) for Q = 1/sqrt(2); the component's rules: Q 0.5..2 and f0 <= rate/2 accepted
 * (valid 1), anything else refused (valid 0, out = in); coefficients only
 * on an enable edge; out = in bit for bit while disabled. */
#include <complex.h>
#include <math.h>
#include "hg_biquad.h"
#include "hg_test.h"

#define PI 3.14159265358979323846
#define PERIOD 1000000L            /* a 1 ms servo thread: rate 1000 Hz */

/* The prewarped analog notch (or low pass) at f (Hz): the closed form. */
static double complex analog(int type, double f0, double q, double f)
{
    double T = PERIOD * 1e-9, w0 = tan(PI * f0 * T);
    double complex s = I * tan(PI * f * T);
    double complex den = s * s + s * w0 / q + w0 * w0;
    return (type == HG_BIQUAD_NOTCH ? s * s + w0 * w0 : w0 * w0) / den;
}

/* The filter's steady-state response to a unit sine at f: run 4000
 * periods, correlate the last 2000 output samples with the input. */
static double complex measured(hg_biquad *b, double f)
{
    double complex num = 0, den = 0;
    int i;
    for (i = 0; i < 4000; i++) {
        double t = i * PERIOD * 1e-9;
        b->in = sin(2 * PI * f * t);
        hg_biquad_run(b, PERIOD);
        if (i >= 2000) {
            double complex ref = cexp(-I * 2 * PI * f * t);
            num += b->out * ref;
            den += b->in * ref;
        }
    }
    return num / den;
}

int main(void)
{
    static const double freqs[] = {5, 40, 150, 300, 340, 352.75, 365, 420, 480};
    static const double qs[] = {0.5, 0.7, 2.0};
    hg_biquad b;
    double worst = 0, worst_r = 0, re, im;
    unsigned i, j;

    for (j = 0; j < sizeof qs / sizeof qs[0]; j++)
        for (i = 0; i < sizeof freqs / sizeof freqs[0]; i++) {
            double complex want = analog(HG_BIQUAD_NOTCH, 352.75, qs[j], freqs[i]), got;
            hg_biquad_notch(&b, 352.75, qs[j]);
            got = measured(&b, freqs[i]);
            if (cabs(got - want) > worst)
                worst = cabs(got - want);
            hg_biquad_response(&b, PERIOD, freqs[i], &re, &im);
            if (cabs(re + I * im - want) > worst_r)
                worst_r = cabs(re + I * im - want);
        }
    CHECK(worst < 1e-10, "notch f0 352.75 Hz, Q 0.5, 0.7, 2: the filtered sines' response = the prewarped "
          "bilinear notch at 9 frequencies 5..480 Hz (worst |difference| %.2e)", worst);
    CHECK(worst_r < 1e-10, "hg_biquad_response = the closed form (worst %.2e)", worst_r);
    hg_biquad_notch(&b, 352.75, 0.7);
    hg_biquad_response(&b, PERIOD, 352.75, &re, &im);
    CHECK(hypot(re, im) < 1e-9, "the notch's zero at f0: |H(352.75 Hz)| = %.1e", hypot(re, im));
    hg_biquad_response(&b, PERIOD, 40, &re, &im);
    CHECK(fabs(hypot(re, im) - cabs(analog(HG_BIQUAD_NOTCH, 352.75, 0.7, 40))) < 1e-12 && hypot(re, im) < 1 &&
          hypot(re, im) > 0.97, "... and |H(40 Hz)| = %.4f (the notch's skirt at the crossover)", hypot(re, im));

    /* low pass: DC gain 1, |H(f0)| = 1/sqrt(2) for Q = 0.7071... */
    hg_biquad_defaults(&b);
    b.type = HG_BIQUAD_LOW_PASS;
    b.f0 = 100;
    b.Q = 1 / sqrt(2.0);
    b.enable = 1;
    hg_biquad_response(&b, PERIOD, 1e-9, &re, &im);
    CHECK(fabs(re - 1) < 1e-12 && fabs(im) < 1e-9, "low pass: DC gain 1 (%.15f)", re);
    hg_biquad_response(&b, PERIOD, 100, &re, &im);
    CHECK(fabs(hypot(re, im) - sqrt(0.5)) < 1e-9, "low pass at f0, Q 1/sqrt(2): |H| = %.9f = 1/sqrt(2)", hypot(re, im));

    /* the component's rules: Q within 0.5..2 (both ends in), f0 <= rate / 2 */
    {
        static const double q_ok[] = {0.5, 2.0}, q_bad[] = {0.4999, 2.0001, 0.0, -1.0};
        int ok = 1;
        for (i = 0; i < 2; i++) {
            hg_biquad_notch(&b, 300, q_ok[i]);
            b.in = 1;
            hg_biquad_run(&b, PERIOD);
            ok &= b.valid == 1;
        }
        hg_biquad_notch(&b, 500, 1);
        hg_biquad_run(&b, PERIOD);
        ok &= b.valid == 1;
        CHECK(ok, "Q 0.5 and 2 and f0 = rate/2 = 500 Hz accepted (valid 1)");
        ok = 1;
        for (i = 0; i < 4; i++) {
            hg_biquad_notch(&b, 300, q_bad[i]);
            b.in = 0.123456789;
            hg_biquad_run(&b, PERIOD);
            ok &= b.valid == 0 && b.out == b.in && hg_biquad_response(&b, PERIOD, 300, &re, &im) == 0 && re == 1;
        }
        hg_biquad_notch(&b, 500.001, 1);
        b.in = -3.5;
        hg_biquad_run(&b, PERIOD);
        ok &= b.valid == 0 && b.out == -3.5;
        CHECK(ok, "Q 0.4999, 2.0001, 0, -1 and f0 500.001 Hz refused: valid 0, out = in");
    }

    /* coefficients only on an enable edge; disabled: out = in, bit for bit */
    {
        double n1;
        hg_biquad_notch(&b, 300, 1);
        b.in = 1;
        hg_biquad_run(&b, PERIOD);
        n1 = b.n1;
        b.f0 = 100;
        hg_biquad_run(&b, PERIOD);
        CHECK(b.n1 == n1 && fabs(n1 + 2 * cos(2 * 3.141592653589 * 300 / 1000) / (1 + sin(2 * 3.141592653589 * 300 / 1000) / 2)) < 1e-15,
              "f0 changed while enabled: the coefficients stay (n1 = -2 cos w0 / (1 + alpha) of 300 Hz)");
        b.enable = 0;
        b.in = 0.1 + 1e-17;
        hg_biquad_run(&b, PERIOD);
        CHECK(b.out == b.in, "disabled: out = in bit for bit");
        b.enable = 1;
        hg_biquad_run(&b, PERIOD);
        CHECK(b.n1 != n1 && b.s1 != 0, "re-enabled: the coefficients of the new f0 (100 Hz), states restarted");
    }
    return hg_test_exit();
}
