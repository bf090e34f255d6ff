/* hg_forces.c - drive, friction and hard-stop forces on the carriages. */
#include <math.h>
#include "hg_forces.h"
#include "hg_units.h"

#define HG_DAC_MAX_V 10.0

/* Amplifier current (A) for a DAC command. */
static inline double drive_current(const hg_params *p, double volts)
{
    double v = isfinite(volts) ? volts : 0.0;
    double i;
    if (v > HG_DAC_MAX_V)
        v = HG_DAC_MAX_V;
    if (v < -HG_DAC_MAX_V)
        v = -HG_DAC_MAX_V;
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

void hg_carriage_forces(const hg_params *p, const double z_m[6], const double zd_mps[6],
                        const double volts[6], double force_n[6], double current_a[6])
{
    const double screw = 2.0 * HG_PI / p->lead_m; /* N per N m */
    int k;
    for (k = 0; k < 6; k++) {
        double i = drive_current(p, volts[k]);
        double f = i * p->kt_nm_per_a * screw - p->c_visc_ns_per_m * zd_mps[k];
        if (p->f_coulomb_n > 0.0)
            f -= p->f_coulomb_n * tanh(zd_mps[k] / p->v_coulomb_mps);
        f += stop_force(p, z_m[k], zd_mps[k]);
        force_n[k] = f;
        if (current_a)
            current_a[k] = i;
    }
}
