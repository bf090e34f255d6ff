/* test_dynamics_terms.c - the generated mass matrices and potentials
 * against a second formulation written here from the spec: kinetic energy
 * by Koenig's theorem (bar: COM at mid-length, inertia i_bar - m_bar l^2/4
 * about it; head: COM velocity and body angular velocity from finite
 * differences of the rotation), velocities by finite differences of the
 * closed-form inverse kinematics. Also the structured Standard step against
 * the dense generic one. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_step.h"
#include "hg_errors.h"

#define EPS 1e-6

/* joints and pose at parameter s along c + s cd */
static void state_at(const hg_params *p, const double c[6], const double cd[6], double s,
                     double z[6], double pose[6])
{
    int i;
    for (i = 0; i < 6; i++)
        pose[i] = c[i] + s * cd[i];
    hg_inverse_kinematics(&p->geo, pose, z);
}

/* bar angles of the standard model for (z, pose) */
static void angles_at(const hg_params *p, const double z[6], const double pose[6], double a[12])
{
    double B[6][3], A[6][3];
    int k;
    hg_joint_points(&p->geo, z, pose, B, A);
    for (k = 0; k < 6; k++) {
        double u[3] = {(A[k][0] - B[k][0]) / p->geo.l_m, (A[k][1] - B[k][1]) / p->geo.l_m,
                       (A[k][2] - B[k][2]) / p->geo.l_m};
        a[2 * k] = atan2(u[1], -u[2]);
        a[2 * k + 1] = asin(-u[0]);
    }
}

/* Koenig kinetic energy and gravity potential of the state c + s cd. */
static void reference_energy(const hg_params *p, const double c[6], const double cd[6],
                             double *T, double *V)
{
    double z0[6], z1[6], zm[6], p0[6], p1[6], pm[6], B0[6][3], A0[6][3], B1[6][3], A1[6][3];
    double Bm[6][3], Am[6][3], R0[9], R1[9], Rm[9], W[9], t = 0, v = 0;
    double rotor = p->j_rotor_kgm2 * pow(2 * M_PI / p->lead_m, 2);
    double icom = p->i_bar_kgm2 - p->m_bar_kg * p->geo.l_m * p->geo.l_m / 4;
    double sh[3] = {0, 0, -p->head_com_m}, G0[3], G1[3], Gm[3];
    int k, r, j;
    state_at(p, c, cd, -EPS, z0, p0);
    state_at(p, c, cd, EPS, z1, p1);
    state_at(p, c, cd, 0, zm, pm);
    hg_joint_points(&p->geo, z0, p0, B0, A0);
    hg_joint_points(&p->geo, z1, p1, B1, A1);
    hg_joint_points(&p->geo, zm, pm, Bm, Am);
    for (k = 0; k < 6; k++) {
        double zd = (z1[k] - z0[k]) / (2 * EPS), vc2 = 0, ud2 = 0;
        t += 0.5 * (p->m_carriage_kg + rotor) * zd * zd;
        for (r = 0; r < 3; r++) {
            double vc = ((A1[k][r] + B1[k][r]) - (A0[k][r] + B0[k][r])) / (4 * EPS);
            double ud = ((A1[k][r] - B1[k][r]) - (A0[k][r] - B0[k][r])) / (2 * EPS * p->geo.l_m);
            vc2 += vc * vc;
            ud2 += ud * ud;
        }
        t += 0.5 * p->m_bar_kg * vc2 + 0.5 * icom * ud2;
        v += p->g_mps2 * (p->m_carriage_kg * zm[k] + p->m_bar_kg * (Am[k][2] + Bm[k][2]) / 2);
    }
    hg_rotation(p0[3], p0[4], p0[5], R0);
    hg_rotation(p1[3], p1[4], p1[5], R1);
    hg_rotation(pm[3], pm[4], pm[5], Rm);
    for (r = 0; r < 3; r++) {
        G0[r] = p0[r]; G1[r] = p1[r]; Gm[r] = pm[r];
        for (j = 0; j < 3; j++) {
            G0[r] += R0[3 * r + j] * sh[j];
            G1[r] += R1[3 * r + j] * sh[j];
            Gm[r] += Rm[3 * r + j] * sh[j];
        }
    }
    for (r = 0; r < 3; r++) {
        double vg = (G1[r] - G0[r]) / (2 * EPS);
        t += 0.5 * p->m_head_kg * vg * vg;
        for (j = 0; j < 3; j++) {      /* W = R^T R' (body angular velocity, skew) */
            int i;
            W[3 * r + j] = 0;
            for (i = 0; i < 3; i++)
                W[3 * r + j] += Rm[3 * i + r] * (R1[3 * i + j] - R0[3 * i + j]) / (2 * EPS);
        }
    }
    {
        double wb[3] = {W[7], W[2], W[3]};
        t += 0.5 * (p->i_head_xx_kgm2 * wb[0] * wb[0] + p->i_head_yy_kgm2 * wb[1] * wb[1] +
                    p->i_head_zz_kgm2 * wb[2] * wb[2]);
    }
    v += p->g_mps2 * p->m_head_kg * Gm[2];
    *T = t;
    *V = v;
}

/* hg_data of model kind for the state c + 0 cd (velocities by central differences). */
static void make_data(const hg_model *m, const double c[6], const double cd[6], hg_data *d)
{
    double z0[6], z1[6], p0[6], p1[6], a0[12], a1[12];
    int i;
    memset(d, 0, sizeof *d);
    state_at(&m->p, c, cd, 0, d->z_m, d->pose);
    state_at(&m->p, c, cd, -EPS, z0, p0);
    state_at(&m->p, c, cd, EPS, z1, p1);
    for (i = 0; i < 6; i++) {
        d->zd_mps[i] = (z1[i] - z0[i]) / (2 * EPS);
        d->posed[i] = cd[i];
    }
    angles_at(&m->p, d->z_m, d->pose, d->bar_rad);
    angles_at(&m->p, z0, p0, a0);
    angles_at(&m->p, z1, p1, a1);
    for (i = 0; i < 12; i++)
        d->bar_radps[i] = (a1[i] - a0[i]) / (2 * EPS);
}

static void test_energies(void)
{
    hg_params p;
    hg_model m[2];
    double home_v, worst_t[2] = {0, 0}, worst_v[2] = {0, 0}, tmax = 0, zero[6] = {0, 0, 0, 0, 0, 0};
    int kind, n, i;
    hg_params_default(&p);
    hg_model_init(&m[0], &p, HG_MODEL_STANDARD, 0, 0);
    hg_model_init(&m[1], &p, HG_MODEL_REDUCED_CARTESIAN, 0, 0);
    {
        double t;
        reference_energy(&p, zero, zero, &t, &home_v);
    }
    for (n = 0; n < 20; n++) {
        double c[6], cd[6], tr, vr;
        for (i = 0; i < 3; i++) {
            c[i] = hg_test_uniform(-0.05, 0.05);
            c[i + 3] = hg_test_uniform(-0.15, 0.15);
            cd[i] = hg_test_uniform(-0.5, 0.5);
            cd[i + 3] = hg_test_uniform(-1.0, 1.0);
        }
        reference_energy(&p, c, cd, &tr, &vr);
        tmax = fmax(tmax, tr);
        for (kind = 0; kind < 2; kind++) {
            hg_data d;
            double t, v;
            make_data(&m[kind], c, cd, &d);
            hg_energy(&m[kind], &d, &t, &v);
            worst_t[kind] = fmax(worst_t[kind], fabs(t - tr) / tr);
            worst_v[kind] = fmax(worst_v[kind], fabs(v - (vr - home_v)));
        }
    }
    for (kind = 0; kind < 2; kind++) {
        CHECK(worst_t[kind] < 1e-7, "%s: kinetic energy 1/2 q'^T M q' = Koenig's formula at 20 random "
              "states (max rel. diff %.1e, T up to %.1f J)", kind ? "reduced" : "standard", worst_t[kind], tmax);
        CHECK(worst_v[kind] < 1e-9, "%s: gravity potential = spec's masses times heights (max diff %.1e J)",
              kind ? "reduced" : "standard", worst_v[kind]);
    }
}

/* The structured Standard step and the dense generic one give the same state. */
static void test_standard_dense(void)
{
    hg_params p;
    hg_model m;
    hg_data d;
    double v[6] = {1, -2, 0.5, 2, -1, 0.3}, fz[6], q0[24], qd0[24], q1[24], qd1[24], qdd[24];
    double q2[24], qd2[24], qdd2[24], r1, r2, worst = 0;
    int i, s, rc1 = 0, rc2 = 0;
    hg_params_default(&p);
    hg_model_init(&m, &p, HG_MODEL_STANDARD, 0, 0);
    hg_data_reset(&m, &d);
    for (s = 0; s < 100; s++)
        hg_step(&m, &d, v, 1e-3);
    for (i = 0; i < 6; i++) {
        q0[i] = d.z_m[i]; qd0[i] = d.zd_mps[i];
        q0[18 + i] = d.pose[i]; qd0[18 + i] = d.posed[i];
        fz[i] = 100.0 * (i - 2.5);
    }
    for (i = 0; i < 12; i++) {
        q0[6 + i] = d.bar_rad[i];
        qd0[6 + i] = d.bar_radps[i];
    }
    rc1 = hg_step_standard(&m, q0, qd0, fz, 1e-3, q1, qd1, qdd, &r1);
    rc2 = hg_step_joints(&m, q0, qd0, fz, 1e-3, q2, qd2, qdd2, &r2);
    for (i = 0; i < 24; i++)
        worst = fmax(worst, fabs(qdd[i] - qdd2[i]) + fabs(q1[i] - q2[i]) + fabs(qd1[i] - qd2[i]));
    CHECK(rc1 == 0 && rc2 == 0 && worst < 1e-9,
          "standard: structured step = dense 18x18 step (max difference %.1e)", worst);
}

int main(void)
{
    test_energies();
    test_standard_dense();
    return hg_test_exit();
}
