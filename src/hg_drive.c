/* hg_drive.c - servo amplifiers and windings over one step (hg_drive.h). */
#include "hg_math.h"
#include "hg_drive.h"
#include "hg_units.h"

double hg_drive_log(double x)
{
    double y, s = 1.0;
    int k;
    if (!(x > 1.0))
        return 0.0;
    for (k = 0; k < 60 && x > 1.001; k++) {     /* x^(2^-k) close to 1 */
        x = sqrt(x);
        s *= 2.0;
    }
    y = x - 1.0;                                /* ln(1 + y), |y| < 1e-3: 5 terms */
    return s * y * (1.0 - y * (0.5 - y * (1.0 / 3.0 - y * (0.25 - y * 0.2))));
}

void hg_drive_init(hg_drive_channel *c, const hg_drive_params *p)
{
    c->p = *p;
    c->force_per_amp_n = p->kt_nm_per_a * (2.0 * HG_PI / p->lead_m);
    c->tau_s = p->l_winding_h / p->r_winding_ohm;
}

/* x clamped to [-lim, lim], lim > 0, x finite: libm's fmax(-lim, fmin(lim, x)) bit for bit. */
static inline double clamp(double x, double lim)
{
    return x > lim ? lim : (x < -lim ? -lim : x);
}

/* exp(-dt / tau) of channel k, from the memo when it holds them. */
static double decay_of(hg_drive_memo *memo, int k, double dt, double tau)
{
    double e;
    if (memo && memo->dt_s[k] == dt && memo->tau_s[k] == tau)
        return memo->decay[k];
    e = exp(-dt / tau);
    if (memo) {
        memo->dt_s[k] = dt;
        memo->tau_s[k] = tau;
        memo->decay[k] = e;
    }
    return e;
}

/* The winding of channel k (c) from current i0 over dt with command
 * iref, back-EMF e (V): mean and end current. The amplifier applies
 * u = +-v_bus towards iref (i relaxes to (u - e) / r) until the current
 * gets there, then holds it if |r iref + e| <= v_bus. */
static void winding(const hg_drive_channel *c, int k, double i0, double iref, double e, double dt,
                    hg_drive_memo *memo, double *mean, double *end, int *limited)
{
    const double v = c->p.v_bus_v, r = c->p.r_winding_ohm, tau = c->tau_s;
    double u, is, decay, iend, ts;
    *limited = 0;
    if (i0 < iref || (i0 == iref && r * iref + e > v))
        u = v;
    else if (i0 > iref || (i0 == iref && r * iref + e < -v))
        u = -v;
    else {                                      /* held at the command */
        *mean = *end = iref;
        return;
    }
    is = (u - e) / r;                           /* where full voltage takes the current */
    decay = decay_of(memo, k, dt, tau);
    iend = is + (i0 - is) * decay;
    if ((u > 0.0 && is > iref && iend >= iref) || (u < 0.0 && is < iref && iend <= iref)) {
        /* reaches the command at ts = tau ln((is - i0) / (is - iref)) < dt, then holds */
        ts = tau * hg_drive_log((is - i0) / (is - iref));
        if (ts > dt)
            ts = dt;
        *mean = (iref * dt + (is - iref) * ts + tau * (i0 - iref)) / dt;
        *end = iref;
        return;
    }
    /* full voltage all step long: the bus limits the current */
    *mean = is + (i0 - is) * tau * (1.0 - decay) / dt;
    *end = iend;
    *limited = 1;
}

void hg_drive_step(const hg_drive_channel *c, int n, const double *volts, const double *current_a,
                   const double *speed_mps, const double *vloop_int_m, unsigned enabled, double dt,
                   hg_drive_memo *memo, hg_drive_out *o)
{
    int k;
    o->limited = 0;
    for (k = 0; k < n && k < HG_DRIVE_MAX; k++) {
        const hg_drive_params *p = &c[k].p;
        double v = isfinite(volts[k]) ? clamp(volts[k], HG_DAC_VOLTS_MAX) : 0.0;
        double iref, e = c[k].force_per_amp_n * speed_mps[k];   /* back-EMF: kt (2 pi / lead) z' */
        int lim, wl;
        o->v_ref[k] = v * p->v_rated_mps / HG_DAC_VOLTS_MAX;
        if (!((enabled >> k) & 1u)) {
            o->i_mean[k] = o->i_end[k] = o->i_ref[k] = 0.0;
            continue;
        }
        if (p->amp_mode == 1.0)
            iref = p->kp_vel_as_per_m * (o->v_ref[k] - speed_mps[k]) + p->ki_vel_a_per_m * vloop_int_m[k];
        else
            iref = p->ka_a_per_v * v;
        lim = !(fabs(iref) <= p->i_max_a);
        iref = clamp(isfinite(iref) ? iref : 0.0, p->i_max_a);
        o->i_ref[k] = iref;
        winding(&c[k], k, current_a[k], iref, e, dt, memo, &o->i_mean[k], &o->i_end[k], &wl);
        if (lim || wl)
            o->limited |= 1u << k;
    }
}

void hg_drive_integral(const hg_drive_channel *c, int n, unsigned enabled, const hg_drive_out *o,
                       const double *z0, const double *z1, double dt, double *vint)
{
    int k;
    for (k = 0; k < n && k < HG_DRIVE_MAX; k++) {
        if (c[k].p.amp_mode != 1.0 || !((enabled >> k) & 1u))
            vint[k] = 0.0;
        else if (!((o->limited >> k) & 1u))
            vint[k] += o->v_ref[k] * dt - (z1[k] - z0[k]);
    }
}
