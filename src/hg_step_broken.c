/* hg_step_broken.c - one step of the machine with one or more bars removed
 * (fault injection "a bar that breaks"). Without all six bars there is no
 * independent-coordinate split, so the lumped-bar model is integrated in
 * full coordinates q = [z(6), c(6)]: accelerations from the augmented
 * (KKT) system [M J^T; J 0] [q''; lambda] = [Q + f; -gamma] with J the
 * intact bars' rows of Phi_q, improved Euler, then an M-weighted Newton
 * projection of q and a projection of q' onto the remaining constraints. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE   /* sincos in hg_head_trig's callers; Makefile.modinc defines it */
#endif
#include <math.h>
#include <string.h>
#include "hg_step.h"
#include "hg_linalg.h"
#include "hg_errors.h"
#include "hg_gen_reduced.h"

#define NQ HG_NQ_REDUCED
#define BROKEN_NR_MAX_ITER 8        /* Newton projection iterations at most */
#define BROKEN_NR_TOL_M2 1e-13      /* |B-A|^2 - l^2 small enough to stop (m^2) */

typedef char hg_lumped_consts_fit[HG_GEN_REDUCED_NCONST <= HG_MAX_LUMPED_CONSTS ? 1 : -1];

/* Dense symmetric 12 x 12 M from the generated blocks (M_zz diagonal). */
static void mass_matrix(const double mzz[6], const double Mzc[36], const double Mcc[36],
                        double *M)
{
    int i, j;
    memset(M, 0, NQ * NQ * sizeof(double));
    for (i = 0; i < 6; i++) {
        M[i * NQ + i] = mzz[i];
        for (j = 0; j < 6; j++) {
            M[i * NQ + 6 + j] = Mzc[i * 6 + j];
            M[(6 + j) * NQ + i] = Mzc[i * 6 + j];
            M[(6 + i) * NQ + 6 + j] = Mcc[i * 6 + j];
        }
    }
}

/* Rows of the intact bars: J (nc x 12) of Phi_q = [diag(Phi_z) | Phi_c]
 * and, when v is given, out[r] = v[bar of row r]. Returns nc. */
static int intact_rows(unsigned broken, const double pz[6], const double pc[36],
                       const double *v, double *J, double *out)
{
    int k, j, nc = 0;
    for (k = 0; k < 6; k++) {
        if (broken & (1u << k))
            continue;
        memset(J + nc * NQ, 0, 6 * sizeof(double));
        J[nc * NQ + k] = pz[k];
        for (j = 0; j < 6; j++)
            J[nc * NQ + 6 + j] = pc[k * 6 + j];
        if (v)
            out[nc] = v[k];
        nc++;
    }
    return nc;
}

/* Solve [M J^T; J 0] [x; mu] = [top; bot] for x (12); nc <= 6 rows.
 * 0 or HG_ERR_SINGULAR_JACOBIAN (dependent constraints, singular M). */
static int kkt_solve(const double *M, int nc, const double *J, const double *top,
                     const double *bot, double *x)
{
    double K[HG_LINALG_MAX_N * HG_LINALG_MAX_N], b[HG_LINALG_MAX_N];
    int piv[HG_LINALG_MAX_N], n = NQ + nc, i, j, rc;
    memset(K, 0, sizeof K);
    for (i = 0; i < NQ; i++) {
        for (j = 0; j < NQ; j++)
            K[i * n + j] = M[i * NQ + j];
        b[i] = top[i];
    }
    for (i = 0; i < nc; i++) {
        for (j = 0; j < NQ; j++) {
            K[(NQ + i) * n + j] = J[i * NQ + j];
            K[j * n + NQ + i] = J[i * NQ + j];
        }
        b[NQ + i] = bot[i];
    }
    rc = hg_lu_factor(n, K, piv);
    if (rc)
        return rc;
    hg_lu_solve(n, K, piv, 1, b);
    memcpy(x, b, NQ * sizeof(double));
    return 0;
}

/* Intact-bar constraints at q: phi (nc, m^2) and J; returns max |phi|. */
static double constraints(const hg_model *m, unsigned broken, const double *q, double *phi,
                          double *J, int *nc)
{
    double sc[6], all[6], pz[6], pc[36], worst = 0.0;
    int r;
    hg_head_trig(q + 6, sc);
    hg_gen_reduced_constraints(m->k_lumped, q, sc, all, pz, pc);
    *nc = intact_rows(broken, pz, pc, all, J, phi);
    for (r = 0; r < *nc; r++)
        if (!(fabs(phi[r]) <= worst))
            worst = fabs(phi[r]);
    return worst;
}

/* Newton projection of q1 onto the intact constraints, minimum M-norm
 * corrections, then q1' projected (M-weighted) onto J q' = 0 at the
 * final q1. Returns 0 or a code; *residual_m the largest bar-length error. */
static int project(const hg_model *m, unsigned broken, const double *M, double *q1,
                   double *qd1, double *residual_m)
{
    static const double zero[NQ] = {0};
    double phi[6], J[6 * NQ], dq[NQ], Mv[NQ], neg[6], prev = INFINITY, worst = 0.0;
    const double l = m->p.geo.l_m;
    int it, r, i, j, nc = 0, rc;
    for (it = 0; it <= BROKEN_NR_MAX_ITER; it++) {
        double now = constraints(m, broken, q1, phi, J, &nc);
        if (!isfinite(now))
            return HG_ERR_STABILIZATION;
        if (now <= BROKEN_NR_TOL_M2 || it == BROKEN_NR_MAX_ITER)
            break;
        if (!(now < prev))
            return HG_ERR_DIVERGED;
        prev = now;
        for (r = 0; r < nc; r++)
            neg[r] = -phi[r];
        rc = kkt_solve(M, nc, J, zero, neg, dq);
        if (rc)
            return rc;
        for (i = 0; i < NQ; i++)
            q1[i] += dq[i];
    }
    for (r = 0; r < nc; r++) {        /* from phi = |B-A|^2 - l^2 */
        double e = fabs(phi[r]) / (sqrt(fmax(phi[r] + l * l, 0.0)) + l);
        if (!(e <= worst))
            worst = e;
        neg[r] = 0.0;
    }
    *residual_m = worst;
    for (i = 0; i < NQ; i++) {
        double v = 0.0;
        for (j = 0; j < NQ; j++)
            v += M[i * NQ + j] * qd1[j];
        Mv[i] = v;
    }
    return kkt_solve(M, nc, J, Mv, neg, qd1);
}

/* 0, or OUT_OF_VOLUME for a state the model no longer represents
 * (limits in hg_dynamics.h; NaN counts as out). */
static int check_volume(const double *q)
{
    int k, in = q[8] >= HG_BROKEN_HEAD_Z_MIN_M && fabs(q[6]) <= HG_BROKEN_REACH_M &&
                fabs(q[7]) <= HG_BROKEN_REACH_M;
    for (k = 0; k < 6; k++)
        in = in && fabs(q[k]) <= HG_BROKEN_REACH_M;
    for (k = 9; k < 12; k++)
        in = in && fabs(q[k]) <= HG_BROKEN_ROT_MAX_RAD;
    return in ? 0 : HG_ERR_OUT_OF_VOLUME;
}

int hg_step_broken(const hg_model *m, unsigned broken, const double *q0, const double *qd0,
                   const double fz[6], double dt, double *q1, double *qd1, double *qdd,
                   double *residual_m)
{
    double mzz[6], Mzc[36], Mcc[36], Q[NQ], pz[6], pc[36], gm[6], sc[6];
    double M[NQ * NQ], J[6 * NQ], rhs[6];
    int k, nc, rc;
    broken &= HG_BARS_ALL;
    hg_head_trig(q0 + 6, sc);
    hg_gen_reduced_terms(m->k_lumped, q0, qd0, sc, mzz, Mzc, Mcc, Q, pz, pc, gm);
    mass_matrix(mzz, Mzc, Mcc, M);
    for (k = 0; k < 6; k++) {
        Q[k] += fz[k];
        gm[k] = -gm[k];
    }
    nc = intact_rows(broken, pz, pc, gm, J, rhs);
    rc = kkt_solve(M, nc, J, Q, rhs, qdd);
    if (rc)
        return rc;
    hg_improved_euler(NQ, q0, qd0, qdd, dt, q1, qd1);
    /* the projection's metric: M at the predicted state */
    hg_head_trig(q1 + 6, sc);
    hg_gen_reduced_terms(m->k_lumped, q1, qd1, sc, mzz, Mzc, Mcc, Q, pz, pc, gm);
    mass_matrix(mzz, Mzc, Mcc, M);
    rc = project(m, broken, M, q1, qd1, residual_m);
    if (rc)
        return rc;
    return check_volume(q1);
}
