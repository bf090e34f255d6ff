/* test_regressor.c - the identification regressor (src/hg_regressor.c,
 * generated hg_gen_regressor) against the dynamics: Y(z, z', z'') pi must
 * be the drive force that produced the accelerations the dynamics computed.
 *
 * Independent facts: random parameter sets and random tilted, rotating
 * states (carriage velocities by finite differences of the closed-form
 * inverse kinematics, not by the A of the regressor); one improved-Euler
 * hg_step from that state gives z'' at the start state (hg_data.zdd_mps2)
 * for given DAC volts; the drive force is ka V kt 2 pi / lead, written
 * here; pi is written here from docs/model.md (the lumped bar, the head's
 * first moment -m_head head_com and inertia about Op by the parallel-axis
 * theorem, the reflected rotor j_rotor (2 pi / lead)^2, the carriage weight
 * on the offset column, c_visc, f_coulomb; f_static = f_coulomb so the
 * sliding force is the same at every speed). Checked for the Standard kind
 * (rigid bars with angles: a second formulation, not the lumped one the
 * regressor is derived from) and both reduced kinds. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_regressor.h"
#include "hg_errors.h"

#define FD 1e-6

/* pi of the spec's parameter set p, written from docs/model.md */
static void pi_of(const hg_params *p, double pi[HG_REG_NCOL])
{
    double l2 = p->geo.l_m * p->geo.l_m, hc = p->head_com_m, m = p->m_head_kg;
    double rotor = p->j_rotor_kgm2 * pow(2 * M_PI / p->lead_m, 2);
    int k;
    memset(pi, 0, sizeof(double) * HG_REG_NCOL);
    pi[0] = m;
    pi[3] = -m * hc;                                  /* first moment, head z */
    pi[4] = p->i_head_xx_kgm2 + m * hc * hc;          /* inertia about Op */
    pi[5] = p->i_head_yy_kgm2 + m * hc * hc;
    pi[6] = p->i_head_zz_kgm2;
    pi[10] = 2 * p->i_bar_kgm2 / l2 - p->m_bar_kg / 2; /* m_end: 2 me + mm = m_bar, me + mm/4 = i_bar/l^2 */
    pi[11] = p->m_bar_kg - 2 * pi[10];                /* m_mid */
    for (k = 0; k < 6; k++) {
        pi[12 + k] = p->m_carriage_kg + rotor;
        pi[HG_REG_FCOL(k, HG_REG_F_OFFSET)] = p->g_mps2 * p->m_carriage_kg;
        pi[HG_REG_FCOL(k, HG_REG_F_VISCOUS)] = p->c_visc_ns_per_m;
        pi[HG_REG_FCOL(k, HG_REG_F_COULOMB)] = p->f_coulomb_n;
    }
}

/* A random parameter set around the spec's, friction on. */
static void random_params(hg_params *p)
{
    hg_test_rigid_defaults(p);
    p->m_head_kg *= hg_test_uniform(0.6, 1.6);
    p->head_com_m *= hg_test_uniform(0.3, 2.0);
    p->i_head_xx_kgm2 *= hg_test_uniform(0.5, 2.0);
    p->i_head_yy_kgm2 *= hg_test_uniform(0.5, 2.0);
    p->i_head_zz_kgm2 *= hg_test_uniform(0.5, 2.0);
    p->m_bar_kg *= hg_test_uniform(0.7, 1.3);
    p->i_bar_kgm2 = p->m_bar_kg * p->geo.l_m * p->geo.l_m * hg_test_uniform(0.27, 0.45);
    p->m_carriage_kg *= hg_test_uniform(0.5, 2.0);
    p->j_rotor_kgm2 *= hg_test_uniform(0.5, 1.5);
    p->c_visc_ns_per_m *= hg_test_uniform(0.5, 1.5);
    p->f_coulomb_n = hg_test_uniform(20, 200);
    p->f_static_n = p->f_coulomb_n;   /* a constant sliding force: the start state's force */
    p->v_bus_v = 1000.0;              /* no back-EMF limit at these speeds: the current is ka V */
}

/* hg_regressor_slide, one carriage alone, against closed forms: stick holds
 * exactly up to f_static and breaks away in the first step beyond it;
 * Coulomb friction alone stops a carriage where m v0^2 / (2 f_c) says
 * and holds it there; viscous and Coulomb under a constant force approach
 * (u - f_c)/c as v_inf + (v0 - v_inf) exp(-c t / m) (each scheme to its
 * order); runs batched as one call are the runs alone; bad input refused. */
static void slide_checks(void)
{
    enum { N = 400 };
    static double u[N], m[N], z[N], v[N], zz[N], vv[N];
    const double dt = 0.001, mass = 56.0, fs = 100.0, fc = 40.0;
    hg_params p;
    long first[8] = {0, N};
    double z0 = 0.01, v0 = 0.0, worst = 0.0;
    int i, moved = -1, scheme, e;
    hg_test_rigid_defaults(&p);
    p.f_static_n = fs;
    p.f_coulomb_n = fc;
    p.c_visc_ns_per_m = 0.0;
    for (i = 0; i < N; i++) {            /* a force ramp through f_static */
        u[i] = -2.0 * fs * (i + 0.5) / N;
        m[i] = mass;
    }
    CHECK(hg_regressor_slide(&p, HG_INTEGRATOR_HEUN, dt, 1, first, &z0, &v0, u, m, z, v) == 0, "slide runs");
    for (i = 0; i < N && moved < 0; i++)
        if (z[i] != z0 || v[i] != 0.0)
            moved = i;
    CHECK(moved >= 0 && -u[moved] > fs && (moved == 0 || -u[moved - 1] <= fs) && v[moved] < 0,
          "stuck exactly while |u| <= f_static, away downwards in the first step beyond it (step %d, u %.2f N)",
          moved, moved >= 0 ? u[moved] : 0.0);
    /* Coulomb alone (the Stribeck curve flat): a carriage at 5 mm/s stops after m v0^2 / (2 f_c) and stays */
    p.f_static_n = fc;
    for (i = 0; i < N; i++)
        u[i] = 0.0;
    v0 = 0.005;
    hg_regressor_slide(&p, HG_INTEGRATOR_HEUN, dt, 1, first, &z0, &v0, u, m, z, v);
    CHECK(fabs(z[N - 1] - z0 - mass * v0 * v0 / (2 * fc)) < 1e-15 && v[N - 1] == 0.0 &&
          z[N - 1] == z[N / 2],
          "Coulomb friction stops it at m v0^2/(2 f_c) = %.4f um and holds it (%.1e m off)",
          1e6 * mass * v0 * v0 / (2 * fc), fabs(z[N - 1] - z0 - mass * v0 * v0 / (2 * fc)));
    /* viscous and Coulomb under a constant force, on the flat of the Stribeck curve */
    p.c_visc_ns_per_m = 6000.0;
    for (i = 0; i < N; i++)
        u[i] = 400.0;
    v0 = 0.02;
    for (scheme = HG_INTEGRATOR_IMPROVED_EULER; scheme <= HG_INTEGRATOR_RK4; scheme++) {
        const double tol[3] = {2e-2, 2e-3, 2e-6}, vinf = (400.0 - fc) / 6000.0;
        worst = 0.0;
        hg_regressor_slide(&p, scheme, dt, 1, first, &z0, &v0, u, m, v, z);   /* v: heights, z: speeds */
        for (i = 0; i < N; i++)
            worst = fmax(worst, fabs(z[i] - (vinf + (v0 - vinf) * exp(-6000.0 * (i + 1) * dt / mass))));
        CHECK(worst < tol[scheme] * vinf, "scheme %d: the speed approaches (u - f_c)/c as the closed form "
              "(%.1e of it)", scheme, worst / vinf);
    }
    /* seven runs of different lengths in one call = each alone, to the friction solve's
     * tolerance (its fixed point over the Stribeck curve sees the whole batch) */
    {
        double zs[7], vs[7], vmax = 0.0;
        first[0] = 0;
        for (e = 0; e < 7; e++) {
            first[e + 1] = first[e] + 20 + 7 * e;
            zs[e] = 0.001 * e;
            vs[e] = e % 2 ? 0.0 : 0.003 * (e - 3);
        }
        for (i = 0; i < first[7]; i++)
            u[i] = 150.0 * sin(0.05 * i);
        p.f_static_n = fs;
        hg_regressor_slide(&p, HG_INTEGRATOR_HEUN, dt, 7, first, zs, vs, u, m, z, v);
        worst = 0.0;
        for (e = 0; e < 7; e++) {
            long one[2] = {0, first[e + 1] - first[e]};
            hg_regressor_slide(&p, HG_INTEGRATOR_HEUN, dt, 1, one, zs + e, vs + e, u + first[e], m + first[e],
                               zz, vv);
            for (i = 0; i < one[1]; i++) {
                worst = fmax(worst, fabs(vv[i] - v[first[e] + i]));
                vmax = fmax(vmax, fabs(vv[i]));
            }
        }
        CHECK(worst < 3e-3 * vmax, "seven runs in one call are each run alone (speeds within %.1e of the "
              "largest)", worst / vmax);
    }
    first[0] = 0;
    first[1] = N;
    CHECK(hg_regressor_slide(&p, 7, dt, 1, first, &z0, &v0, u, m, z, v) == HG_ERR_BAD_PARAM,
          "an unknown integrator is refused");
    m[3] = 0.0;
    CHECK(hg_regressor_slide(&p, HG_INTEGRATOR_HEUN, dt, 1, first, &z0, &v0, u, m, z, v) == HG_ERR_BAD_PARAM,
          "a mass that is not positive is refused");
}

/* One random state through one step of `kind`: max |Y pi - F| / max |F|. */
static double one_case(hg_model_kind kind, double *fscale)
{
    hg_params p;
    hg_model m;
    hg_data d;
    hg_regressor r;
    double c[6], cd[6], z[6], zd[6], zp[6], zm[6], cp[6], cm[6], volts[6], a[12], ap[12], am[12];
    double Y[6 * HG_REG_NCOL], pi[HG_REG_NCOL], pose[6] = {0, 0, 0, 0, 0, 0}, worst = 0, fmax = 0;
    const char *bad = 0, *why = 0;
    int i, k, rc;
    random_params(&p);
    if (hg_model_init(&m, &p, kind, &bad, &why) || hg_data_reset(&m, &d) ||
        hg_regressor_init(&r, &p, &bad, &why) || hg_model_set_integrator(&m, HG_INTEGRATOR_IMPROVED_EULER))
        return 1e9;
    do {                                          /* every carriage sliding, clearly (no stop within the step) */
        double slowest = INFINITY;
        for (i = 0; i < 3; i++) {
            c[i] = hg_test_uniform(-0.06, 0.06);
            c[3 + i] = hg_test_uniform(-0.15, 0.15);
            cd[i] = hg_test_uniform(-0.08, 0.08);
            cd[3 + i] = hg_test_uniform(-0.4, 0.4);
        }
        for (i = 0; i < 6; i++) {
            cp[i] = c[i] + FD * cd[i];
            cm[i] = c[i] - FD * cd[i];
            volts[i] = hg_test_uniform(-3, 3);
        }
        if (hg_inverse_kinematics(&p.geo, c, z) || hg_inverse_kinematics(&p.geo, cp, zp) ||
            hg_inverse_kinematics(&p.geo, cm, zm))
            return 1e9;
        for (k = 0; k < 6; k++) {
            zd[k] = (zp[k] - zm[k]) / (2 * FD);
            slowest = fmin(slowest, fabs(zd[k]));
        }
        if (slowest > 0.005)
            break;
    } while (1);
    memcpy(d.z_m, z, sizeof z);
    memcpy(d.zd_mps, zd, sizeof zd);
    memcpy(d.pose, c, sizeof c);
    memcpy(d.posed, cd, sizeof cd);
    if (kind == HG_MODEL_STANDARD) {
        hg_test_bar_angles(&p, z, c, a);
        hg_test_bar_angles(&p, zp, cp, ap);
        hg_test_bar_angles(&p, zm, cm, am);
        for (i = 0; i < 12; i++) {
            d.bar_rad[i] = a[i];
            d.bar_radps[i] = (ap[i] - am[i]) / (2 * FD);
        }
    }
    d.trig_valid = 0;
    d.stuck = 0;                                  /* every carriage moves: sliding friction */
    for (k = 0; k < 6; k++)                       /* the windings carry ka V already */
        d.current_a[k] = p.ka_a_per_v * volts[k];
    rc = hg_step(&m, &d, volts, 1e-4);            /* improved Euler: zdd at the start state */
    if (rc || d.stuck)
        return 1e9;
    rc = hg_regressor_joints(&r, z, zd, d.zdd_mps2, pose, Y);
    if (rc)
        return 1e9;
    pi_of(&p, pi);
    for (k = 0; k < 6; k++) {
        double f = p.ka_a_per_v * volts[k] * p.kt_nm_per_a * 2 * M_PI / p.lead_m, y = 0;
        for (i = 0; i < HG_REG_NCOL; i++)
            y += Y[HG_REG_NCOL * k + i] * pi[i];
        if (fabs(y - f) > worst)
            worst = fabs(y - f);
        if (fabs(f) > fmax)
            fmax = fabs(f);
    }
    *fscale = fmax;
    return worst / fmax;
}

int main(void)
{
    static const hg_model_kind kinds[] = {HG_MODEL_STANDARD, HG_MODEL_REDUCED_JOINTS,
                                          HG_MODEL_REDUCED_CARTESIAN};
    hg_params p;
    hg_regressor r;
    double pi_gen[HG_GEN_REGRESSOR_NPAR], pi[HG_REG_NCOL], worst_spec = 0;
    const char *bad = 0, *why = 0;
    int i, n;

    /* the generated spec mapping against the one written here */
    for (n = 0; n < 5; n++) {
        random_params(&p);
        hg_gen_regressor_spec(&p, pi_gen);
        pi_of(&p, pi);
        for (i = 0; i < HG_GEN_REGRESSOR_NPAR; i++)
            if (fabs(pi_gen[i] - pi[i]) > worst_spec * (1 + fabs(pi[i])))
                worst_spec = fabs(pi_gen[i] - pi[i]) / (1 + fabs(pi[i]));
    }
    CHECK(worst_spec < 1e-13, "hg_gen_regressor_spec = pi written from docs/model.md (5 random sets, %.1e)",
          worst_spec);

    for (i = 0; i < 3; i++) {
        double worst = 0, fs = 0, f = 0;
        for (n = 0; n < 8; n++) {
            double e = one_case(kinds[i], &f);
            if (e > worst)
                worst = e;
            if (f > fs)
                fs = f;
        }
        CHECK(worst < 1e-7, "%s: Y(z, z', z'') pi = the drive force ka V kt 2 pi/lead of hg_step's "
              "accelerations, 8 random sets and tilted rotating states (worst %.1e of up to %.0f N)",
              hg_model_name(kinds[i]), worst, fs);
    }

    /* pose and joint entry points agree */
    {
        double c[6] = {0.03, -0.02, -0.05, 0.1, -0.08, 0.2}, cd[6] = {0.05, 0.02, -0.04, 0.2, 0.1, -0.3};
        double cdd[6] = {0.5, -0.3, 0.2, 1.0, -2.0, 0.5}, z[6], zd[6], zdd[6], Yp[6 * HG_REG_NCOL];
        double Yj[6 * HG_REG_NCOL], pose[6] = {0, 0, 0, 0, 0, 0}, diff = 0, scale = 0;
        hg_test_rigid_defaults(&p);
        hg_regressor_init(&r, &p, &bad, &why);
        CHECK(hg_regressor_pose(&r, c, cd, cdd, Yp, z, zd, zdd) == 0 &&
              hg_regressor_joints(&r, z, zd, zdd, pose, Yj) == 0, "both entry points evaluate");
        for (i = 0; i < 6 * HG_REG_NCOL; i++) {
            if (fabs(Yp[i] - Yj[i]) > diff)
                diff = fabs(Yp[i] - Yj[i]);
            if (fabs(Yp[i]) > scale)
                scale = fabs(Yp[i]);
        }
        for (i = 0; i < 6; i++)
            if (fabs(pose[i] - c[i]) > 1e-12)
                diff = 1e9;
        CHECK(diff < 1e-9 * scale, "from the pose and from the joints: the same Y (%.1e of %.1f) and pose",
              diff, scale);
    }

    /* the friction columns of a sliding carriage: offset 1, viscous z', Coulomb sign(z'),
     * breakaway excess the Stribeck shape exp(-(z'/v_stribeck)^2) sign(z') */
    {
        double zd[6] = {0.01, -0.002, 0.0005, 0.003, -0.05, 1e-4}, cols[6][HG_REG_NFRIC], e = 0;
        hg_test_rigid_defaults(&p);
        hg_regressor_init(&r, &p, &bad, &why);
        hg_regressor_friction(&r, zd, cols);
        for (i = 0; i < 6; i++) {
            double sg = zd[i] > 0 ? 1.0 : -1.0, x = zd[i] / 0.002;
            e = fmax(e, fabs(cols[i][HG_REG_F_OFFSET] - 1));
            e = fmax(e, fabs(cols[i][HG_REG_F_VISCOUS] - zd[i]));
            e = fmax(e, fabs(cols[i][HG_REG_F_COULOMB] - sg));
            e = fmax(e, fabs(cols[i][HG_REG_F_BREAKAWAY] - exp(-x * x) * sg));
        }
        CHECK(e < 1e-15, "friction columns: 1, z', sign(z'), exp(-(z'/2 mm/s)^2) sign(z') (%.1e)", e);
    }
    slide_checks();
    CHECK(hg_regressor_joints(&r, (double[6]){5, 5, 5, 5, 5, 5}, (double[6]){0}, (double[6]){0},
                              (double[6]){0}, (double[6 * HG_REG_NCOL]){0}) != 0,
          "joints out of reach are refused (%s)", "forward kinematics fails");
    return hg_test_exit();
}
