/* hg_step_cartesian.c - the Reduced Cartesian parametrization
 * (head pose c independent, carriage heights z dependent): Phi_z is
 * diagonal, so A = -Phi_z^-1 Phi_c comes generated (one reciprocal per
 * carriage, hg_gen_cartesian_terms) and the position
 * stabilization is one diagonal Newton step per carriage. The fused
 * variant is the whole improved-Euler step as one generated function. */
#include "hg_step_cartesian.h"
#include "hg_system.h"
#include "hg_spd6.h"
#include "hg_errors.h"
#include "hg_unroll.h"

#include "hg_gen_reduced.h"

/* One Newton step z -= phi / Phi_z at the predicted state, then
 * z' = A c' = -Phi_z^-1 (Phi_c c'). Phi is exactly quadratic in z_k
 * (d^2 Phi_k / dz_k^2 = 2), so the bar's residual after the step is
 * delta^2 (m^2): the bar-length error delta^2 / (2 l) needs no new
 * evaluation: *residual_m is that error (m). */
int hg_cartesian_stabilize(const hg_model *m, hg_data *d, double *q1, double *qd1,
                           double *residual_m)
{
    double phi[6], pz[6], vc[6], worst = 0.0, *sc1 = d->work.sc1;
    const double r2l = 1.0 / (2.0 * m->p.geo.l_m);
    int k;
    hg_head_trig(q1 + 6, sc1);
    hg_gen_reduced_stabilize(m->k, q1, qd1, sc1, phi, pz, vc);
    HG_UNROLL
    for (k = 0; k < 6; k++) {
        double ipz = 1.0 / pz[k], delta = phi[k] * ipz, e;
        q1[k] -= delta;
        qd1[k] = -vc[k] * ipz;
        e = delta * delta * r2l;
        if (!(e <= worst))
            worst = e;
    }
    *residual_m = worst;
    return 0;
}

/* Scratch laid over d->work.step: the generated terms (the algebra's
 * temporaries stay on the stack, where the compiler knows they alias
 * nothing: 1.3 KB). */
typedef struct {
    double mzz[6], Mzc[36], Mcc[36], Q[12], A[36], b[6], sc[6];
} cartesian_ws;
typedef char hg_cartesian_ws_fits[sizeof(cartesian_ws) <= sizeof(((hg_work *)0)->step) ? 1 : -1];

/* sin/cos of q's head angles: d's cache when it holds them, else computed into buf. */
static const double *head_trig(const hg_data *d, const double *q, double buf[6])
{
    if (d->trig_valid && d->trig_key_rad[0] == q[9] && d->trig_key_rad[1] == q[10] &&
        d->trig_key_rad[2] == q[11])
        return d->trig_sc;
    hg_head_trig(q + 6, buf);
    return buf;
}

int hg_cartesian_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                       const double fz[6], double *qdd)
{
    cartesian_ws *w = (cartesian_ws *)d->work.step;
    const double *mzz = w->mzz, *Mzc = w->Mzc, *Mcc = w->Mcc, *Q = w->Q, *A = w->A, *b = w->b;
    double W[36], P[36], Mh[36], rhs[6];
    const double *sc = head_trig(d, q, w->sc); /* the last stabilization's, if q is its state */
    int i, j, k, rc;
    /* A = -Phi_z^-1 Phi_c and b = -Phi_z^-1 gamma come generated */
    hg_gen_cartesian_terms(m->k, q, qd, sc, w->mzz, w->Mzc, w->Mcc, w->Q, w->A, w->b);
    /* Eq. 13 with z dependent, as sums of outer products over the carriages
     * (rows of A): with W_k = M_zc,k + M_zz,k A_k / 2 and P = A^T W,
     *   M_cc + M_cz A + (M_cz A)^T + A^T M_zz A = M_cc + P + P^T,
     *   Q_c + A^T Q_z - (M_cz + A^T M_zz) b = Q_c + A^T (Q_z - M_zz b) - M_cz b. */
    HG_UNROLL
    for (i = 0; i < 6; i++)
        rhs[i] = Q[6 + i];
    HG_UNROLL
    for (k = 0; k < 6; k++) {
        const double hm = 0.5 * mzz[k];
        double t;
        HG_UNROLL
        for (j = 0; j < 6; j++)
            W[6 * k + j] = Mzc[6 * k + j] + hm * A[6 * k + j];
        t = Q[k] + fz[k] - mzz[k] * b[k];
        HG_UNROLL
        for (i = 0; i < 6; i++)
            rhs[i] += A[6 * k + i] * t - Mzc[6 * k + i] * b[k];
    }
    /* P[i][j] = sum over k (in k order) of A[k][i] W[k][j], one row at a time */
    HG_UNROLL
    for (i = 0; i < 6; i++) {
        double pr[6];
        HG_UNROLL
        for (j = 0; j < 6; j++)
            pr[j] = A[i] * W[j];
        HG_UNROLL
        for (k = 1; k < 6; k++)
            HG_UNROLL
            for (j = 0; j < 6; j++)
                pr[j] += A[6 * k + i] * W[6 * k + j];
        HG_UNROLL
        for (j = 0; j < 6; j++)
            P[6 * i + j] = pr[j];
    }
    HG_UNROLL
    for (i = 0; i < 6; i++)
        HG_UNROLL
        for (j = 0; j <= i; j++)
            Mh[6 * i + j] = Mcc[6 * i + j] + P[6 * i + j] + P[6 * j + i];
    rc = hg_spd6_solve(Mh, rhs);
    if (rc)
        return rc;
    HG_UNROLL
    for (k = 0; k < 6; k++) {          /* z'' = A c'' + b */
        double v = b[k];
        HG_UNROLL
        for (j = 0; j < 6; j++)
            v += A[6 * k + j] * rhs[j];
        qdd[k] = v;
        qdd[6 + k] = rhs[k];
    }
    return 0;
}

const hg_dae hg_cartesian_dae = {HG_NQ_REDUCED, hg_cartesian_accel, hg_cartesian_stabilize};

int hg_fused_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                   const double fz[6], double *qdd)
{
    double buf[6];
    return hg_gen_fused_accel(m->k, q, qd, head_trig(d, q, buf), fz, qdd);
}

const hg_dae hg_fused_dae = {HG_NQ_REDUCED, hg_fused_accel, hg_cartesian_stabilize};

int hg_fused_step(const hg_model *m, hg_data *d, const double *q0, const double *qd0,
                  const double sc0[6], const double fz[6], double dt, double *q1,
                  double *qd1, double *qdd, double *residual_m)
{
    return hg_gen_fused_step(m->k, q0, qd0, sc0, fz, dt, q1, qd1, qdd, d->work.sc1, residual_m);
}
