/* hg_step_joints.c - one step of the z-independent parametrizations
 * (Standard, Reduced Joints): the paper's Eq. 13 reduced to z'', improved
 * Euler on the full state, one Newton-Raphson position iteration on the
 * dependent coordinates and the velocity projection d' = A z'. */
#include <string.h>
#include "hg_step.h"
#include "hg_linalg.h"
#include "hg_spd6.h"
#include "hg_lu6.h"
#include "hg_errors.h"

void hg_improved_euler(int n, const double *q0, const double *qd0, const double *qdd,
                       double dt, double *q1, double *qd1)
{
    int i;
    double h2 = 0.5 * dt * dt;
    for (i = 0; i < n; i++) {
        q1[i] = q0[i] + qd0[i] * dt + qdd[i] * h2;
        qd1[i] = qd0[i] + qdd[i] * dt;
    }
}

/* LU of Phi_d (nd x nd): the unrolled 6x6 one for the reduced model. */
static int factor(int nd, double *Phi_d, int *piv)
{
    return nd == 6 ? hg_lu6_factor(Phi_d, piv) : hg_lu_factor(nd, Phi_d, piv);
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

/* X = Phi_d^-1 [Phi_z | v] (nd x 7) from a factored Phi_d. */
static void solve_a_b(int nd, const double *lu, const int *piv, const double *Phi_z,
                      const double *v, double *X)
{
    int r, j;
    for (r = 0; r < nd; r++) {
        for (j = 0; j < 6; j++)
            X[r * 7 + j] = Phi_z[r * 6 + j];
        X[r * 7 + 6] = v[r];
    }
    if (nd == 6)
        hg_lu6_solve(lu, piv, 7, X);
    else
        hg_lu_solve(nd, lu, piv, 7, X);
}

/* z'' from Eq. 13: (M_zz + M_zd A + (M_zd A)^T + A^T M_dd A) z''
 *   = Q_z + A^T Q_d - (M_zd + A^T M_dd) b,  A = -X[:, :6], b = -X[:, 6]. */
static inline __attribute__((always_inline)) int
reduced_accelerations(const int nd, const hg_system *s, const double *X, const double fz[6],
                      double *qdd)
{
    int i, j, r, t, rc;
    double T1[6 * 18], Mh[36], rhs[6];
    for (i = 0; i < 6; i++)            /* T1 = M_zd + A^T M_dd (6 x nd) */
        for (r = 0; r < nd; r++) {
            double acc = s->Mzd[i * nd + r];
            for (t = 0; t < nd; t++)
                acc -= X[t * 7 + i] * s->Mdd[t * nd + r];
            T1[i * nd + r] = acc;
        }
    for (i = 0; i < 6; i++) {
        double acc = s->Q[i] + fz[i];
        for (r = 0; r < nd; r++)
            acc += -X[r * 7 + i] * s->Q[6 + r] + T1[i * nd + r] * X[r * 7 + 6];
        rhs[i] = acc;
        for (j = 0; j <= i; j++) {     /* T1 A + (M_zd A)^T, lower triangle */
            double v = (i == j) ? s->mzz[i] : 0.0;
            for (r = 0; r < nd; r++)
                v -= T1[i * nd + r] * X[r * 7 + j] + s->Mzd[j * nd + r] * X[r * 7 + i];
            Mh[i * 6 + j] = v;
        }
    }
    rc = hg_spd6_solve(Mh, rhs);
    if (rc)
        return rc;
    for (i = 0; i < 6; i++)
        qdd[i] = rhs[i];
    for (r = 0; r < nd; r++) {         /* d'' = A z'' + b */
        double acc = -X[r * 7 + 6];
        for (j = 0; j < 6; j++)
            acc -= X[r * 7 + j] * rhs[j];
        qdd[6 + r] = acc;
    }
    return 0;
}

int hg_step_joints(const hg_model *m, const double *q0, const double *qd0,
                   const double fz[6], double dt, double *q1, double *qd1, double *qdd,
                   double *residual_m)
{
    hg_system s;
    double X[18 * 7], phi[18];
    int piv[18], rc, nd, n;
    hg_system_terms(m, q0, qd0, &s);
    nd = s.nd;
    n = 6 + nd;
    rc = factor(nd, s.Phi_d, piv);
    if (rc)
        return rc;
    solve_a_b(nd, s.Phi_d, piv, s.Phi_z, s.gamma, X);
    /* nd as a constant lets the compiler unroll the 6-coordinate case */
    rc = nd == 6 ? reduced_accelerations(6, &s, X, fz, qdd) : reduced_accelerations(18, &s, X, fz, qdd);
    if (rc)
        return rc;
    hg_improved_euler(n, q0, qd0, qdd, dt, q1, qd1);
    /* stabilization: Jacobians at the predicted state, one NR iteration,
     * then d' = A z' */
    hg_system_constraints(m, q1, phi, s.Phi_d, s.Phi_z);
    rc = factor(nd, s.Phi_d, piv);
    if (rc)
        return rc;
    solve_a_b(nd, s.Phi_d, piv, s.Phi_z, phi, X);
    hg_stabilize_dependent(nd, X, q1, qd1);
    *residual_m = hg_bar_length_error(&m->p.geo, q1, q1 + n - 6);
    return 0;
}
