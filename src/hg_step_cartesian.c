/* hg_step_cartesian.c - one step of the Reduced Cartesian parametrization
 * (head pose c independent, carriage heights z dependent): Phi_z is
 * diagonal, so A = -Phi_z^-1 Phi_c costs 36 products and the position
 * stabilization is one diagonal Newton step per carriage. The fused
 * variant gets its accelerations from one generated function. */
#include "hg_step.h"
#include "hg_linalg.h"
#include "hg_errors.h"
#include "hg_gen_reduced.h"

/* One Newton step z -= phi / Phi_z at the predicted state, then z' = A c'. */
static void stabilize(const hg_model *m, double *q1, double *qd1)
{
    double phi[6], pz[6], pc[36];
    int k, j;
    hg_gen_reduced_constraints(m->k, q1, phi, pz, pc);
    for (k = 0; k < 6; k++) {
        double ipz = 1.0 / pz[k], v = 0.0;
        q1[k] -= phi[k] * ipz;
        for (j = 0; j < 6; j++)
            v += pc[6 * k + j] * qd1[6 + j];
        qd1[k] = -v * ipz;
    }
}

int hg_step_cartesian(const hg_model *m, const double *q0, const double *qd0,
                      const double fz[6], double dt, double *q1, double *qd1, double *qdd)
{
    double mzz[6], Mzc[36], Mcc[36], Q[12], pz[6], pc[36], gm[6];
    double A[36], b[6], fq[6], T1[36], Mh[36], rhs[6];
    int i, j, k, rc;
    hg_gen_reduced_terms(m->k, q0, qd0, mzz, Mzc, Mcc, Q, pz, pc, gm);
    for (k = 0; k < 6; k++) {
        double ipz = 1.0 / pz[k];
        for (j = 0; j < 6; j++)
            A[6 * k + j] = -pc[6 * k + j] * ipz;
        b[k] = -gm[k] * ipz;
        fq[k] = Q[k] + fz[k];
    }
    for (i = 0; i < 6; i++)            /* T1 = M_cz + A^T M_zz */
        for (k = 0; k < 6; k++)
            T1[6 * i + k] = Mzc[6 * k + i] + A[6 * k + i] * mzz[k];
    for (i = 0; i < 6; i++) {
        double r = Q[6 + i];
        for (k = 0; k < 6; k++)
            r += A[6 * k + i] * fq[k] - T1[6 * i + k] * b[k];
        rhs[i] = r;
        for (j = 0; j <= i; j++) {
            double v = Mcc[6 * i + j];
            for (k = 0; k < 6; k++)
                v += T1[6 * i + k] * A[6 * k + j] + Mzc[6 * k + j] * A[6 * k + i];
            Mh[6 * i + j] = v;
        }
    }
    rc = hg_cholesky_factor(6, Mh);
    if (rc)
        return rc;
    hg_cholesky_solve(6, Mh, rhs);
    for (k = 0; k < 6; k++) {          /* z'' = A c'' + b */
        double v = b[k];
        for (j = 0; j < 6; j++)
            v += A[6 * k + j] * rhs[j];
        qdd[k] = v;
        qdd[6 + k] = rhs[k];
    }
    hg_improved_euler(HG_NQ_REDUCED, q0, qd0, qdd, dt, q1, qd1);
    stabilize(m, q1, qd1);
    return 0;
}

int hg_step_fused(const hg_model *m, const double *q0, const double *qd0,
                  const double fz[6], double dt, double *q1, double *qd1, double *qdd)
{
    int rc = hg_gen_fused_accel(m->k, q0, qd0, fz, qdd);
    if (rc)
        return rc;
    hg_improved_euler(HG_NQ_REDUCED, q0, qd0, qdd, dt, q1, qd1);
    stabilize(m, q1, qd1);
    return 0;
}
