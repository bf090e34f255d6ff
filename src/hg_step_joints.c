/* hg_step_joints.c - the Reduced Joints parametrization (z independent):
 * the paper's Eq. 13 reduced to z'' with A = -Phi_c^-1 Phi_z (Phi_z
 * diagonal), one Newton-Raphson position iteration on the head pose and
 * the velocity projection c' = A z'. */
#include "hg_step_joints.h"
#include "hg_system.h"
#include "hg_kinematics.h"
#include "hg_spd6.h"
#include "hg_lu6.h"
#include "hg_compiler.h"
#include "hg_gen_reduced.h"

/* Scratch laid over d->work.step. */
typedef struct {
    double mzz[6], Mzc[36], Mcc[36], Q[12], pz[6], pc[36], gm[6], sc[6];
    double X[6 * 7], phi[6];
    int piv[6];
} joints_ws;
typedef char hg_joints_ws_fits[sizeof(joints_ws) <= sizeof(((hg_work *)0)->step) ? 1 : -1];

/* X = Phi_c^-1 [diag(pz) | v] (6 x 7) with Phi_c (w->pc) factored in place. */
static int solve_a_b(joints_ws *w, const double *v)
{
    int r, j, rc = hg_lu6_factor(w->pc, w->piv);
    if (rc)
        return rc;
    HG_UNROLL
    for (r = 0; r < 6; r++) {
        HG_UNROLL
        for (j = 0; j < 6; j++)
            w->X[r * 7 + j] = r == j ? w->pz[r] : 0.0;
        w->X[r * 7 + 6] = v[r];
    }
    hg_lu6_solve(w->pc, w->piv, 7, w->X);
    return 0;
}

int hg_joints_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                    const double fz[6], double *qdd)
{
    joints_ws *w = (joints_ws *)d->work.step;
    const double *X = w->X;
    double T1[36], Mh[36], rhs[6], inv_d[6]; /* on the stack: they alias nothing */
    int i, j, r, t, rc;
    hg_head_trig(q + 6, w->sc);
    hg_gen_reduced_terms(m->k, q, qd, w->sc, w->mzz, w->Mzc, w->Mcc, w->Q, w->pz, w->pc, w->gm);
    if ((rc = solve_a_b(w, w->gm)))
        return rc;
    /* (M_zz + M_zc A + (M_zc A)^T + A^T M_cc A) z'' = Q_z + A^T Q_c - (M_zc + A^T M_cc) b,
     * A = -X[:, :6], b = -X[:, 6] */
    for (i = 0; i < 6; i++)            /* T1 = M_zc + A^T M_cc */
            for (r = 0; r < 6; r++) {
            double acc = w->Mzc[i * 6 + r];
                    for (t = 0; t < 6; t++)
                acc -= X[t * 7 + i] * w->Mcc[t * 6 + r];
            T1[i * 6 + r] = acc;
        }
    for (i = 0; i < 6; i++) {
        double acc = w->Q[i] + fz[i];
            for (r = 0; r < 6; r++)
            acc += -X[r * 7 + i] * w->Q[6 + r] + T1[i * 6 + r] * X[r * 7 + 6];
        rhs[i] = acc;
        for (j = 0; j <= i; j++) {     /* T1 A + (M_zc A)^T, lower triangle */
            double v = (i == j) ? w->mzz[i] : 0.0;
                    for (r = 0; r < 6; r++)
                v -= T1[i * 6 + r] * X[r * 7 + j] + w->Mzc[j * 6 + r] * X[r * 7 + i];
            Mh[i * 6 + j] = v;
        }
    }
    if ((rc = hg_spd6_factor(Mh, inv_d)))
        return rc;
    hg_spd6_apply(Mh, inv_d, rhs);
    if (d->work.mass.want)             /* the step's start: friction's mass data, T = I */
        hg_mass_save_reduced(&d->work.mass, Mh, inv_d, 0);
    for (r = 0; r < 6; r++) {          /* c'' = A z'' + b */
        double acc = -X[r * 7 + 6];
            for (j = 0; j < 6; j++)
            acc -= X[r * 7 + j] * rhs[j];
        qdd[r] = rhs[r];
        qdd[6 + r] = acc;
    }
    return 0;
}

int hg_joints_stabilize(const hg_model *m, hg_data *d, double *q1, double *qd1,
                        double *residual_m)
{
    joints_ws *w = (joints_ws *)d->work.step;
    int rc;
    hg_head_trig(q1 + 6, w->sc);
    hg_gen_reduced_constraints(m->k, q1, w->sc, w->phi, w->pz, w->pc);
    if ((rc = solve_a_b(w, w->phi)))
        return rc;
    hg_stabilize_dependent(6, w->X, q1, qd1);
    *residual_m = hg_bar_length_error(&m->p.geo, q1, q1 + 6);
    return 0;
}

const hg_dae hg_joints_dae = {HG_NQ_REDUCED, 0, 6, hg_joints_accel, hg_hold_independent,
                              hg_joints_stabilize};
