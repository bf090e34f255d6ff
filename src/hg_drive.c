/* hg_drive.c - servo amplifiers and windings over one step (hg_drive.h). */
#include "hg_math.h"
#include "hg_drive.h"
#include "hg_forces.h"

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

/* The winding from current i0 over dt with command iref, back-EMF e (V),
 * bus v, resistance r, time constant tau: mean and end current. The
 * amplifier applies u = +-v towards iref (i relaxes to (u - e) / r) until
 * the current gets there, then holds it if |r iref + e| <= v. */
static void winding(double i0, double iref, double e, double v, double r, double tau, double dt,
                    double *mean, double *end, int *limited)
{
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
    decay = exp(-dt / tau);
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

void hg_drive_step(const hg_model *m, const hg_data *d, const double volts[6], double dt,
                   hg_drive_out *o)
{
    const hg_params *p = &m->p;
    const double tau = p->l_winding_h / p->r_winding_ohm;
    int k;
    o->limited = 0;
    for (k = 0; k < 6; k++) {
        double v = isfinite(volts[k]) ? fmax(-HG_DAC_VOLTS_MAX, fmin(HG_DAC_VOLTS_MAX, volts[k])) : 0.0;
        double iref, e = m->force_per_amp_n * d->zd_mps[k];   /* back-EMF: kt (2 pi / lead) z' */
        int lim, wl;
        o->v_ref[k] = v * p->v_rated_mps / HG_DAC_VOLTS_MAX;
        if (!((d->amp_enabled >> k) & 1u)) {
            o->i_mean[k] = o->i_end[k] = o->i_ref[k] = 0.0;
            continue;
        }
        if (p->amp_mode == 1.0)
            iref = p->kp_vel_as_per_m * (o->v_ref[k] - d->zd_mps[k]) + p->ki_vel_a_per_m * d->vloop_int_m[k];
        else
            iref = p->ka_a_per_v * v;
        lim = !(fabs(iref) <= p->i_max_a);
        iref = fmax(-p->i_max_a, fmin(p->i_max_a, isfinite(iref) ? iref : 0.0));
        o->i_ref[k] = iref;
        winding(d->current_a[k], iref, e, p->v_bus_v, p->r_winding_ohm, tau, dt, &o->i_mean[k],
                &o->i_end[k], &wl);
        if (lim || wl)
            o->limited |= 1u << k;
    }
}

void hg_drive_integral(const hg_model *m, unsigned enabled, const hg_drive_out *o,
                       const double z0[6], const double z1[6], double dt, double vint[6])
{
    int k;
    for (k = 0; k < 6; k++) {
        if (m->p.amp_mode != 1.0 || !((enabled >> k) & 1u))
            vint[k] = 0.0;
        else if (!((o->limited >> k) & 1u))
            vint[k] += o->v_ref[k] * dt - (z1[k] - z0[k]);
    }
}
