/* hg_biquad.c - LinuxCNC's biquad component (biquad.comp of f1270d6ed7) as a pure function. */
#include "hg_biquad.h"
#include "hg_math.h"
#include "hg_units.h"

#define BIQUAD_PI 3.141592653589   /* biquad.comp's PI (not M_PI) */

void hg_biquad_defaults(hg_biquad *b)
{
    *b = (hg_biquad){0};
    b->f0 = 250.0;
    b->Q = 0.7071;
    b->n0 = 1.0;
}

void hg_biquad_notch(hg_biquad *b, double f0_hz, double q)
{
    hg_biquad_defaults(b);
    b->type = HG_BIQUAD_NOTCH;
    b->f0 = f0_hz;
    b->Q = q;
    b->enable = 1;
}

/* The enable edge's coefficients (biquad.comp's do { ... } while (0) block). */
static void calc_coeffs(hg_biquad *b, long period)
{
    double sampleRate, w0, alpha;
    double b0, b1, b2, a0, a1, a2;
    if (b->type != HG_BIQUAD_DIRECT) {
        b->valid = 0;
        sampleRate = 1.0 / (period * 1e-9);
        if ((b->f0 > sampleRate / 2.0) || (b->Q > 2.0) || (b->Q < 0.5))
            return;
        w0 = 2.0 * BIQUAD_PI * b->f0 / sampleRate;
        alpha = sin(w0) / (2.0 * b->Q);
        if (b->type == HG_BIQUAD_LOW_PASS) {
            b0 = (1.0 - cos(w0)) / 2.0;
            b1 = 1.0 - cos(w0);
            b2 = (1.0 - cos(w0)) / 2.0;
            a0 = 1.0 + alpha;
            a1 = -2.0 * cos(w0);
            a2 = 1.0 - alpha;
        } else if (b->type == HG_BIQUAD_NOTCH) {
            b0 = 1.0;
            b1 = -2.0 * cos(w0);
            b2 = 1.0;
            a0 = 1.0 + alpha;
            a1 = -2.0 * cos(w0);
            a2 = 1.0 - alpha;
        } else {
            return;
        }
        b->n0 = b0 / a0;
        b->n1 = b1 / a0;
        b->n2 = b2 / a0;
        b->d1 = a1 / a0;
        b->d2 = a2 / a0;
        b->s1 = b->s2 = 0.0;
    }
    b->valid = 1;
}

void hg_biquad_run(hg_biquad *b, long period_ns)
{
    if (b->last_enable != b->enable) {
        b->last_enable = b->enable;
        if (b->enable)
            calc_coeffs(b, period_ns);
    }
    if (!b->enable || !b->valid) {
        b->out = b->in;
    } else {                           /* transposed direct form II */
        b->out = b->in * b->n0 + b->s1;
        b->s1 = b->in * b->n1 - b->out * b->d1 + b->s2;
        b->s2 = b->in * b->n2 - b->out * b->d2;
    }
}

int hg_biquad_response(const hg_biquad *b, long period_ns, double f_hz, double *re, double *im)
{
    hg_biquad c = *b;
    double w = 2.0 * HG_PI * f_hz * (period_ns * 1e-9);
    double c1 = cos(w), s1 = -sin(w), c2 = cos(2 * w), s2 = -sin(2 * w);   /* z^-1, z^-2 */
    double nr, ni, dr, di, dd;
    c.last_enable = 0;
    c.enable = 1;
    calc_coeffs(&c, period_ns);
    if (!c.valid) {
        *re = 1.0;
        *im = 0.0;
        return 0;
    }
    nr = c.n0 + c.n1 * c1 + c.n2 * c2;
    ni = c.n1 * s1 + c.n2 * s2;
    dr = 1.0 + c.d1 * c1 + c.d2 * c2;
    di = c.d1 * s1 + c.d2 * s2;
    dd = dr * dr + di * di;
    *re = (nr * dr + ni * di) / dd;
    *im = (ni * dr - nr * di) / dd;
    return 1;
}
