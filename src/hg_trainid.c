/* hg_trainid.c - the trains' small motion about a slow one, stepped as the board steps (hg_trainid.h). */
#include "hg_trainid.h"
#include "hg_integrate.h"
#include "hg_spd6.h"
#include "hg_errors.h"
#include "hg_math.h"
#include "hg_string.h"
#include "hg_drive.h"

/* The load's factored mass matrix M_L = M - diag(m_r) of one period. */
typedef struct {
    double ldl[36], inv_d[6];
} load_mass;

/* State derivative y' of y (rotors, their speeds, carriages, their speeds) under motor forces u. */
static void deriv(const hg_trainid_params *p, const load_mass *L, const double *y, const double *u, double *dy)
{
    double f[6];
    int k;
    for (k = 0; k < 6; k++) {
        double ft = p->k[k] * (y[k] - y[12 + k]) + p->c[k] * (y[6 + k] - y[18 + k]);
        dy[k] = y[6 + k];
        dy[12 + k] = y[18 + k];
        dy[6 + k] = (u[k] - ft) / p->m_rotor[k];
        f[k] = ft - p->c_visc[k] * y[18 + k];
    }
    hg_spd6_apply(L->ldl, L->inv_d, f);
    memcpy(dy + 18, f, sizeof f);
}

/* One substep h of the scheme from y (in place) with the forces u held. */
static void substep(const hg_trainid_params *p, const load_mass *L, hg_integrator scheme, double h, double *y,
                    const double *u)
{
    double k[4][HG_TRAINID_NSTATE], ys[HG_TRAINID_NSTATE], sum[HG_TRAINID_NSTATE];
    const double *c, *b;
    int ns, s, i;
    if (scheme == HG_INTEGRATOR_IMPROVED_EULER) {   /* q += q' h + q'' h^2/2, q' += q'' h */
        deriv(p, L, y, u, k[0]);
        for (i = 0; i < 6; i++) {
            y[i] += (y[6 + i] + 0.5 * h * k[0][6 + i]) * h;
            y[12 + i] += (y[18 + i] + 0.5 * h * k[0][18 + i]) * h;
            y[6 + i] += h * k[0][6 + i];
            y[18 + i] += h * k[0][18 + i];
        }
        return;
    }
    ns = hg_scheme_tableau(scheme, &c, &b);
    memset(sum, 0, sizeof sum);
    for (s = 0; s < ns; s++) {                   /* explicit stages, each from y (the tableaus are diagonal) */
        for (i = 0; i < HG_TRAINID_NSTATE; i++)
            ys[i] = s ? y[i] + c[s] * h * k[s - 1][i] : y[i];
        deriv(p, L, ys, u, k[s]);
        for (i = 0; i < HG_TRAINID_NSTATE; i++)
            sum[i] += b[s] * k[s][i];
    }
    for (i = 0; i < HG_TRAINID_NSTATE; i++)
        y[i] += h * sum[i];
}

/* M_L of a rigid mass matrix: factored, or HG_ERR_SINGULAR_MASS. */
static int load_of(const hg_trainid_params *p, const double *mass, load_mass *L)
{
    int i, j;
    for (i = 0; i < 6; i++)
        for (j = 0; j < 6; j++)
            L->ldl[6 * i + j] = 0.5 * (mass[6 * i + j] + mass[6 * j + i]) - (i == j ? p->m_rotor[i] : 0.0);
    return hg_spd6_factor(L->ldl, L->inv_d);
}

int hg_trainid_response(const hg_trainid_params *p, hg_integrator scheme, int ns, double dt, long np,
                        const double *mass, long every, const double *u, double x[HG_TRAINID_NSTATE],
                        double *motor, double *load)
{
    load_mass L;
    const double *c, *b;
    long n, at = -1;
    int k, s, rc;
    if (!(scheme == HG_INTEGRATOR_IMPROVED_EULER || hg_scheme_tableau(scheme, &c, &b) > 0) || ns < 1 ||
        every < 1 || !(dt > 0.0))
        return HG_ERR_BAD_PARAM;
    for (k = 0; k < 6; k++)
        if (!(p->k[k] > 0.0) || !(p->m_rotor[k] > 0.0) || !(p->c[k] >= 0.0))
            return HG_ERR_BAD_PARAM;
    for (n = 0; n < np; n++) {
        if (n / every != at) {
            at = n / every;
            rc = load_of(p, mass + 36 * at, &L);
            if (rc)
                return rc;
        }
        for (s = 0; s < ns; s++)
            substep(p, &L, scheme, dt / ns, x, u + 6 * (n * ns + s));
        memcpy(motor + 6 * n, x, 6 * sizeof(double));
        if (load)
            memcpy(load + 6 * n, x + 12, 6 * sizeof(double));
    }
    return 0;
}

int hg_trainid_drive(const hg_model *m, int ns, double dt, long np, const double *volts, const double *speed,
                     double *u)
{
    double cur[6] = {0, 0, 0, 0, 0, 0}, vint[6] = {0, 0, 0, 0, 0, 0}, z0[6] = {0, 0, 0, 0, 0, 0}, z1[6];
    hg_drive_memo memo;
    hg_drive_out o;
    long n;
    int s, k;
    if (ns < 1 || !(dt > 0.0))
        return HG_ERR_BAD_PARAM;
    memset(&memo, 0, sizeof memo);
    for (n = 0; n < np; n++)
        for (s = 0; s < ns; s++) {
            hg_drive_step(m->drive, 6, volts + 6 * n, cur, speed + 6 * n, vint, 0x3fu, dt / ns, &memo, &o);
            for (k = 0; k < 6; k++) {
                u[6 * (n * ns + s) + k] = o.i_mean[k] * m->drive[k].force_per_amp_n;
                z1[k] = z0[k] + speed[6 * n + k] * dt / ns;
            }
            hg_drive_integral(m->drive, 6, 0x3fu, &o, z0, z1, dt / ns, vint);
            memcpy(cur, o.i_end, sizeof cur);
            memcpy(z0, z1, sizeof z0);
        }
    return 0;
}
