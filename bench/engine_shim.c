/* engine_shim.c - one hg_step engine behind an interface that does not
 * depend on hg_model's or hg_data's layout, so that bench_baseline can
 * run today's core and an earlier commit's side by side: compiled once
 * against today's src/ and once against the baseline's (bench/baseline.sh,
 * which renames ENGINE(x) to old_engine_x and hides every other symbol).
 * Both machines have rigid drive trains: the only ones d20d9e5 knew.
 * Host code (malloc). */
#include <stdlib.h>
#include "hg_dynamics.h"

#ifndef ENGINE
#define ENGINE(x) now_engine_##x
#endif

typedef struct {
    hg_model m;
    hg_data d;
} engine;

/* A machine with the default parameters at HOME: model kind, scheme,
 * frictionless (1: no sliding or static friction); 0 when it cannot be built. */
void *ENGINE(new)(int kind, int integrator, int frictionless)
{
    engine *e = malloc(sizeof *e);
    hg_params p;
    hg_params_default(&p);
#ifdef HG_DRIVETRAIN_H
    p.k_axial_n_per_m = 0.0;   /* the rigid trains of the machine before the drive train (d20d9e5's) */
#endif
    if (frictionless)
        p.f_coulomb_n = p.f_static_n = 0.0;
    if (!e || hg_model_init(&e->m, &p, (hg_model_kind)kind, 0, 0) ||
        hg_model_set_integrator(&e->m, integrator) || hg_data_reset(&e->m, &e->d)) {
        free(e);
        return 0;
    }
    return e;
}

/* One hg_step of dt with the volts; the carriage heights after it in z. 0 or the code. */
int ENGINE(step)(void *h, const double volts[6], double dt, double z[6])
{
    engine *e = h;
    int k, rc = hg_step(&e->m, &e->d, volts, dt);
    for (k = 0; k < 6; k++)
        z[k] = e->d.z_m[k];
    return rc;
}

/* The voltage that holds the machine's weight at HOME (V per drive). */
double ENGINE(hold_volts)(void *h)
{
    const engine *e = h;
    const hg_params *p = &e->m.p;
    return p->g_mps2 * (p->m_head_kg + 6.0 * (p->m_bar_kg + p->m_carriage_kg)) / 6.0 /
           e->m.force_per_volt_n;
}

void ENGINE(free)(void *h)
{
    free(h);
}
