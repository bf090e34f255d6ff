/* hg_forces.c - drive, friction and hard-stop forces on the carriages. */
#include "hg_math.h"
#include "hg_forces.h"

/* Amplifier current (A) for a DAC command. */
static inline double drive_current(const hg_params *p, double volts)
{
    double v = isfinite(volts) ? volts : 0.0;
    double i;
    if (v > HG_DAC_VOLTS_MAX)
        v = HG_DAC_VOLTS_MAX;
    if (v < -HG_DAC_VOLTS_MAX)
        v = -HG_DAC_VOLTS_MAX;
    i = p->ka_a_per_v * v;
    if (i > p->i_max_a)
        i = p->i_max_a;
    if (i < -p->i_max_a)
        i = -p->i_max_a;
    return i;
}

/* Force (N, +z) of the hard stops on a carriage at z_m moving at zd_mps. */
static inline double stop_force(const hg_params *p, double z_m, double zd_mps)
{
    double f = 0.0;
    if (z_m > p->stop_max_m) {
        f = -p->k_stop_n_per_m * (z_m - p->stop_max_m) - p->c_stop_ns_per_m * zd_mps;
        if (f > 0.0)
            f = 0.0;
    } else if (z_m < p->stop_min_m) {
        f = p->k_stop_n_per_m * (p->stop_min_m - z_m) - p->c_stop_ns_per_m * zd_mps;
        if (f < 0.0)
            f = 0.0;
    }
    return f;
}

/* tanh from exp (rtapi_math has no tanh): odd series below |x| = 1e-3
 * (error below x^7), 1 - 2/(e^2|x| + 1) above (exp overflowing to inf
 * gives exactly 1); within 2e-16 of libm's. */
static inline double smooth_sign(double x)
{
    double a = fabs(x), t;
    if (a < 1e-3) {
        double x2 = x * x;
        return x * (1.0 - x2 * (1.0 / 3.0 - x2 * (2.0 / 15.0)));
    }
    t = 1.0 - 2.0 / (exp(2.0 * a) + 1.0);
    return x < 0.0 ? -t : t;
}

void hg_carriage_forces(const hg_model *m, const double z_m[6], const double zd_mps[6],
                        const double volts[6], double force_n[6], double current_a[6])
{
    const hg_params *p = &m->p;
    int k;
    for (k = 0; k < 6; k++) {
        double i = drive_current(p, volts[k]);
        double f = i * m->force_per_amp_n - p->c_visc_ns_per_m * zd_mps[k];
        if (p->f_coulomb_n > 0.0)
            f -= p->f_coulomb_n * smooth_sign(zd_mps[k] / p->v_coulomb_mps);
        f += stop_force(p, z_m[k], zd_mps[k]);
        force_n[k] = f;
        if (current_a)
            current_a[k] = i;
    }
}
