/* hg_step_standard.c - the Standard parametrization (q = [z, a, c], z
 * independent) for hg_integrate, exploiting the structure of the bar
 * constraints B_k + l u_k - A_k = 0: Phi_d = [blockdiag(P_k) | C] with P_k
 * the 3x2 Jacobian of bar k's end in its two angles. Projecting bar k's
 * three rows on n_k = P_k(:,0) x P_k(:,1) removes its angles, so
 * Phi_d x = y is a 6x6 solve for x_c plus a 2x2 least-squares solve per
 * bar; the mass matrix is block diagonal in d. Eq. 13 as in the dense
 * formulation, a fraction of the work. */
#include "hg_step_standard.h"
#include "hg_system.h"
#include "hg_kinematics.h"
#include "hg_spd6.h"
#include "hg_lu6.h"
#include "hg_errors.h"
#include "hg_gen_standard.h"

/* Phi_d factored by bars. */
typedef struct {
    double n[6][3];      /* normal of bar k's angle columns */
    double G[6][6];      /* (P^T P)^-1 P^T, 2x3 per bar */
    double S[36];        /* S[k][j] = n_k . C_k(:, j), LU-factored */
    int piv[6];
    const double *Pc;    /* Phi_c, 18 x 6 */
} std_factor;

/* Factor Phi_d = [blockdiag(Pa) | Pc] by bars into f. */
static int factor(const double *Pa, const double *Pc, std_factor *f)
{
    int k, j, r;
    for (k = 0; k < 6; k++) {
        const double *P = Pa + 6 * k;   /* P[2r+s] */
        double *n = f->n[k], a, b, c, det, ia;
        n[0] = P[2] * P[5] - P[4] * P[3];
        n[1] = P[4] * P[1] - P[0] * P[5];
        n[2] = P[0] * P[3] - P[2] * P[1];
        a = P[0] * P[0] + P[2] * P[2] + P[4] * P[4];
        b = P[0] * P[1] + P[2] * P[3] + P[4] * P[5];
        c = P[1] * P[1] + P[3] * P[3] + P[5] * P[5];
        det = a * c - b * b;
        if (!(det > 1e-12 * a * c))
            return HG_ERR_SINGULAR_JACOBIAN;
        ia = 1.0 / det;
        for (r = 0; r < 3; r++) {       /* rows of (P^T P)^-1 P^T */
            f->G[k][r] = (c * P[2 * r] - b * P[2 * r + 1]) * ia;
            f->G[k][3 + r] = (a * P[2 * r + 1] - b * P[2 * r]) * ia;
        }
        for (j = 0; j < 6; j++)
            f->S[6 * k + j] = n[0] * Pc[(3 * k) * 6 + j] + n[1] * Pc[(3 * k + 1) * 6 + j] +
                              n[2] * Pc[(3 * k + 2) * 6 + j];
    }
    f->Pc = Pc;
    return hg_lu6_factor(f->S, f->piv);
}

/* X = Phi_d^-1 [Phi_z | v] (18 x 7, row-major; rows a(12) then c(6)):
 * Phi_z's column j is the unit load on bar j's z row. */
static void solve7(const std_factor *f, const double v[18], double X[18 * 7])
{
    double xc[6 * 7];
    int k, j, r, s;
    for (k = 0; k < 6; k++) {          /* xc = S^-1 (n_k . Y_k) */
        for (j = 0; j < 6; j++)
            xc[7 * k + j] = (j == k) ? f->n[k][2] : 0.0;
        xc[7 * k + 6] = f->n[k][0] * v[3 * k] + f->n[k][1] * v[3 * k + 1] +
                        f->n[k][2] * v[3 * k + 2];
    }
    hg_lu6_solve(f->S, f->piv, 7, xc);
    for (k = 0; k < 6; k++) {          /* bar k: x_a = G_k (Y_k - C_k xc) */
        double t[3][7];
        for (r = 0; r < 3; r++) {
            const double *row = f->Pc + (3 * k + r) * 6;
            for (s = 0; s < 7; s++) {
                double y = (s == 6) ? v[3 * k + r] : (r == 2 && s == k ? 1.0 : 0.0);
                for (j = 0; j < 6; j++)
                    y -= row[j] * xc[7 * j + s];
                t[r][s] = y;
            }
        }
        for (s = 0; s < 7; s++) {
            X[(2 * k) * 7 + s] = f->G[k][0] * t[0][s] + f->G[k][1] * t[1][s] + f->G[k][2] * t[2][s];
            X[(2 * k + 1) * 7 + s] = f->G[k][3] * t[0][s] + f->G[k][4] * t[1][s] + f->G[k][5] * t[2][s];
        }
    }
    for (k = 0; k < 6; k++)
        for (s = 0; s < 7; s++)
            X[(12 + k) * 7 + s] = xc[7 * k + s];
}

/* Scratch laid over d->work.step. */
typedef struct {
    double mzz[6], Mza[12], Maa[24], Mcc[36], Q[24], Pa[36], Pc[108], gm[18];
    double A[18 * 6], b[18], T1[6 * 18], Mh[36], inv_d[6], rhs[6], phi[18], X[18 * 7];
    std_factor f;
} standard_ws;
typedef char hg_standard_ws_fits[sizeof(standard_ws) <= sizeof(((hg_work *)0)->step) ? 1 : -1];

int hg_standard_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                      const double fz[6], double *qdd)
{
    standard_ws *w = (standard_ws *)d->work.step;
    double *A = w->A, *b = w->b, *T1 = w->T1;
    int i, j, k, r, s, rc;
    hg_gen_standard_terms(m->k, q, qd, w->mzz, w->Mza, w->Maa, w->Mcc, w->Q, w->Pa, w->Pc, w->gm);
    if ((rc = factor(w->Pa, w->Pc, &w->f)))
        return rc;
    solve7(&w->f, w->gm, w->X);
    for (r = 0; r < 18; r++) {         /* A = -X(:, 0:6), b = -X(:, 6) */
        for (j = 0; j < 6; j++)
            A[r * 6 + j] = -w->X[r * 7 + j];
        b[r] = -w->X[r * 7 + 6];
    }
    for (i = 0; i < 6; i++) {          /* T1 = M_zd + A^T M_dd, M_dd block diagonal */
        for (k = 0; k < 6; k++)
            for (s = 0; s < 2; s++)
                T1[i * 18 + 2 * k + s] = (k == i ? w->Mza[2 * k + s] : 0.0) +
                                         A[(2 * k) * 6 + i] * w->Maa[4 * k + s] +
                                         A[(2 * k + 1) * 6 + i] * w->Maa[4 * k + 2 + s];
        for (j = 0; j < 6; j++) {
            double v = 0.0;
            for (r = 0; r < 6; r++)
                v += A[(12 + r) * 6 + i] * w->Mcc[6 * r + j];
            T1[i * 18 + 12 + j] = v;
        }
    }
    for (i = 0; i < 6; i++) {
        double acc = w->Q[i] + fz[i];
        for (r = 0; r < 18; r++)
            acc += A[r * 6 + i] * w->Q[6 + r] - T1[i * 18 + r] * b[r];
        w->rhs[i] = acc;
        for (j = 0; j <= i; j++) {     /* M_zz + T1 A + (M_zd A)^T */
            double v = (i == j ? w->mzz[i] : 0.0) + w->Mza[2 * j] * A[(2 * j) * 6 + i] +
                       w->Mza[2 * j + 1] * A[(2 * j + 1) * 6 + i];
            for (r = 0; r < 18; r++)
                v += T1[i * 18 + r] * A[r * 6 + j];
            w->Mh[6 * i + j] = v;
        }
    }
    if ((rc = hg_spd6_factor(w->Mh, w->inv_d)))
        return rc;
    hg_spd6_apply(w->Mh, w->inv_d, w->rhs);
    if (d->work.mass.want)             /* the step's start: friction's mass data, T = I */
        hg_mass_save_reduced(&d->work.mass, w->Mh, w->inv_d, 0);
    for (i = 0; i < 6; i++)
        qdd[i] = w->rhs[i];
    for (r = 0; r < 18; r++) {         /* d'' = A z'' + b */
        double v = b[r];
        for (j = 0; j < 6; j++)
            v += A[r * 6 + j] * w->rhs[j];
        qdd[6 + r] = v;
    }
    return 0;
}

int hg_standard_stabilize(const hg_model *m, hg_data *d, double *q1, double *qd1,
                          double *residual_m)
{
    standard_ws *w = (standard_ws *)d->work.step;
    int rc;
    /* Jacobians at the predicted state: one NR iteration, d' = A z' */
    hg_gen_standard_constraints(m->k, q1, w->phi, w->Pa, w->Pc);
    if ((rc = factor(w->Pa, w->Pc, &w->f)))
        return rc;
    solve7(&w->f, w->phi, w->X);
    hg_stabilize_dependent(18, w->X, q1, qd1);
    *residual_m = hg_bar_length_error(&m->p.geo, q1, q1 + 18);
    return 0;
}

const hg_dae hg_standard_dae = {HG_NQ_STANDARD, 0, 6, hg_standard_accel, hg_hold_independent,
                                hg_standard_stabilize};
