/* hg_step_cartesian.c - the Reduced Cartesian parametrization
 * (head pose c independent, carriage heights z dependent): Phi_z is
 * diagonal, so A = -Phi_z^-1 Phi_c comes generated (one reciprocal per
 * carriage, hg_gen_cartesian_terms) and the position
 * stabilization is one diagonal Newton step per carriage. The fused
 * variant is the whole improved-Euler step as one generated function. */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_step_cartesian.h"
#include "hg_system.h"
#include "hg_spd6.h"
#include "hg_errors.h"
#include "hg_compiler.h"

#include "hg_linalg.h"
#include "hg_gen_reduced.h"

#define HOLD_NEWTON_ITER 3   /* Newton steps that put the held carriages back (each squares the error) */
#define HOLD_SIX_AT_ONCE 4   /* held carriages from which one six-column mass solve costs less than one per column */

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
    if (!(d->work.sc1_valid &&
          memcmp(d->work.sc1_key, q1 + 9, sizeof d->work.sc1_key) == 0)) // NOLINT(bugprone-suspicious-memory-comparison): bitwise on purpose, the same bits give the same sin/cos
        hg_head_trig(q1 + 6, sc1);     /* else the hold's last ones are these angles' (same bits) */
    d->work.sc1_valid = 0;
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

/* Eq. 13 with z dependent: the reduced mass matrix Mh (lower triangle)
 * and right-hand side rhs at (q, qd) with carriage forces fz; A and b in
 * d->work.step. */
static void cartesian_system(const hg_model *m, hg_data *d, const double *q, const double *qd,
                             const double fz[6], double Mh[36], double rhs[6])
{
    cartesian_ws *w = (cartesian_ws *)d->work.step;
    const double *mzz = w->mzz, *Mzc = w->Mzc, *Mcc = w->Mcc, *Q = w->Q, *A = w->A, *b = w->b;
    double W[36], P[36];
    hg_v2 r[3];
    const double *sc = head_trig(d, q, w->sc); /* the last stabilization's, if q is its state */
    int i, j, k;
    /* A = -Phi_z^-1 Phi_c and b = -Phi_z^-1 gamma come generated */
    hg_gen_cartesian_terms(m->k, q, qd, sc, w->mzz, w->Mzc, w->Mcc, w->Q, w->A, w->b);
    /* Eq. 13 with z dependent, as sums of outer products over the carriages
     * (rows of A): with W_k = M_zc,k + M_zz,k A_k / 2 and P = A^T W,
     *   M_cc + M_cz A + (M_cz A)^T + A^T M_zz A = M_cc + P + P^T,
     *   Q_c + A^T Q_z - (M_cz + A^T M_zz) b = Q_c + A^T (Q_z - M_zz b) - M_cz b. */
    /* two columns at a time (hg_v2: each entry's operations in the scalar order) */
    HG_UNROLL
    for (j = 0; j < 6; j += 2)
        r[j / 2] = hg_v2_load(Q + 6 + j);
    HG_UNROLL
    for (k = 0; k < 6; k++) {
        const hg_v2 hm = hg_v2_dup(0.5 * mzz[k]), bk = hg_v2_dup(b[k]);
        const hg_v2 t = hg_v2_dup(Q[k] + fz[k] - mzz[k] * b[k]);
        HG_UNROLL
        for (j = 0; j < 6; j += 2) {
            const hg_v2 a = hg_v2_load(A + 6 * k + j), mzc = hg_v2_load(Mzc + 6 * k + j);
            hg_v2_store(W + 6 * k + j, hg_v2_add(mzc, hg_v2_mul(hm, a)));
            r[j / 2] = hg_v2_add(r[j / 2], hg_v2_sub(hg_v2_mul(a, t), hg_v2_mul(mzc, bk)));
        }
    }
    HG_UNROLL
    for (j = 0; j < 6; j += 2)
        hg_v2_store(rhs + j, r[j / 2]);
    /* P[i][j] = sum over k (in k order) of A[k][i] W[k][j], one row at a time */
    HG_UNROLL
    for (i = 0; i < 6; i++) {
        hg_v2 pr[3];
        HG_UNROLL
        for (j = 0; j < 3; j++)
            pr[j] = hg_v2_mul(hg_v2_dup(A[i]), hg_v2_load(W + 2 * j));
        HG_UNROLL
        for (k = 1; k < 6; k++)
            HG_UNROLL
            for (j = 0; j < 3; j++)
                pr[j] = hg_v2_add(pr[j], hg_v2_mul(hg_v2_dup(A[6 * k + i]), hg_v2_load(W + 6 * k + 2 * j)));
        HG_UNROLL
        for (j = 0; j < 3; j++)
            hg_v2_store(P + 6 * i + 2 * j, pr[j]);
    }
    HG_UNROLL
    for (i = 0; i < 6; i++)
        HG_UNROLL
        for (j = 0; j <= i; j++)
            // cppcheck-suppress uninitvar ; P is written above through hg_v2_store (memcpy)
            Mh[6 * i + j] = Mcc[6 * i + j] + P[6 * i + j] + P[6 * j + i];
}

int hg_cartesian_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                       const double fz[6], double *qdd)
{
    cartesian_ws *w = (cartesian_ws *)d->work.step;
    hg_mass_snapshot *s = &d->work.mass;
    double own[36], rhs[6], own_d[6];
    double *Mh = s->want ? s->ldl : own, *inv_d = s->want ? s->inv_d : own_d; /* friction's: in place */
    int j, k, rc;
    cartesian_system(m, d, q, qd, fz, Mh, rhs);
    rc = hg_spd6_factor(Mh, inv_d);
    if (rc)
        return rc;
    hg_spd6_apply(Mh, inv_d, rhs);
    if (s->want)                      /* the step's start: friction's mass data, z' = A c' */
        hg_mass_save_reduced(s, Mh, inv_d, w->A);
    HG_UNROLL
    for (k = 0; k < 6; k++) {          /* z'' = A c'' + b */
        double v = w->b[k];
        HG_UNROLL
        for (j = 0; j < 6; j++)
            v += w->A[6 * k + j] * rhs[j];
        qdd[k] = v;
        qdd[6 + k] = rhs[k];
    }
    return 0;
}

/* Y's first n columns = Mh^-1 (rows idx[0..n) of pc)^T: six at a time
 * (hg_spd6_apply6, columns past n 0 and unused) from HOLD_SIX_AT_ONCE held, else
 * one by one; each column hg_spd6_apply's bits either way. */
static void hold_response(const hg_mass_snapshot *s, const double pc[36], const int idx[6], int n, double Y[36])
{
    int i, j;
    if (n >= HOLD_SIX_AT_ONCE) {
        for (i = 0; i < 6; i++)
            HG_UNROLL
            for (j = 0; j < 6; j++)
                Y[6 * j + i] = i < n ? pc[6 * idx[i] + j] : 0.0;
        hg_spd6_apply6(s->ldl, s->inv_d, Y);
        return;
    }
    for (i = 0; i < n; i++) {
        double y[6];
        for (j = 0; j < 6; j++)
            y[j] = pc[6 * idx[i] + j];
        hg_spd6_apply(s->ldl, s->inv_d, y);
        for (j = 0; j < 6; j++)
            Y[6 * j + i] = y[j];
    }
}

void hg_cartesian_hold(const hg_model *m, hg_data *d, const double z0[6], unsigned held,
                       double *q1, double *qd1)
{
    const hg_mass_snapshot *s = &d->work.mass;
    double sc[6], phi[6], pz[6], pc[36], Y[36], G[36], r[6];
    int idx[6], piv[6], n = 0, it, i, j, k;
    for (k = 0; k < 6; k++)
        if ((held >> k) & 1u) {
            q1[k] = z0[k];
            idx[n++] = k;
        }
    if (n == 0 || s->kind != 1)
        return;
    /* c such that the held bars close with their carriages at z0 (minimum
     * Mh-norm Newton steps), then c' with no speed along those carriages */
    for (it = 0; it <= HOLD_NEWTON_ITER; it++) {
        double worst = 0.0;
        hg_head_trig(q1 + 6, sc);
        memcpy(d->work.sc1, sc, sizeof sc);  /* the stabilization's, if these angles stay */
        memcpy(d->work.sc1_key, q1 + 9, sizeof d->work.sc1_key);
        d->work.sc1_valid = 1;
        hg_gen_reduced_constraints(m->k, q1, sc, phi, pz, pc);
        hold_response(s, pc, idx, n, Y);   /* Y = Mh^-1 J^T, G = J Y with J = Phi_c's held rows */
        for (i = 0; i < n; i++) {      /* libm's fmax(worst, |phi|), without its call */
            double v = fabs(phi[idx[i]]);
            worst = v > worst ? v : worst;
        }
        for (i = 0; i < n; i++) {
            const double *row = pc + 6 * idx[i];
            for (j = 0; j + 1 < n; j += 2) {  /* two columns at a time, each summed over k in order */
                hg_v2 v = hg_v2_dup(0.0);
                HG_UNROLL
                for (k = 0; k < 6; k++)
                    v = hg_v2_add(v, hg_v2_mul(hg_v2_dup(row[k]), hg_v2_load(Y + 6 * k + j)));
                hg_v2_store(G + n * i + j, v);
            }
            for (; j < n; j++) {
                double v = 0.0;
                for (k = 0; k < 6; k++)
                    v += row[k] * Y[6 * k + j];
                G[n * i + j] = v;
            }
        }
        if (hg_lu_factor(n, G, piv))
            return;                   /* dependent constraints: leave it to the stabilization */
        if (it == HOLD_NEWTON_ITER || worst == 0.0)
            break;
        for (i = 0; i < n; i++)
            r[i] = phi[idx[i]];
        hg_lu_solve(n, G, piv, 1, r);
        for (j = 0; j < 6; j++) {
            double v = 0.0;
            for (i = 0; i < n; i++)
                v += Y[6 * j + i] * r[i];
            q1[6 + j] -= v;
        }
    }
    for (i = 0; i < n; i++) {          /* J c' = 0 */
        double v = 0.0;
        for (j = 0; j < 6; j++)
            v += pc[6 * idx[i] + j] * qd1[6 + j];
        r[i] = v;
    }
    hg_lu_solve(n, G, piv, 1, r);
    for (j = 0; j < 6; j++) {
        double v = 0.0;
        for (i = 0; i < n; i++)
            v += Y[6 * j + i] * r[i];
        qd1[6 + j] -= v;
    }
}

const hg_dae hg_cartesian_dae = {HG_NQ_REDUCED, 6, 6, hg_cartesian_accel, hg_cartesian_hold,
                                 hg_cartesian_stabilize};

int hg_fused_accel(const hg_model *m, hg_data *d, const double *q, const double *qd,
                   const double fz[6], double *qdd)
{
    double buf[6];
    if (d->work.mass.want) {          /* friction's mass data: built as hg_cartesian_accel does */
        cartesian_ws *w = (cartesian_ws *)d->work.step;
        hg_mass_snapshot *s = &d->work.mass;
        double rhs[6];
        int rc;
        cartesian_system(m, d, q, qd, fz, s->ldl, rhs);
        rc = hg_spd6_factor(s->ldl, s->inv_d);
        if (rc)
            return rc;
        hg_mass_save_reduced(s, s->ldl, s->inv_d, w->A);
    }
    return hg_gen_fused_accel(m->k, q, qd, head_trig(d, q, buf), fz, qdd);
}

const hg_dae hg_fused_dae = {HG_NQ_REDUCED, 6, 6, hg_fused_accel, hg_cartesian_hold,
                             hg_cartesian_stabilize};

int hg_fused_step(const hg_model *m, hg_data *d, const double *q0, const double *qd0,
                  const double sc0[6], const double fz[6], double dt, double *q1,
                  double *qd1, double *qdd, double *residual_m)
{
    return hg_gen_fused_step(m->k, q0, qd0, sc0, fz, dt, q1, qd1, qdd, d->work.sc1, residual_m);
}
