/* hg_system.c - what every parametrization's step shares: the full
 * Newton-Raphson position solve, bar angles and the energies (from the
 * generated blocks, no dense matrices). */
#include "hg_math.h"
#include "hg_system.h"
#include "hg_kinematics.h"
#include "hg_lu6.h"
#include "hg_errors.h"
#include "hg_gen_reduced.h"
#include "hg_gen_standard.h"

#define HG_NR_MAX_ITER 50
#define HG_NR_TOL_M2 1e-15   /* |B-A|^2 - l^2 residual (m^2) */

int hg_system_nq(const hg_model *m)
{
    return m->kind == HG_MODEL_STANDARD ? HG_NQ_STANDARD : HG_NQ_REDUCED;
}

void hg_bar_angles(const hg_params *p, const double z[6], const double c[6], double a[12])
{
    double B[6][3], A[6][3];
    int k;
    hg_joint_points(&p->geo, z, c, B, A);
    for (k = 0; k < 6; k++) {
        double u[3], n;
        int r;
        for (r = 0; r < 3; r++)
            u[r] = A[k][r] - B[k][r];
        n = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        if (!(n > 0.0))                /* a broken bar's ends can meet */
            continue;
        a[2 * k] = atan2(u[1], -u[2]);
        a[2 * k + 1] = asin(fmax(-1.0, fmin(1.0, -u[0] / n)));
    }
}

int hg_solve_positions(const hg_model *m, double *q)
{
    /* the bars' lengths fix the head pose alike in every parametrization:
     * solve it with the lumped-bar constraints (the model's own k for the
     * reduced kinds) */
    const double *k = m->kind == HG_MODEL_STANDARD ? m->k_lumped : m->k;
    double *c = q + hg_system_nq(m) - 6;
    double qr[HG_NQ_REDUCED], phi[6], pz[6], pc[36], sc[6];
    int piv[6], it, i, rc;
    for (i = 0; i < 6; i++) {
        qr[i] = q[i];
        qr[6 + i] = c[i];
    }
    for (it = 0; it < HG_NR_MAX_ITER; it++) {
        double worst = 0.0;
        hg_head_trig(qr + 6, sc);
        hg_gen_reduced_constraints(k, qr, sc, phi, pz, pc);
        for (i = 0; i < 6; i++)
            if (fabs(phi[i]) > worst)
                worst = fabs(phi[i]);
        if (!isfinite(worst))
            return HG_ERR_NO_CONVERGENCE;
        if (worst <= HG_NR_TOL_M2)
            break;
        rc = hg_lu6_factor(pc, piv);
        if (rc)
            return rc;
        hg_lu6_solve(pc, piv, 1, phi);
        for (i = 0; i < 6; i++)
            qr[6 + i] -= phi[i];
    }
    if (it == HG_NR_MAX_ITER)
        return HG_ERR_NO_CONVERGENCE;
    for (i = 0; i < 6; i++)
        c[i] = qr[6 + i];
    if (m->kind == HG_MODEL_STANDARD)
        hg_bar_angles(&m->p, q, c, q + 6);
    return 0;
}

void hg_stabilize_dependent(int nd, const double *X, double *q1, double *qd1)
{
    int r, j;
    for (r = 0; r < nd; r++) {
        double v = 0.0;
        q1[6 + r] -= X[r * 7 + 6];
        for (j = 0; j < 6; j++)
            v -= X[r * 7 + j] * qd1[j];
        qd1[6 + r] = v;
    }
}

/* 1/2 x^T B y summed over a dense nr x nc block B (row-major), times w. */
static double quad(int nr, int nc, const double *B, const double *x, const double *y, double w)
{
    double t = 0.0;
    int i, j;
    for (i = 0; i < nr; i++)
        for (j = 0; j < nc; j++)
            t += B[i * nc + j] * x[i] * y[j];
    return w * t;
}

void hg_lumped_energy(const double *k, const double *q, const double *qd,
                      double *kinetic_j, double *potential_j)
{
    double mzz[6], Mzc[36], Mcc[36], Q[12], pz[6], pc[36], gm[6], sc[6], t = 0.0;
    int i;
    hg_head_trig(q + 6, sc);
    hg_gen_reduced_terms(k, q, qd, sc, mzz, Mzc, Mcc, Q, pz, pc, gm);
    for (i = 0; i < 6; i++)
        t += 0.5 * mzz[i] * qd[i] * qd[i];
    *kinetic_j = t + quad(6, 6, Mzc, qd, qd + 6, 1.0) + quad(6, 6, Mcc, qd + 6, qd + 6, 0.5);
    hg_gen_reduced_potential(k, q, sc, potential_j);
}

void hg_model_energy(const hg_model *m, const double *q, const double *qd,
                     double *kinetic_j, double *potential_j)
{
    double mzz[6], Mza[12], Maa[24], Mcc[36], Q[24], Pa[36], Pc[108], gm[18], t = 0.0;
    int i;
    if (m->kind != HG_MODEL_STANDARD) {
        hg_lumped_energy(m->k, q, qd, kinetic_j, potential_j);
        return;
    }
    hg_gen_standard_terms(m->k, q, qd, mzz, Mza, Maa, Mcc, Q, Pa, Pc, gm);
    for (i = 0; i < 6; i++)            /* M_zz, M_za (bar i's row), M_aa 2x2 per bar */
        t += 0.5 * mzz[i] * qd[i] * qd[i] + qd[i] * (Mza[2 * i] * qd[6 + 2 * i] +
                                                     Mza[2 * i + 1] * qd[7 + 2 * i]) +
             quad(2, 2, Maa + 4 * i, qd + 6 + 2 * i, qd + 6 + 2 * i, 0.5);
    *kinetic_j = t + quad(6, 6, Mcc, qd + 18, qd + 18, 0.5);
    hg_gen_standard_potential(m->k, q, potential_j);
}
