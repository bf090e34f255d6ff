/* hg_forces.c - drive, viscous and hard-stop forces on the carriages. */
#include "hg_math.h"
#include "hg_forces.h"
#include "hg_stop.h"

/* Force (N, +z) of the hard stops on a carriage at z_m moving at zd_mps. */
static inline double stop_force(const hg_params *p, double z_m, double zd_mps)
{
    return hg_stop_force(z_m, zd_mps, p->stop_min_m, p->stop_max_m, p->k_stop_n_per_m, p->c_stop_ns_per_m);
}

void hg_carriage_forces(const hg_model *m, const double z_m[6], const double zd_mps[6],
                        const double drive_n[6], double force_n[6])
{
    const hg_params *p = &m->p;
    int k;
    for (k = 0; k < 6; k++)
        force_n[k] = drive_n[k] - p->c_visc_ns_per_m * zd_mps[k] + stop_force(p, z_m[k], zd_mps[k]);
}
