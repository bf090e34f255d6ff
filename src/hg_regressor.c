/* hg_regressor.c - drive forces linear in the parameters (hg_regressor.h). */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_regressor.h"
#include "hg_dynamics.h"
#include "hg_gen_reduced.h"
#include "hg_linalg.h"
#include "hg_errors.h"
#include "hg_friction.h"
#include "hg_integrate.h"

unsigned long hg_regressor_sizeof(void)
{
    return sizeof(hg_regressor);
}

int hg_regressor_init(hg_regressor *r, const hg_params *p, const char **bad_field, const char **why)
{
    hg_params q = *p;
    int rc;
    memset(r, 0, sizeof *r);
    rc = hg_model_init(&r->model, &q, HG_MODEL_REDUCED_CARTESIAN, bad_field, why);
    if (rc)
        return rc;
    hg_gen_regressor_init(p, r->k);
    return 0;
}

/* ---- the drive and friction columns: the only place they are written ---- */
static const char *const fric_name[HG_REG_NFRIC] = {"f_offset", "c_visc", "f_coulomb", "f_breakaway"};
static const char *const fric_unit[HG_REG_NFRIC] = {"N", "N s/m", "N", "N"};

const char *hg_regressor_column(int j, const char **unit, int *carriage)
{
    if (j < 0 || j >= HG_REG_NCOL)
        return 0;
    if (j < HG_REG_NIN) {
        if (unit)
            *unit = hg_gen_regressor_units[j];
        if (carriage)
            *carriage = -1;
        return hg_gen_regressor_names[j];
    }
    j -= HG_REG_NIN;
    if (unit)
        *unit = fric_unit[j / 6];
    if (carriage)
        *carriage = j % 6;
    return fric_name[j / 6];
}

void hg_regressor_friction(const hg_regressor *r, const double zd[6], double cols[6][HG_REG_NFRIC])
{
    int k;
    for (k = 0; k < 6; k++) {
        double v = zd[k], shape = (v > 0) - (v < 0);   /* sliding friction opposes the motion */
        cols[k][HG_REG_F_OFFSET] = 1.0;
        cols[k][HG_REG_F_VISCOUS] = v;
        cols[k][HG_REG_F_COULOMB] = shape;
        cols[k][HG_REG_F_BREAKAWAY] = hg_friction_stribeck(&r->model.p, v) * shape;
    }
}

/* A = dz/dc (z' = A c') and b (z'' = A c'' + b) at q = [z, pose], qd = [z', pose']. */
static void kinematic_terms(const hg_regressor *r, const double q[12], const double qd[12],
                            const double sc[6], double A[36], double b[6])
{
    double Mzz[6], Mzc[36], Mcc[36], Q[12];
    hg_gen_cartesian_terms(r->model.k_lumped, q, qd, sc, Mzz, Mzc, Mcc, Q, A, b);
}

/* Y = Yz + A^-T Yc and the friction columns, at a consistent state. */
static int assemble(const hg_regressor *r, const double q[12], const double qd[12],
                    const double qdd[12], const double sc[6], const double A[36],
                    double Y[6 * HG_REG_NCOL])
{
    double Yz[6 * HG_REG_NIN], Yc[6 * HG_REG_NIN], At[36], fr[6][HG_REG_NFRIC];
    int piv[6], i, j, rc;
    hg_gen_regressor(r->k, q, qd, qdd, sc, Yz, Yc);
    for (i = 0; i < 6; i++)
        for (j = 0; j < 6; j++)
            At[6 * i + j] = A[6 * j + i];
    rc = hg_lu_factor(6, At, piv);
    if (rc)
        return rc;
    hg_lu_solve(6, At, piv, HG_REG_NIN, Yc);       /* Yc := A^-T Yc */
    memset(Y, 0, sizeof(double) * 6 * HG_REG_NCOL);
    for (i = 0; i < 6; i++)
        for (j = 0; j < HG_REG_NIN; j++)
            Y[HG_REG_NCOL * i + j] = Yz[HG_REG_NIN * i + j] + Yc[HG_REG_NIN * i + j];
    hg_regressor_friction(r, qd, fr);
    for (i = 0; i < 6; i++)
        for (j = 0; j < HG_REG_NFRIC; j++)
            Y[HG_REG_NCOL * i + HG_REG_FCOL(i, j)] = fr[i][j];
    return hg_all_finite(6 * HG_REG_NCOL, Y) ? 0 : HG_ERR_STATE_NONFINITE;
}

/* sin/cos of the head angles of q, as the generated functions take them. */
static void trig(const double q[12], double sc[6])
{
    int i;
    for (i = 0; i < 3; i++) {
        sc[2 * i] = sin(q[9 + i]);
        sc[2 * i + 1] = cos(q[9 + i]);
    }
}

int hg_regressor_pose(const hg_regressor *r, const double pose[6], const double posed[6],
                      const double posedd[6], double Y[6 * HG_REG_NCOL],
                      double z[6], double zd[6], double zdd[6])
{
    double q[12], qd[12], qdd[12], sc[6], A[36], b[6];
    int i, j, rc = hg_inverse_kinematics(&r->model.p.geo, pose, q);
    if (rc)
        return rc;
    for (i = 0; i < 6; i++) {
        q[6 + i] = pose[i];
        qd[6 + i] = posed[i];
        qdd[6 + i] = posedd[i];
        qd[i] = 0.0;
    }
    trig(q, sc);
    kinematic_terms(r, q, qd, sc, A, b);         /* A needs q only */
    for (i = 0; i < 6; i++) {
        qd[i] = 0.0;
        for (j = 0; j < 6; j++)
            qd[i] += A[6 * i + j] * posed[j];
    }
    kinematic_terms(r, q, qd, sc, A, b);         /* b at the full velocities */
    for (i = 0; i < 6; i++) {
        qdd[i] = b[i];
        for (j = 0; j < 6; j++)
            qdd[i] += A[6 * i + j] * posedd[j];
    }
    for (i = 0; i < 6; i++) {
        if (z)
            z[i] = q[i];
        if (zd)
            zd[i] = qd[i];
        if (zdd)
            zdd[i] = qdd[i];
    }
    return assemble(r, q, qd, qdd, sc, A, Y);
}

int hg_regressor_joints(const hg_regressor *r, const double z[6], const double zd[6],
                        const double zdd[6], double pose[6], double Y[6 * HG_REG_NCOL])
{
    double q[12], qd[12], qdd[12], sc[6], A[36], b[6], lu[36], x[6];
    int piv[6], i, rc = hg_forward_kinematics(&r->model.p.geo, z, pose, 0, 0);
    if (rc)
        return rc;
    for (i = 0; i < 6; i++) {
        q[i] = z[i];
        q[6 + i] = pose[i];
        qd[i] = zd[i];
        qd[6 + i] = 0.0;
    }
    trig(q, sc);
    kinematic_terms(r, q, qd, sc, A, b);         /* A needs q only */
    memcpy(lu, A, sizeof lu);
    rc = hg_lu_factor(6, lu, piv);
    if (rc)
        return rc;
    memcpy(x, zd, sizeof x);                     /* c' = A^-1 z' */
    hg_lu_solve(6, lu, piv, 1, x);
    for (i = 0; i < 6; i++)
        qd[6 + i] = x[i];
    kinematic_terms(r, q, qd, sc, A, b);         /* b at the full velocities */
    for (i = 0; i < 6; i++)
        x[i] = zdd[i] - b[i];                    /* c'' = A^-1 (z'' - b) */
    hg_lu_solve(6, lu, piv, 1, x);
    for (i = 0; i < 6; i++) {
        qdd[i] = zdd[i];
        qdd[6 + i] = x[i];
    }
    return assemble(r, q, qd, qdd, sc, A, Y);
}

int hg_regressor_joints_n(const hg_regressor *r, long n, const double *z, const double *zd,
                          const double *zdd, const double guess[6], double *poses, double *Y,
                          long *failed_at)
{
    double pose[6] = {0, 0, 0, 0, 0, 0};
    long i;
    if (guess)
        memcpy(pose, guess, sizeof pose);
    if (failed_at)
        *failed_at = -1;
    for (i = 0; i < n; i++) {
        int rc = hg_regressor_joints(r, z + 6 * i, zd + 6 * i, zdd + 6 * i, pose,
                                     Y + 6 * HG_REG_NCOL * i);
        if (rc) {
            if (failed_at)
                *failed_at = i;
            return rc;
        }
        if (poses)
            memcpy(poses + 6 * i, pose, sizeof pose);
    }
    return 0;
}

int hg_regressor_pose_n(const hg_regressor *r, long n, const double *pose, const double *posed,
                        const double *posedd, double *Y, double *z, double *zd, double *zdd,
                        long *failed_at)
{
    long i;
    if (failed_at)
        *failed_at = -1;
    for (i = 0; i < n; i++) {
        int rc = hg_regressor_pose(r, pose + 6 * i, posed + 6 * i, posedd + 6 * i,
                                   Y + 6 * HG_REG_NCOL * i, z ? z + 6 * i : 0,
                                   zd ? zd + 6 * i : 0, zdd ? zdd + 6 * i : 0);
        if (rc) {
            if (failed_at)
                *failed_at = i;
            return rc;
        }
    }
    return 0;
}

/* Smooth part of one step of carriages ch (mask) of a slide batch: the
 * scheme's stages on a = (u - c v + e) / m (e the friction held), as
 * hg_integrate: end speeds v1 and heights z1 before friction. */
static void slide_smooth(int integrator, double c, double dt, const double u[6], const double m[6],
                         const double e[6], const double z0[6], const double v0[6], double z1[6],
                         double v1[6])
{
    const double *cs, *bs;
    int ns = hg_scheme_tableau((hg_integrator)integrator, &cs, &bs), k, s;
    for (k = 0; k < 6; k++) {
        double a = (u[k] - c * v0[k] + e[k]) / m[k], vs = v0[k], sq = 0.0, sv = 0.0;
        if (ns == 0) {                 /* improved Euler */
            z1[k] = z0[k] + v0[k] * dt + 0.5 * a * dt * dt;
            v1[k] = v0[k] + a * dt;
            continue;
        }
        for (s = 0; s < ns; s++) {
            if (s > 0) {
                vs = v0[k] + cs[s] * dt * a;
                a = (u[k] - c * vs + e[k]) / m[k];
            }
            sq += bs[s] * vs;
            sv += bs[s] * a;
        }
        z1[k] = z0[k] + dt * sq;
        v1[k] = v0[k] + dt * sv;
    }
}

int hg_regressor_slide(const hg_params *p, int integrator, double dt, long nev, const long *first,
                       const double *z0, const double *v0, const double *u, const double *m,
                       double *z, double *v)
{
    hg_friction_channel fc[6];
    long g, e, i;
    if (integrator < 0 || integrator >= HG_INTEGRATOR_COUNT || !(dt > 0.0))
        return HG_ERR_BAD_PARAM;
    for (i = 0; i < 6; i++)            /* every carriage alike */
        hg_friction_channel_of(p, &fc[i]);
    for (e = 0; e < nev; e++)
        if (first[e + 1] < first[e])
            return HG_ERR_BAD_PARAM;
    for (i = 0; i < first[nev]; i++)
        if (!(m[i] > 0.0))
            return HG_ERR_BAD_PARAM;
    for (g = 0; g < nev; g += 6) {   /* six runs at a time, one per channel: W is diagonal */
        double zc[6], vc[6], fe[6], uu[6], mm[6], z1[6], v1[6], W[36], vf[6];
        unsigned stuck = 0;
        long len = 0, t;
        int k;
        for (k = 0; k < 6; k++) {
            e = g + k;
            zc[k] = e < nev ? z0[e] : 0.0;
            vc[k] = e < nev ? v0[e] : 0.0;
            /* a moving start: the machine's stages hold the last step's friction, its sliding force */
            fe[k] = vc[k] == 0.0 ? 0.0 : (vc[k] > 0.0 ? -1.0 : 1.0) * hg_friction_curve(&fc[k], fabs(vc[k]));
            if (vc[k] == 0.0)
                stuck |= 1u << k;
            if (e < nev && first[e + 1] - first[e] > len)
                len = first[e + 1] - first[e];
        }
        for (t = 0; t < len; t++) {
            hg_friction_out fo;
            unsigned live = 0;
            int rc;
            for (k = 0; k < 6; k++) {  /* a channel past its run idles at rest */
                e = g + k;
                live |= (e < nev && t < first[e + 1] - first[e]) ? 1u << k : 0u;
                uu[k] = (live >> k) & 1u ? u[first[e] + t] : 0.0;
                mm[k] = (live >> k) & 1u ? m[first[e] + t] : 1.0;
                if (!((live >> k) & 1u))
                    zc[k] = vc[k] = fe[k] = 0.0, stuck |= 1u << k;
            }
            slide_smooth(integrator, p->c_visc_ns_per_m, dt, uu, mm, fe, zc, vc, z1, v1);
            memset(W, 0, sizeof W);
            for (k = 0; k < 6; k++) {
                W[7 * k] = 1.0 / mm[k];
                vf[k] = v1[k] - fe[k] * dt / mm[k];   /* without the friction the stages held */
            }
            rc = hg_friction_solve(fc, 6, W, vf, vc, stuck, dt, &fo);
            if (rc)
                return rc;
            for (k = 0; k < 6; k++) {
                double dv = (fo.impulse[k] - fe[k] * dt) / mm[k];
                v1[k] += dv;
                z1[k] += 0.5 * dt * dv;
                if ((fo.stuck >> k) & 1u) {  /* held where it stopped, as hg_integrate's friction() */
                    z1[k] = zc[k] + ((stuck >> k) & 1u ? 0.0 : 0.5 * vc[k] * fo.stop[k] * dt);
                    v1[k] = 0.0;
                }
                fe[k] = fo.impulse[k] / dt;
                zc[k] = z1[k];
                vc[k] = v1[k];
                if ((live >> k) & 1u) {
                    z[first[g + k] + t] = z1[k];
                    v[first[g + k] + t] = v1[k];
                }
            }
            stuck = fo.stuck;
        }
    }
    return 0;
}
