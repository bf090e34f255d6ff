/* hg_biquad.h - LinuxCNC's `biquad` HAL component (src/hal/components/
 * biquad.comp at LinuxCNC commit f1270d6ed71521f6551397a98b7496027cd331b8,
 * Debian's 2.9), expression by expression: one instance's pins and
 * parameters, and its function, so that an offline loop with a notch
 * (hg_loop: pid.N.output -> biquad.N -> the DAC) predicts what LinuxCNC runs.
 *
 * What biquad.comp does: on a rising edge of `enable` (and only then) it
 * computes the coefficients for `type` (1 low pass, 2 notch; 0 keeps the
 * n0 n1 n2 d1 d2 parameters as set) from f0 (Hz), Q and the sample rate
 * 1 / the thread's period: w0 = 2 PI f0 / rate with its PI = 3.141592653589,
 * alpha = sin(w0) / (2 Q); notch b = (1, -2 cos w0, 1), a = (1 + alpha,
 * -2 cos w0, 1 - alpha) (the bilinear transform of (s^2 + w^2) / (s^2 +
 * s w / Q + w^2) prewarped at f0); it refuses (valid 0: the input passes
 * unfiltered) Q outside 0.5..2 or f0 above half the rate; states s1 s2
 * start at 0. Each period: out = in while disabled or not valid, else the
 * transposed direct form II. (Its man page says "2 > Q > 0.5" and
 * "f0 > sampleRate/2"; the code accepts Q = 0.5 and 2 and needs f0 <= rate/2.)
 * There is no sample-rate pin: the rate is the thread's (s1, s2 are the
 * states, for debugging).
 * Pure C, no allocation, no stdio (host only: LinuxCNC runs its own biquad). */
#ifndef HG_BIQUAD_H
#define HG_BIQUAD_H

enum { HG_BIQUAD_DIRECT = 0, HG_BIQUAD_LOW_PASS = 1, HG_BIQUAD_NOTCH = 2 };

/* One instance biquad.N: its pins and parameters, named as in HAL, and the
 * component's Internal data. */
typedef struct {
    double in;                 /* pin in */
    double out;                /* pin out */
    int enable;                /* pin enable */
    int valid;                 /* pin valid (out) */
    unsigned type;             /* pin type (type_ in the .comp) */
    double f0;                 /* pin f0 (Hz) */
    double Q;                  /* pin Q */
    double d1, d2, n0, n1, n2; /* rw parameters: the coefficients */
    double s1, s2;             /* pins s1, s2: the states */
    int last_enable;           /* Internal.lastEnable */
} hg_biquad;

/* The values of a freshly loaded instance (loadrt biquad): disabled,
 * type 0, f0 250 Hz, Q 0.7071, n0 1, every other coefficient and state 0. */
void hg_biquad_defaults(hg_biquad *b);

/* A notch as `setp biquad.N.type 2`, `f0`, `Q`, `enable 1` would set it on
 * a freshly loaded instance (coefficients computed at the first period). */
void hg_biquad_notch(hg_biquad *b, double f0_hz, double q);

/* The component's function for one period of period_ns: b->in -> b->out. */
void hg_biquad_run(hg_biquad *b, long period_ns);

/* What the filter does in steady state at f_hz once enabled with b's
 * settings in a thread of period_ns: H(e^{j 2 pi f T}) of the coefficients
 * the enable edge computes (1 when they are refused), as re, im; returns
 * the valid pin (1, or 0: refused, the input passes). b is not changed. */
int hg_biquad_response(const hg_biquad *b, long period_ns, double f_hz, double *re, double *im);

#endif
