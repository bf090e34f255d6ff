/* test_trainid.c - hg_trainid_response (the drive trains' small motion that
 * identify's c_axial fit steps) against closed forms of two-mass systems:
 * with a diagonal mass matrix each drive is its own rotor m_r on a spring k
 * and damper c against a carriage m_L; free vibration at
 * sqrt(k (1/m_r + 1/m_L)) / 2 pi with the log decrement of
 * zeta = c / (2 sqrt(k mu)), mu = m_r m_L / (m_r + m_L); a constant motor
 * force F accelerating both at F / (m_r + m_L) with the spring deflected by
 * F m_L / ((m_r + m_L) k); the refusals. */
#include "hg_test.h"
#include "hg_trainid.h"
#include "hg_errors.h"

#define NP 2000
#define NS 16

static double u[NP * NS * 6], motor[NP * 6], load[NP * 6], mass[36];

static void diagonal(const double *m)
{
    int i;
    memset(mass, 0, sizeof mass);
    for (i = 0; i < 6; i++)
        mass[7 * i] = m[i];
}

int main(void)
{
    const double dt = 1e-3, PI = 3.14159265358979323846;
    hg_trainid_params p;
    double x[HG_TRAINID_NSTATE], m[6];
    int k, rc;
    for (k = 0; k < 6; k++) {          /* six different drives */
        p.k[k] = 2e7 + 2e6 * k;
        p.c[k] = 500.0 + 150.0 * k;
        p.m_rotor[k] = 52.0 - k;
        p.c_visc[k] = 0.0;
        m[k] = p.m_rotor[k] + 6.0 + 0.5 * k;   /* the rigid model's: rotor + carriage */
    }
    diagonal(m);
    /* free vibration from a deflection of 10 um, sampled every 0.1 ms (about 30 samples a period) */
    memset(u, 0, sizeof u);
    memset(x, 0, sizeof x);
    for (k = 0; k < 6; k++)
        x[k] = 1e-5;
    rc = hg_trainid_response(&p, HG_INTEGRATOR_RK4, NS, 1e-4, NP, mass, NP, u, x, motor, load);  /* one mass matrix */
    CHECK(rc == 0, "free vibration: rc %d", rc);
    for (k = 0; k < 6; k++) {
        double mL = m[k] - p.m_rotor[k], mu = p.m_rotor[k] * mL / (p.m_rotor[k] + mL);
        double fn = sqrt(p.k[k] / mu) / (2 * PI), zeta = p.c[k] / (2 * sqrt(p.k[k] * mu));
        double fd = fn * sqrt(1 - zeta * zeta), t0 = -1, t1 = -1, a0 = -1, a1 = -1;
        int n, ups = 0, peaks = 0, last = 0;
        for (n = 1; n + 1 < NP; n++) {
            double d0 = motor[6 * (n - 1) + k] - load[6 * (n - 1) + k], d1 = motor[6 * n + k] - load[6 * n + k];
            double d2 = motor[6 * (n + 1) + k] - load[6 * (n + 1) + k];
            if (d0 < 0 && d1 >= 0) {           /* an upward zero crossing (linear interpolation) */
                double t = (n - 1 + d0 / (d0 - d1)) * 1e-4;
                if (++ups == 1)
                    t0 = t;
                t1 = t;
                last = ups;
            }
            if (d1 > d0 && d1 >= d2 && d1 > 0) {   /* a peak: the parabola through three samples */
                double pk = d1 + 0.125 * (d2 - d0) * (d2 - d0) / (2 * d1 - d0 - d2);
                if (++peaks == 2)
                    a0 = pk;
                if (peaks == 22)
                    a1 = pk;
            }
        }
        CHECK(ups >= 20 && fabs((last - 1) / (t1 - t0) / fd - 1) < 1e-3,
              "drive %d: free vibration at %.2f Hz, sqrt(k (1/m_r + 1/m_L)) sqrt(1 - zeta^2) / 2 pi = %.2f Hz",
              k, (last - 1) / (t1 - t0), fd);
        {
            double want = exp(-zeta * 2 * PI * fn * 20 / fd);
            CHECK(a0 > 0 && a1 > 0 && fabs(a1 / a0 / want - 1) < 0.01, "drive %d: decay over twenty periods %.4f, "
                  "exp(-zeta w_n 20 T_d) = %.4f (zeta %.4f, c %.0f N s/m)", k, a1 / a0, want, zeta, p.c[k]);
        }
    }
    /* a constant force from rest: both accelerate at F / (m_r + m_L), the spring at F m_L / ((m_r + m_L) k);
     * critically damped (c = 2 sqrt(k mu)) so it settles */
    for (k = 0; k < 6; k++) {
        double mL = m[k] - p.m_rotor[k], mu = p.m_rotor[k] * mL / (p.m_rotor[k] + mL);
        p.c[k] = 2 * sqrt(p.k[k] * mu);
    }
    for (rc = 0; rc < NP * NS; rc++)
        for (k = 0; k < 6; k++)
            u[6 * rc + k] = 100.0 * (k + 1);
    memset(x, 0, sizeof x);
    rc = hg_trainid_response(&p, HG_INTEGRATOR_HEUN, NS, dt, 200, mass, 200, u, x, motor, load);
    CHECK(rc == 0, "constant force (Heun): rc %d", rc);
    for (k = 0; k < 6; k++) {
        double mL = m[k] - p.m_rotor[k], F = 100.0 * (k + 1), t = 0.2;
        double d = motor[6 * 199 + k] - load[6 * 199 + k], dwant = F * mL / (m[k] * p.k[k]);
        double xwant = 0.5 * F / m[k] * t * t;          /* the centre of mass */
        double xc = (p.m_rotor[k] * motor[6 * 199 + k] + mL * load[6 * 199 + k]) / m[k];
        CHECK(fabs(d / dwant - 1) < 1e-3, "drive %d: deflection %.5g m under %g N, F m_L / ((m_r + m_L) k) = %.5g m",
              k, d, F, dwant);
        CHECK(fabs(xc / xwant - 1) < 1e-6, "drive %d: centre of mass at %.6g m, F t^2 / (2 (m_r + m_L)) = %.6g m",
              k, xc, xwant);
    }
    /* refusals */
    memset(x, 0, sizeof x);
    p.k[2] = 0.0;
    rc = hg_trainid_response(&p, HG_INTEGRATOR_RK4, NS, dt, 10, mass, 10, u, x, motor, load);
    CHECK(rc == HG_ERR_BAD_PARAM, "a stiffness of 0 refused (rc %d)", rc);
    p.k[2] = 2e7;
    p.m_rotor[3] = m[3] + 1.0;
    rc = hg_trainid_response(&p, HG_INTEGRATOR_RK4, NS, dt, 10, mass, 10, u, x, motor, load);
    CHECK(rc == HG_ERR_SINGULAR_MASS, "a rotor heavier than the rigid model's carriage mass refused (rc %d)", rc);
    p.m_rotor[3] = 49.0;
    rc = hg_trainid_response(&p, HG_INTEGRATOR_RK4, 0, dt, 10, mass, 10, u, x, motor, load);
    CHECK(rc == HG_ERR_BAD_PARAM, "no substeps refused (rc %d)", rc);
    return hg_test_exit();
}
