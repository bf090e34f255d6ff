/* hg_regressor.c - drive forces linear in the parameters (hg_regressor.h). */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_regressor.h"
#include "hg_dynamics.h"
#include "hg_gen_reduced.h"
#include "hg_linalg.h"
#include "hg_errors.h"
#include "hg_friction.h"

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
