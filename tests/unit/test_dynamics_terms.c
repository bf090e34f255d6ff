/* test_dynamics_terms.c - the generated mass matrices and potentials
 * against a second formulation written here from the spec: kinetic energy
 * by Koenig's theorem (bar: COM at mid-length, inertia i_bar - m_bar l^2/4
 * about it; head: COM velocity and body angular velocity from finite
 * differences of the rotation), velocities by finite differences of the
 * closed-form inverse kinematics. Also the structured Standard
 * accelerations against the dense augmented (KKT) system solved here, and
 * its stabilization against the constraints it must restore. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_integrate.h"
#include "hg_step_standard.h"
#include "hg_gen_standard.h"
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
    hg_test_bar_angles(&m->p, d->z_m, d->pose, d->bar_rad);
    hg_test_bar_angles(&m->p, z0, p0, a0);
    hg_test_bar_angles(&m->p, z1, p1, a1);
    for (i = 0; i < 12; i++)
        d->bar_radps[i] = (a1[i] - a0[i]) / (2 * EPS);
}

static void test_energies(void)
{
    hg_params p;
    hg_model m[2];
    double home_v, worst_t[2] = {0, 0}, worst_v[2] = {0, 0}, tmax = 0, zero[6] = {0, 0, 0, 0, 0, 0};
    int kind, n, i;
    hg_test_rigid_defaults(&p);
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

/* Dense Phi_q (18 x 24) of the standard model from the generated blocks. */
static void standard_jacobian(const double Pa[36], const double Pc[108], double *J)
{
    int k, r, c;
    memset(J, 0, 18 * 24 * sizeof(double));
    for (k = 0; k < 6; k++)
        for (r = 0; r < 3; r++) {
            J[(3 * k + r) * 24 + k] = r == 2 ? 1.0 : 0.0;  /* B_k moves with z_k along +z */
            for (c = 0; c < 2; c++)
                J[(3 * k + r) * 24 + 6 + 2 * k + c] = Pa[6 * k + 2 * r + c];
            for (c = 0; c < 6; c++)
                J[(3 * k + r) * 24 + 18 + c] = Pc[6 * (3 * k + r) + c];
        }
}

/* The structured Standard accelerations equal the dense KKT solution of
 * [M Phi_q^T; Phi_q 0] [q''; lambda] = [Q + f; -gamma] (a second
 * formulation of Eq. 13), and its stabilization leaves the constraints
 * and the velocity constraints at rounding level. */
static void test_standard_kkt(void)
{
    hg_params p;
    static hg_model m;
    static hg_data d;
    static double K[42 * 42], J[18 * 24];
    double v[6] = {1, -2, 0.5, 2, -1, 0.3}, fz[6], q0[24], qd0[24], q1[24], qd1[24], qdd[24];
    double mzz[6], Mza[12], Maa[24], Mcc[36], Q[24], Pa[36], Pc[108], gm[18], phi[18], b[42];
    double worst = 0, scale = 0, res, pworst = 0, vworst = 0;
    int i, j, k, r, c, rc;
    hg_test_rigid_defaults(&p);
    hg_model_init(&m, &p, HG_MODEL_STANDARD, 0, 0);
    hg_data_reset(&m, &d);
    for (i = 0; i < 100; i++)
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
    rc = hg_standard_accel(&m, &d, q0, qd0, fz, qdd);
    hg_gen_standard_terms(m.k, q0, qd0, mzz, Mza, Maa, Mcc, Q, Pa, Pc, gm);
    standard_jacobian(Pa, Pc, J);
    memset(K, 0, sizeof K);
    for (k = 0; k < 6; k++) {          /* M: z diagonal, z_k with bar k's angles, 2x2 per bar, c */
        K[k * 42 + k] = mzz[k];
        for (c = 0; c < 2; c++) {
            K[k * 42 + 6 + 2 * k + c] = K[(6 + 2 * k + c) * 42 + k] = Mza[2 * k + c];
            for (r = 0; r < 2; r++)
                K[(6 + 2 * k + r) * 42 + 6 + 2 * k + c] = Maa[4 * k + 2 * r + c];
        }
        for (c = 0; c < 6; c++)
            K[(18 + k) * 42 + 18 + c] = Mcc[6 * k + c];
    }
    for (r = 0; r < 18; r++)
        for (j = 0; j < 24; j++)
            K[(24 + r) * 42 + j] = K[j * 42 + 24 + r] = J[r * 24 + j];
    for (i = 0; i < 24; i++)
        b[i] = Q[i] + (i < 6 ? fz[i] : 0.0);
    for (r = 0; r < 18; r++)
        b[24 + r] = -gm[r];
    hg_test_solve(42, K, b);
    for (i = 0; i < 24; i++) {
        worst = fmax(worst, fabs(qdd[i] - b[i]));
        scale = fmax(scale, fabs(b[i]));
    }
    CHECK(rc == 0 && worst <= 1e-9 * scale,
          "standard: structured Eq. 13 accelerations = dense KKT solution (max difference %.1e, "
          "largest q'' %.2f)", worst, scale);
    for (i = 0; i < 24; i++) {         /* improved Euler, then the stabilization */
        q1[i] = q0[i] + qd0[i] * 1e-3 + 0.5e-6 * qdd[i];
        qd1[i] = qd0[i] + qdd[i] * 1e-3;
    }
    rc = hg_standard_stabilize(&m, &d, q1, qd1, &res);
    hg_gen_standard_constraints(m.k, q1, phi, Pa, Pc);
    standard_jacobian(Pa, Pc, J);
    for (r = 0; r < 18; r++) {
        double vc = 0;
        for (j = 0; j < 24; j++)
            vc += J[r * 24 + j] * qd1[j];
        pworst = fmax(pworst, fabs(phi[r]));
        vworst = fmax(vworst, fabs(vc));
    }
    CHECK(rc == 0 && pworst < 1e-11 && vworst < 1e-9,
          "standard: after the stabilization |Phi| = %.1e m, |Phi_q q'| = %.1e m/s", pworst, vworst);
}

int main(void)
{
    test_energies();
    test_standard_kkt();
    return hg_test_exit();
}
