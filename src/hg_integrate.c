/* hg_integrate.c - improved Euler, Heun and RK4 on the state of any
 * parametrization, then friction at the velocity level, then its
 * constraint stabilization. */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_integrate.h"
#include "hg_system.h"
#include "hg_forces.h"
#include "hg_friction.h"
#include "hg_spd6.h"
#include "hg_linalg.h"
#include "hg_errors.h"
#include "hg_compiler.h"

/* Stage vectors laid over hg_work.stage. */
typedef struct {
    double qs[HG_NQ_MAX], vs[HG_NQ_MAX]; /* stage state */
    double a[HG_NQ_MAX];                 /* stage accelerations */
    double sq[HG_NQ_MAX], sv[HG_NQ_MAX]; /* weighted sums of the stages' q' and q'' */
    double fz[6];                        /* stage carriage forces */
    double rs[6], rv[6], ra[6];          /* flexible trains: the rotors' stage state and accelerations */
    double rsq[6], rsv[6];               /* ... their weighted sums */
} stage_ws;
typedef char hg_stage_ws_fits[sizeof(stage_ws) <= sizeof(((hg_work *)0)->stage) ? 1 : -1];

/* The paper's step: q1 = q0 + q0' dt + q0'' dt^2/2, q1' = q0' + q0'' dt
 * (the five vectors must not overlap: restrict lets the compiler pack them). */
static HG_ALWAYS_INLINE void
improved_euler(const int n, const double *restrict q0, const double *restrict qd0,
               const double *restrict qdd, double dt, double *restrict q1, double *restrict qd1)
{
    const double h2 = 0.5 * dt * dt;
    int i;
    for (i = 0; i < n; i++) {
        q1[i] = q0[i] + qd0[i] * dt + qdd[i] * h2;
        qd1[i] = qd0[i] + qdd[i] * dt;
    }
}

/* A rotor's acceleration under its motor and the train's force f (N) on the carriage. */
static inline double rotor_acc(const hg_model *m, const hg_data *ctx, int k, double f)
{
    return (ctx->work.motor_n[k] - f) / m->rotor_mass_kg;
}

/* Flexible trains: each rotor's acceleration at its stage state and the
 * carriages' (z, z') of the stage, the train's force added to the
 * carriages' forces fz: (motor - train) / m_rotor. */
static void rotor_accel(const hg_model *m, const hg_data *ctx, const double *z, const double *zd,
                        stage_ws *w, double fz[6])
{
    int k;
    for (k = 0; k < 6; k++) {
        double f = hg_drivetrain_force(&m->train[k], w->rs[k] - z[k], w->rv[k] - zd[k]);
        fz[k] += f;
        w->ra[k] = rotor_acc(m, ctx, k, f);
    }
}

/* Accelerations at the stage state (qs, vs) of w, drive force held (and
 * the trains' at the stage's rotor state). */
static int stage_accel(const hg_model *m, const hg_dae *f, hg_data *ctx, stage_ws *w,
                       const double drive_n[6])
{
    hg_carriage_forces(m, w->qs, w->vs, drive_n, w->fz);
    if (m->flexible)
        rotor_accel(m, ctx, w->qs, w->vs, w, w->fz);
    return f->accel(m, ctx, w->qs, w->vs, w->fz, w->a);
}

/* The rotors at the step's start (stage 0): their acceleration from the
 * trains' force hg_step put into fz0 (ctx->work.train_n, at the rotors'
 * and carriages' start: q0, qd0 are the carriages' z, z'). */
static void rotor_start(const hg_model *m, const hg_data *ctx, stage_ws *w)
{
    int k;
    memcpy(w->rs, ctx->zr_m, sizeof w->rs);
    memcpy(w->rv, ctx->zrd_mps, sizeof w->rv);
    for (k = 0; k < 6; k++)
        w->ra[k] = rotor_acc(m, ctx, k, ctx->work.train_n[k]);
}

void hg_mass_save_reduced(hg_mass_snapshot *s, const double ldl[36], const double inv_d[6],
                          const double *T)
{
    int i, j;
    if (ldl != s->ldl)                /* else factored in place */
        for (i = 0; i < 6; i++)       /* the factors live in the lower triangle: the rest is stale */
            for (j = 0; j < 6; j++)
                s->ldl[6 * i + j] = j <= i ? ldl[6 * i + j] : 0.0;
    if (inv_d != s->inv_d)
        memcpy(s->inv_d, inv_d, sizeof s->inv_d);
    s->t_identity = T == 0;
    if (T)
        memcpy(s->T, T, sizeof s->T);
    s->kind = 1;
}

void hg_mass_save_kkt(hg_mass_snapshot *s, int n, const double *lu, const int *piv)
{
    if (n > HG_KKT_MAX)
        return;                       /* cannot happen: 12 + 5 intact bars */
    memcpy(s->kkt, lu, (unsigned long)(n * n) * sizeof(double));
    memcpy(s->piv, piv, (unsigned long)n * sizeof(int));
    s->nkkt = n;
    s->kind = 2;
}

void hg_hold_independent(const hg_model *m, hg_data *ctx, const double z0[6], unsigned held,
                         double *q1, double *qd1)
{
    int k;
    (void)m;
    (void)ctx;
    for (k = 0; k < 6; k++)
        if ((held >> k) & 1u) {
            q1[k] = z0[k];
            qd1[k] = 0.0;
        }
}

void hg_mass_response(const hg_mass_snapshot *s, const double p[6], double *dv, double dz[6])
{
    int i, j;
    if (s->kind == 1 && s->t_identity) {
        double g[6];
        memcpy(g, p, sizeof g);
        hg_spd6_apply(s->ldl, s->inv_d, g);
        memcpy(dv, g, sizeof g);
        memcpy(dz, g, sizeof g);
    } else if (s->kind == 1) {
        /* g = T^T p and dz = T g, each entry summed from 0 in j order, two
         * entries per vector (hg_v2: the scalar loops' bits) */
        hg_v2 t[3] = {hg_v2_dup(0.0), hg_v2_dup(0.0), hg_v2_dup(0.0)};
        double g[6];
        HG_UNROLL
        for (j = 0; j < 6; j++)
            HG_UNROLL
            for (i = 0; i < 3; i++)
                t[i] = hg_v2_add(t[i], hg_v2_mul(hg_v2_load(s->T + 6 * j + 2 * i), hg_v2_dup(p[j])));
        HG_UNROLL
        for (i = 0; i < 3; i++)
            hg_v2_store(g + 2 * i, t[i]);
        hg_spd6_apply(s->ldl, s->inv_d, g);
        memcpy(dv, g, sizeof g);
        HG_UNROLL
        for (i = 0; i < 3; i++) {
            hg_v2 v = hg_v2_dup(0.0);
            HG_UNROLL
            for (j = 0; j < 6; j++) {
                const hg_v2 rows = hg_v2_set(s->T[12 * i + j], s->T[12 * i + 6 + j]);
                v = hg_v2_add(v, hg_v2_mul(rows, hg_v2_dup(g[j])));
            }
            hg_v2_store(dz + 2 * i, v);
        }
    } else if (s->kind == 2) {
        double b[HG_KKT_MAX];
        for (i = 0; i < s->nkkt; i++)
            b[i] = i < 6 ? p[i] : 0.0;
        hg_lu_solve(s->nkkt, s->kkt, s->piv, 1, b);
        for (i = 0; i < HG_NQ_REDUCED; i++)
            dv[i] = b[i];
        for (i = 0; i < 6; i++)
            dz[i] = b[i];
    } else {
        for (i = 0; i < 6; i++)
            dv[i] = dz[i] = 0.0;
    }
}

void hg_mass_response_matrix(const hg_mass_snapshot *s, double W[36])
{
    double e[6] = {0, 0, 0, 0, 0, 0}, dv[HG_NQ_REDUCED], dz[6], X[36];
    int i, j, k;
    if (s->kind != 1 || (!s->t_identity && !hg_all_finite(36, s->T))) {
        for (k = 0; k < 6; k++) {         /* column k: the response to impulse k */
            e[k] = 1.0;
            hg_mass_response(s, e, dv, dz);
            for (i = 0; i < 6; i++)
                W[6 * i + k] = dz[i];
            e[k] = 0.0;
        }
        return;
    }
    /* hg_mass_response's T^T e_k, 0 + T[j][i] e_k[j] summed over j, is
     * T[k][i] + 0 for a finite T (the identity's: e_k itself) */
    for (i = 0; i < 6; i++)
        for (k = 0; k < 6; k++)
            X[6 * i + k] = s->t_identity ? (i == k ? 1.0 : 0.0) : s->T[6 * k + i] + 0.0;
    hg_spd6_apply6(s->ldl, s->inv_d, X);
    if (s->t_identity) {
        memcpy(W, X, sizeof X);
        return;
    }
    HG_UNROLL
    for (i = 0; i < 6; i++) {             /* W[i][k] = 0 + T[i][j] X[j][k] summed in j order */
        hg_v2 w[3] = {hg_v2_dup(0.0), hg_v2_dup(0.0), hg_v2_dup(0.0)};
        HG_UNROLL
        for (j = 0; j < 6; j++)
            HG_UNROLL
            for (k = 0; k < 3; k++)
                w[k] = hg_v2_add(w[k], hg_v2_mul(hg_v2_dup(s->T[6 * i + j]), hg_v2_load(X + 6 * j + 2 * k)));
        HG_UNROLL
        for (k = 0; k < 3; k++)
            hg_v2_store(W + 6 * i + 2 * k, w[k]);
    }
}

/* The step's friction impulses in general: W, the carriages' response to
 * unit impulses, from the saved mass matrix, the speeds without friction
 * (the stages held est), then the active-set solve. 0 or a code. */
static int friction_general(const hg_model *m, hg_data *ctx, const double *qd0, const double *qd1,
                            const double est[6], double dt, hg_friction_out *fo)
{
    double W[36], vfree[6];
    int i, k;
    hg_mass_response_matrix(&ctx->work.mass, W);
    for (k = 0; k < 6; k++) {             /* the speeds without any sliding or static friction */
        double v = qd1[k];
        for (i = 0; i < 6; i++)
            v -= W[6 * k + i] * est[i];
        vfree[k] = v;
    }
    return hg_friction_solve(m->fric, 6, W, vfree, qd0, ctx->stuck, dt, fo);
}

/* Sliding and static friction on the predicted (q1, qd1), whose stages
 * held the expected sliding friction ctx->work.fric_est_n: the step's
 * impulses (all sliding on the flat of the Stribeck curve without W, else
 * friction_general), their difference from the expected ones into the
 * independent velocities (positions by dt/2 of them: a constant force over
 * the step); every stuck carriage is held at rest where it stopped: where
 * it was for one stuck from the start, after a constant deceleration for
 * one that stopped within the step. 0 or a code. */
static int friction(const hg_model *m, const hg_dae *f, hg_data *ctx, const double *q0,
                    const double *qd0, double dt, double *q1, double *qd1, double *qdd)
{
    hg_work *wk = &ctx->work;
    double est[6], e[6], dv[HG_NQ_REDUCED], dz[6], zstop[6];
    hg_friction_out fo;
    int i, k, rc;
    for (k = 0; k < 6; k++)
        est[k] = wk->fric_est_n[k] * dt;  /* the impulses the stages held */
    if (!hg_friction_all_sliding(m->fric, 6, qd1, qd0, ctx->stuck, est, m->m_min_kg, dt, &fo)) {
        rc = friction_general(m, ctx, qd0, qd1, est, dt, &fo);
        if (rc)
            return rc;
    }
    for (k = 0; k < 6; k++)               /* the stages held fric_est_n: correct by the rest */
        e[k] = fo.impulse[k] - est[k];
    hg_mass_response(&wk->mass, e, dv, dz);
    for (i = 0; i < f->ni; i++) {
        qd1[f->io + i] += dv[i];
        q1[f->io + i] += 0.5 * dt * dv[i];
        qdd[f->io + i] += dv[i] / dt;
    }
    for (k = 0; k < 6; k++)               /* dependent carriages: a start for the stabilization */
        if (f->io != 0) {
            qd1[k] += dz[k];
            q1[k] += 0.5 * dt * dz[k];
            qdd[k] += dz[k] / dt;
        }
    memcpy(wk->fric_impulse, fo.impulse, sizeof wk->fric_impulse);
    wk->fric_stuck = fo.stuck;
    if (fo.stuck) {                       /* where the stuck carriages stay */
        for (k = 0; k < 6; k++)
            zstop[k] = q0[k] + ((ctx->stuck >> k) & 1u ? 0.0 : 0.5 * qd0[k] * fo.stop[k] * dt);
        f->hold(m, ctx, zstop, fo.stuck, q1, qd1);
    }
    return 0;
}

/* The explicit Runge-Kutta scheme of ns stages (c, b) whose stage i starts
 * from y0 + c_i dt k_(i-1), n known where it is inlined: 0 or the first
 * failing accel's code. */
static HG_ALWAYS_INLINE int
runge_kutta(const int n, int ns, const double *c, const double *b, const hg_model *m,
            const hg_dae *f, hg_data *ctx, stage_ws *w, const double *q0, const double *qd0,
            const double drive_n[6], const double fz0[6], double dt, double *q1, double *qd1,
            double *qdd)
{
    int i, s, rc;
    for (s = 0; s < ns; s++) {
        if (s == 0) {
            rc = f->accel(m, ctx, q0, qd0, fz0, w->a);
            ctx->work.mass.want = 0;
            for (i = 0; i < n; i++) {
                w->vs[i] = qd0[i];
                w->sq[i] = 0.0;
                w->sv[i] = 0.0;
            }
            if (m->flexible) {
                rotor_start(m, ctx, w);
                for (i = 0; i < 6; i++)
                    w->rsq[i] = w->rsv[i] = 0.0;
            }
        } else {
            const double h = c[s] * dt;
            double vprev;
            for (i = 0; i < n; i++) {  /* k_(s-1) = (vs, a) of the previous stage */
                vprev = w->vs[i];
                w->qs[i] = q0[i] + h * vprev;
                w->vs[i] = qd0[i] + h * w->a[i];
            }
            if (m->flexible)           /* the rotors' stage, the same way */
                for (i = 0; i < 6; i++) {
                    vprev = w->rv[i];
                    w->rs[i] = ctx->zr_m[i] + h * vprev;
                    w->rv[i] = ctx->zrd_mps[i] + h * w->ra[i];
                }
            rc = stage_accel(m, f, ctx, w, drive_n);
        }
        if (rc)
            return rc;
        for (i = 0; i < n; i++) {
            w->sq[i] += b[s] * w->vs[i];
            w->sv[i] += b[s] * w->a[i];
        }
        if (m->flexible)
            for (i = 0; i < 6; i++) {
                w->rsq[i] += b[s] * w->rv[i];
                w->rsv[i] += b[s] * w->ra[i];
            }
    }
    for (i = 0; i < n; i++) {
        q1[i] = q0[i] + dt * w->sq[i];
        qd1[i] = qd0[i] + dt * w->sv[i];
        qdd[i] = w->sv[i];
    }
    if (m->flexible)
        for (i = 0; i < 6; i++) {
            ctx->work.rotor1_m[i] = ctx->zr_m[i] + dt * w->rsq[i];
            ctx->work.rotor1_mps[i] = ctx->zrd_mps[i] + dt * w->rsv[i];
        }
    return 0;
}

int hg_integrate(const hg_model *m, hg_integrator scheme, const hg_dae *f, hg_data *ctx,
                 const double *q0, const double *qd0, const double drive_n[6],
                 const double fz0[6], double dt, double *q1, double *qd1, double *qdd,
                 double *residual_m)
{
    stage_ws *w = (stage_ws *)ctx->work.stage;
    const double *c, *b;
    const int fric = hg_friction_any(m->fric, 6);
    int n = f->n, ns, rc;
    ctx->work.mass.want = fric;
    ctx->work.mass.kind = 0;
    ctx->work.sc1_valid = 0;
    ctx->work.fric_stuck = 0;
    memset(ctx->work.fric_impulse, 0, sizeof ctx->work.fric_impulse);
    if (scheme == HG_INTEGRATOR_IMPROVED_EULER) {
        rc = f->accel(m, ctx, q0, qd0, fz0, qdd);
        ctx->work.mass.want = 0;
        if (rc)
            return rc;
        if (n == HG_NQ_REDUCED)        /* a constant length lets the compiler unroll */
            improved_euler(HG_NQ_REDUCED, q0, qd0, qdd, dt, q1, qd1);
        else
            improved_euler(n, q0, qd0, qdd, dt, q1, qd1);
        if (m->flexible) {             /* the rotors the same way */
            rotor_start(m, ctx, w);
            improved_euler(6, ctx->zr_m, ctx->zrd_mps, w->ra, dt, ctx->work.rotor1_m, ctx->work.rotor1_mps);
        }
    } else {
        ns = hg_scheme_tableau(scheme, &c, &b);
        if (ns == 0)
            return HG_ERR_BAD_PARAM;
        if (n == HG_NQ_REDUCED)        /* a constant length lets the compiler unroll */
            rc = runge_kutta(HG_NQ_REDUCED, ns, c, b, m, f, ctx, w, q0, qd0, drive_n, fz0, dt, q1,
                             qd1, qdd);
        else
            rc = runge_kutta(n, ns, c, b, m, f, ctx, w, q0, qd0, drive_n, fz0, dt, q1, qd1, qdd);
        if (rc)
            return rc;
    }
    if (fric) {
        rc = friction(m, f, ctx, q0, qd0, dt, q1, qd1, qdd);
        if (rc)
            return rc;
    }
    return f->stabilize(m, ctx, q1, qd1, residual_m);
}
