/* hg_step_broken.c - one step of the machine with one or more bars removed
 * (fault injection "a bar that breaks"). Without all six bars there is no
 * independent-coordinate split, so the lumped-bar model is integrated in
 * full coordinates q = [z(6), c(6)]: accelerations from the augmented
 * (KKT) system [M J^T; J 0] [q''; lambda] = [Q + f; -gamma] with J the
 * intact bars' rows of Phi_q, integrated by hg_integrate, then an
 * M-weighted Newton projection of q and a projection of q' onto the
 * remaining constraints. */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_step_broken.h"
#include "hg_system.h"
#include "hg_linalg.h"
#include "hg_errors.h"
#include "hg_gen_reduced.h"

#define NQ HG_NQ_REDUCED
#define BROKEN_NR_MAX_ITER 8        /* Newton projection iterations at most */
#define BROKEN_NR_TOL_M2 1e-13      /* |B-A|^2 - l^2 small enough to stop (m^2) */

typedef char hg_lumped_consts_fit[HG_GEN_REDUCED_NCONST <= HG_MAX_LUMPED_CONSTS ? 1 : -1];

/* Scratch laid over d->work.step. */
typedef struct {
    double K[HG_LINALG_MAX_N * HG_LINALG_MAX_N], b[HG_LINALG_MAX_N]; /* KKT system */
    int piv[HG_LINALG_MAX_N];
    double M[NQ * NQ], J[6 * NQ];                                     /* mass matrix, intact rows */
    double mzz[6], Mzc[36], Mcc[36], Q[NQ], pz[6], pc[36], gm[6], sc[6], rhs[6];
    double phi[6], dq[NQ], Mv[NQ], neg[6];
} broken_ws;
typedef char hg_broken_ws_fits[sizeof(broken_ws) <= sizeof(((hg_work *)0)->step) ? 1 : -1];

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
static int kkt_solve(broken_ws *w, const double *M, int nc, const double *J, const double *top,
                     const double *bot, double *x)
{
    double *K = w->K, *b = w->b;
    int *piv = w->piv, n = NQ + nc, i, j, rc;
    memset(K, 0, sizeof w->K);
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
static double constraints(const hg_model *m, broken_ws *w, unsigned broken, const double *q,
                          double *phi, double *J, int *nc)
{
    double all[6], worst = 0.0;
    int r;
    hg_head_trig(q + 6, w->sc);
    hg_gen_reduced_constraints(m->k_lumped, q, w->sc, all, w->pz, w->pc);
    *nc = intact_rows(broken, w->pz, w->pc, all, J, phi);
    for (r = 0; r < *nc; r++)
        if (!(fabs(phi[r]) <= worst))
            worst = fabs(phi[r]);
    return worst;
}

/* Newton projection of q1 onto the intact constraints, minimum M-norm
 * corrections, then q1' projected (M-weighted) onto J q' = 0 at the
 * final q1. Returns 0 or a code; *residual_m the largest bar-length error. */
static int project(const hg_model *m, broken_ws *w, unsigned broken, const double *M, double *q1,
                   double *qd1, double *residual_m)
{
    static const double zero[NQ] = {0};
    double *phi = w->phi, *J = w->J, *dq = w->dq, *Mv = w->Mv, *neg = w->neg;
    double prev = INFINITY, worst = 0.0;
    const double l = m->p.geo.l_m;
    int it, r, i, j, nc = 0, rc;
    for (it = 0; it <= BROKEN_NR_MAX_ITER; it++) {
        double now = constraints(m, w, broken, q1, phi, J, &nc);
        if (!isfinite(now))
            return HG_ERR_STABILIZATION;
        if (now <= BROKEN_NR_TOL_M2 || it == BROKEN_NR_MAX_ITER)
            break;
        if (!(now < prev))
            return HG_ERR_DIVERGED;
        prev = now;
        for (r = 0; r < nc; r++)
            neg[r] = -phi[r];
        rc = kkt_solve(w, M, nc, J, zero, neg, dq);
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
    return kkt_solve(w, M, nc, J, Mv, neg, qd1);
}

int hg_broken_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                    const double fz[6], double *qdd)
{
    broken_ws *w = (broken_ws *)d->work.step;
    int k, nc, rc;
    hg_head_trig(q + 6, w->sc);
    hg_gen_reduced_terms(m->k_lumped, q, qd, w->sc, w->mzz, w->Mzc, w->Mcc, w->Q, w->pz, w->pc,
                         w->gm);
    mass_matrix(w->mzz, w->Mzc, w->Mcc, w->M);
    for (k = 0; k < 6; k++) {
        w->Q[k] += fz[k];
        w->gm[k] = -w->gm[k];
    }
    nc = intact_rows(d->broken_bars & HG_BARS_ALL, w->pz, w->pc, w->gm, w->J, w->rhs);
    rc = kkt_solve(w, w->M, nc, w->J, w->Q, w->rhs, qdd);
    if (rc == 0 && d->work.mass.want)  /* the step's start: friction's mass data */
        hg_mass_save_kkt(&d->work.mass, NQ + nc, w->K, w->piv);
    return rc;
}

int hg_broken_stabilize(const hg_model *m, hg_data *d, double *q1, double *qd1,
                        double *residual_m)
{
    broken_ws *w = (broken_ws *)d->work.step;
    /* the projection's metric: M at the predicted state */
    hg_head_trig(q1 + 6, w->sc);
    hg_gen_reduced_terms(m->k_lumped, q1, qd1, w->sc, w->mzz, w->Mzc, w->Mcc, w->Q, w->pz, w->pc,
                         w->gm);
    mass_matrix(w->mzz, w->Mzc, w->Mcc, w->M);
    return project(m, w, d->broken_bars & HG_BARS_ALL, w->M, q1, qd1, residual_m);
}

const hg_dae hg_broken_dae = {NQ, 0, NQ, hg_broken_accel, hg_hold_independent, hg_broken_stabilize};
