/* hg_system.c - the generated terms of each parametrization as dense
 * blocks, the full Newton-Raphson position solve and the energies. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE   /* sincos; Makefile.modinc already defines it */
#endif
#include <math.h>
#include <string.h>
#include "hg_step.h"
#include "hg_linalg.h"
#include "hg_errors.h"
#include "hg_gen_reduced.h"
#include "hg_gen_standard.h"

#define HG_NR_MAX_ITER 50
#define HG_NR_TOL 1e-15   /* m (standard) or m^2 (reduced) residual */

int hg_system_nq(const hg_model *m)
{
    return m->kind == HG_MODEL_STANDARD ? HG_NQ_STANDARD : HG_NQ_REDUCED;
}

/* Standard blocks -> dense: d = [a(12), c(6)]. */
static void standard_terms(const hg_model *m, const double *q, const double *qd, hg_system *s)
{
    double Mza[12], Maa[24], Mcc[36], Phi_a[36], Phi_c[108];
    int k, r, c;
    memset(s, 0, sizeof *s);
    s->nd = 18;
    hg_gen_standard_terms(m->k, q, qd, s->mzz, Mza, Maa, Mcc, s->Q, Phi_a, Phi_c, s->gamma);
    for (k = 0; k < 6; k++) {
        s->Mzd[k * 18 + 2 * k] = Mza[2 * k];
        s->Mzd[k * 18 + 2 * k + 1] = Mza[2 * k + 1];
        for (r = 0; r < 2; r++)
            for (c = 0; c < 2; c++)
                s->Mdd[(2 * k + r) * 18 + 2 * k + c] = Maa[4 * k + 2 * r + c];
        for (r = 0; r < 3; r++)
            for (c = 0; c < 2; c++)
                s->Phi_d[(3 * k + r) * 18 + 2 * k + c] = Phi_a[6 * k + 2 * r + c];
        s->Phi_z[(3 * k + 2) * 6 + k] = 1.0;
    }
    for (r = 0; r < 6; r++)
        for (c = 0; c < 6; c++)
            s->Mdd[(12 + r) * 18 + 12 + c] = Mcc[6 * r + c];
    for (r = 0; r < 18; r++)
        for (c = 0; c < 6; c++)
            s->Phi_d[r * 18 + 12 + c] = Phi_c[6 * r + c];
}

void hg_head_trig(const double *c, double sc[6])
{
    sincos(c[3], &sc[0], &sc[1]);
    sincos(c[4], &sc[2], &sc[3]);
    sincos(c[5], &sc[4], &sc[5]);
}

/* Reduced terms with constants kc -> dense: d = c. */
static void reduced_terms(const double *kc, const double *q, const double *qd, hg_system *s)
{
    double Phi_z[6], sc[6];
    int k;
    s->nd = 6;
    hg_head_trig(q + 6, sc);
    hg_gen_reduced_terms(kc, q, qd, sc, s->mzz, s->Mzd, s->Mdd, s->Q, Phi_z, s->Phi_d, s->gamma);
    memset(s->Phi_z, 0, 36 * sizeof(double));
    for (k = 0; k < 6; k++)
        s->Phi_z[k * 6 + k] = Phi_z[k];
}

void hg_system_terms(const hg_model *m, const double *q, const double *qd, hg_system *s)
{
    if (m->kind == HG_MODEL_STANDARD)
        standard_terms(m, q, qd, s);
    else
        reduced_terms(m->k, q, qd, s);
}

void hg_system_constraints(const hg_model *m, const double *q, double *phi,
                           double *Phi_d, double *Phi_z)
{
    int k, r, c;
    if (m->kind == HG_MODEL_STANDARD) {
        double Phi_a[36], Phi_c[108];
        hg_gen_standard_constraints(m->k, q, phi, Phi_a, Phi_c);
        memset(Phi_d, 0, 18 * 18 * sizeof(double));
        memset(Phi_z, 0, 18 * 6 * sizeof(double));
        for (k = 0; k < 6; k++) {
            for (r = 0; r < 3; r++)
                for (c = 0; c < 2; c++)
                    Phi_d[(3 * k + r) * 18 + 2 * k + c] = Phi_a[6 * k + 2 * r + c];
            Phi_z[(3 * k + 2) * 6 + k] = 1.0;
        }
        for (r = 0; r < 18; r++)
            for (c = 0; c < 6; c++)
                Phi_d[r * 18 + 12 + c] = Phi_c[6 * r + c];
    } else {
        double pz[6], sc[6];
        hg_head_trig(q + 6, sc);
        hg_gen_reduced_constraints(m->k, q, sc, phi, pz, Phi_d);
        memset(Phi_z, 0, 36 * sizeof(double));
        for (k = 0; k < 6; k++)
            Phi_z[k * 6 + k] = pz[k];
    }
}

int hg_solve_positions(const hg_model *m, double *q)
{
    double phi[18], Phi_d[18 * 18], Phi_z[18 * 6];
    int piv[18], it, i, rc;
    int nd = m->kind == HG_MODEL_STANDARD ? 18 : 6;
    for (it = 0; it < HG_NR_MAX_ITER; it++) {
        double worst = 0.0;
        hg_system_constraints(m, q, phi, Phi_d, Phi_z);
        for (i = 0; i < nd; i++)
            if (fabs(phi[i]) > worst)
                worst = fabs(phi[i]);
        if (!isfinite(worst))
            return HG_ERR_NO_CONVERGENCE;
        if (worst <= HG_NR_TOL)
            return 0;
        rc = hg_lu_factor(nd, Phi_d, piv);
        if (rc)
            return rc;
        hg_lu_solve(nd, Phi_d, piv, 1, phi);
        for (i = 0; i < nd; i++)
            q[6 + i] -= phi[i];
    }
    return HG_ERR_NO_CONVERGENCE;
}

/* 1/2 q'^T M q' from the dense blocks of s. */
static double kinetic_energy(const hg_system *s, const double *qd)
{
    double t = 0.0;
    int i, j, nd = s->nd;
    for (i = 0; i < 6; i++) {
        t += 0.5 * s->mzz[i] * qd[i] * qd[i];
        for (j = 0; j < nd; j++)
            t += s->Mzd[i * nd + j] * qd[i] * qd[6 + j];
    }
    for (i = 0; i < nd; i++)
        for (j = 0; j < nd; j++)
            t += 0.5 * s->Mdd[i * nd + j] * qd[6 + i] * qd[6 + j];
    return t;
}

void hg_lumped_energy(const double *k, const double *q, const double *qd,
                      double *kinetic_j, double *potential_j)
{
    hg_system s;
    double sc[6];
    reduced_terms(k, q, qd, &s);
    *kinetic_j = kinetic_energy(&s, qd);
    hg_head_trig(q + 6, sc);
    hg_gen_reduced_potential(k, q, sc, potential_j);
}

void hg_model_energy(const hg_model *m, const double *q, const double *qd,
                     double *kinetic_j, double *potential_j)
{
    hg_system s;
    if (m->kind != HG_MODEL_STANDARD) {
        hg_lumped_energy(m->k, q, qd, kinetic_j, potential_j);
        return;
    }
    hg_system_terms(m, q, qd, &s);
    *kinetic_j = kinetic_energy(&s, qd);
    hg_gen_standard_potential(m->k, q, potential_j);
}
