/* test_drivetrain.c - the flexible drive train against closed forms:
 * the force law (spring, damper, free play whose flanks only push); the
 * first axial mode of the machine in pure vertical motion, every carriage's
 * load m_L = m_head/6 + m_bar + m_carriage against its rotor m_r = j (2 pi /
 * lead)^2 on the spring k: f = sqrt(k (1/m_r + 1/m_L)) / 2 pi, damping ratio
 * c / (2 sqrt(k mu)), mu = m_r m_L / (m_r + m_L); energy kept without
 * dissipation, with and without free play; the lost motion of a slow
 * up-and-down move, the width of the motor-minus-carriage hysteresis
 * b + 2 (f_c + c_visc v) / k while the friction can reverse the train's
 * force, 2 (f_c + c_visc v) / k when gravity's preload keeps the flanks
 * together; and the stability bound of the train's mode under Heun from the
 * complex eigenvalues (the code uses Jury's test on the step matrix). */
#include <complex.h>
#include <math.h>
#include "hg_test.h"
#include "hg_drivetrain.h"
#include "hg_dynamics.h"
#include "hg_errors.h"
#include "hg_plant_hexaglide.h"

#define PI 3.14159265358979323846

static double rotor_mass(const hg_params *p)
{
    double k = 2 * PI / p->lead_m;
    return p->j_rotor_kgm2 * k * k;
}

/* each carriage's share of the machine in pure vertical motion: head and bars translate */
static double vertical_load(const hg_params *p)
{
    return p->m_head_kg / 6 + p->m_bar_kg + p->m_carriage_kg;
}

static void test_force_law(void)
{
    hg_drivetrain_channel c = {3e7, 800, 0};
    CHECK(hg_drivetrain_force(&c, 1e-6, 0) == 30.0 && hg_drivetrain_force(&c, -1e-6, -1e-3) == -30.8,
          "no free play: k d + c dd both ways (30 N at 1 um; -30.8 N at -1 um, -1 mm/s)");
    c.backlash = 20e-6;
    CHECK(hg_drivetrain_force(&c, 9.9e-6, 1.0) == 0.0 && hg_drivetrain_force(&c, -9.9e-6, -1.0) == 0.0,
          "free play of 20 um: no force within +-10 um, whatever the rate");
    CHECK(fabs(hg_drivetrain_force(&c, 11e-6, 0) - 30.0) < 1e-9 && fabs(hg_drivetrain_force(&c, -11e-6, 0) + 30.0) < 1e-9,
          "... k (|d| - b/2) beyond it: +-30 N at +-11 um");
    CHECK(hg_drivetrain_force(&c, 11e-6, -1.0) == 0.0 && hg_drivetrain_force(&c, -11e-6, 1.0) == 0.0,
          "... flanks parting fast: the damper does not pull them (0 N, not 30 - 800 N)");
    CHECK(fabs(hg_drivetrain_energy(&c, 12e-6) - 0.5 * 3e7 * 4e-12) < 1e-18 && hg_drivetrain_energy(&c, 5e-6) == 0.0,
          "energy k (|d| - b/2)^2 / 2 in contact (60 uJ at 12 um), 0 in the play");
    c.k_axial = 0;
    CHECK(hg_drivetrain_rigid(&c), "k_axial 0 is the rigid train");
}

/* Free vertical oscillation: weightless (g 1e-9, the least the table allows), no friction, amplifiers off, every rotor
 * 5 um ahead of its carriage; RK4 at 10 us. Frequency from the upward zero
 * crossings of d = zr - z, damping from the peaks' decay. */
static void test_mode(hg_model_kind kind, double c_axial)
{
    static const double off[6] = {0, 0, 0, 0, 0, 0};
    hg_params p;
    hg_model m;
    hg_data d;
    double dt = 1e-5, prev = 0, t_first = -1, t_last = -1, peak = 0, peak0 = -1, peakn = 0;
    int s, n = 4000, crossings = 0, k, peaks = 0, rising = 0, rc = 0;
    hg_params_default(&p);
    hg_test_frictionless(&p);
    p.g_mps2 = 1e-9;
    p.c_axial_ns_per_m = c_axial;
    if (hg_model_init(&m, &p, kind, 0, 0) || hg_model_set_integrator(&m, HG_INTEGRATOR_RK4) ||
        hg_data_reset(&m, &d)) {
        CHECK(0, "%s: the flexible machine builds", hg_model_name(kind));
        return;
    }
    d.amp_enabled = 0;
    for (k = 0; k < 6; k++)
        d.zr_m[k] = 5e-6;
    prev = 5e-6;
    for (s = 1; s <= n && !rc; s++) {
        double x;
        rc = hg_step(&m, &d, off, dt);
        x = d.zr_m[0] - d.z_m[0];
        if (prev < 0 && x >= 0) {              /* upward crossing, interpolated */
            double t = (s - 1 + -prev / (x - prev)) * dt;
            if (t_first < 0)
                t_first = t;
            t_last = t;
            crossings++;
        }
        if (x > prev)
            rising = 1;
        else if (rising && x < prev) {         /* a peak at the previous step */
            rising = 0;
            if (peak0 < 0)
                peak0 = prev;
            peakn = prev, peaks++;
        }
        peak = fmax(peak, fabs(x));
        prev = x;
    }
    {
        double mr = rotor_mass(&p), ml = vertical_load(&p), mu = mr * ml / (mr + ml);
        double wn = sqrt(p.k_axial_n_per_m / mu), zeta = c_axial / (2 * sqrt(p.k_axial_n_per_m * mu));
        double fd = wn * sqrt(1 - zeta * zeta) / (2 * PI);
        double f = crossings > 1 ? (crossings - 1) / (t_last - t_first) : 0;
        CHECK(rc == 0 && fabs(f / fd - 1) < 2e-3,
              "%s, c_axial %g: vertical axial mode %.2f Hz, closed form sqrt(k (1/m_r + 1/m_L)) / 2 pi = %.2f Hz "
              "(m_r %.2f kg, m_L %.3f kg; %d periods)", hg_model_name(kind), c_axial, f, fd, mr, ml, crossings - 1);
        if (c_axial > 0) {
            /* peaks one damped period apart: ln(A0 / An) = n 2 pi zeta / sqrt(1 - zeta^2) */
            double z = log(peak0 / peakn) / (peaks - 1) / (2 * PI);
            z = z / sqrt(1 + z * z);
            CHECK(peaks > 3 && fabs(z / zeta - 1) < 0.02,
                  "%s: damping ratio %.4f from %d peaks, closed form c / (2 sqrt(k mu)) = %.4f",
                  hg_model_name(kind), z, peaks, zeta);
        } else {
            CHECK(peaks > 3 && fabs(peakn / peak0 - 1) < 1e-3,
                  "%s, undamped: the last peak %.4f um of the first %.4f um", hg_model_name(kind),
                  1e6 * peakn, 1e6 * peak0);
        }
    }
}

/* Energy without dissipation: kick the machine with asymmetric volts, then
 * coast with amplifiers off under gravity; max |E - E0| / E_kin0 over 50 ms. */
static double energy_error(double backlash, double dt, double *ek0)
{
    static const double kick[6] = {0.6, -0.4, 0.3, -0.5, 0.4, -0.2};
    static const double off[6] = {0, 0, 0, 0, 0, 0};
    hg_params p;
    hg_model m;
    hg_data d;
    double t, v, e0, worst = 0;
    long s, n = (long)(0.05 / dt + 0.5);
    hg_params_default(&p);
    hg_test_frictionless(&p);
    p.c_axial_ns_per_m = 0;
    p.backlash_m = backlash;
    if (hg_model_init(&m, &p, HG_MODEL_REDUCED_CARTESIAN, 0, 0) ||
        hg_model_set_integrator(&m, HG_INTEGRATOR_RK4) || hg_data_reset(&m, &d))
        return INFINITY;
    for (s = 0; s < n; s++)
        if (hg_step(&m, &d, kick, dt))
            return INFINITY;
    d.amp_enabled = 0;
    hg_energy(&m, &d, &t, &v);
    e0 = t + v;
    *ek0 = t;
    for (s = 0; s < n; s++) {
        if (hg_step(&m, &d, off, dt))
            return INFINITY;
        hg_energy(&m, &d, &t, &v);
        worst = fmax(worst, fabs(t + v - e0));
    }
    return worst / *ek0;
}

static void test_energy(double backlash)
{
    double ek, e1 = energy_error(backlash, 2e-5, &ek), e2 = energy_error(backlash, 1e-5, &ek);
    CHECK(e1 < 1e-5 && e2 < e1,
          "flexible trains%s, no dissipation: coasting 50 ms under gravity, max |dE| / T0 = %.2e at 20 us, "
          "%.2e at 10 us (T0 = %.4f J)", backlash > 0 ? " with 20 um of free play" : "", e1, e2, ek);
}

/* Up 2 mm at v and back down, each rotor servoed by the test (PD on the
 * motor's position, feed-forward of its load), RK4 at 0.1 ms: the
 * steady offsets zr - z of the two directions, averaged over the middle of
 * each move; their difference is the hysteresis width. */
static double hysteresis_width(double f_coulomb, double backlash, double v, double *up, double *down)
{
    hg_params p;
    hg_model m;
    hg_data d;
    double dt = 1e-4, t_move = 0.002 / v, sum_up = 0, sum_dn = 0, load;
    long s, n = (long)(2 * t_move / dt + 0.5), nu = 0, nd = 0;
    int k;
    hg_params_default(&p);
    load = p.g_mps2 * (p.m_head_kg + 6 * (p.m_bar_kg + p.m_carriage_kg)) / 6;
    p.f_coulomb_n = p.f_static_n = f_coulomb;   /* no Stribeck band: the friction is f_c + c v */
    p.backlash_m = backlash;
    if (hg_model_init(&m, &p, HG_MODEL_REDUCED_CARTESIAN, 0, 0) ||
        hg_model_set_integrator(&m, HG_INTEGRATOR_RK4) || hg_data_reset(&m, &d))
        return NAN;
    for (s = 0; s < n; s++) {
        double t = s * dt, dir = t < t_move ? 1.0 : -1.0;
        double cmd = t < t_move ? v * t : v * (2 * t_move - t), volts[6];
        double ff = load + dir * (f_coulomb + p.c_visc_ns_per_m * v);   /* weight share and friction */
        for (k = 0; k < 6; k++)
            volts[k] = (ff + 2e6 * (cmd - d.zr_m[k]) + 4e4 * (dir * v - d.zrd_mps[k])) / m.force_per_volt_n;
        if (hg_step(&m, &d, volts, dt))
            return NAN;
        if (fabs(t - 0.5 * t_move) < 0.25 * t_move)
            sum_up += d.zr_m[0] - d.z_m[0], nu++;
        if (fabs(t - 1.5 * t_move) < 0.25 * t_move)
            sum_dn += d.zr_m[0] - d.z_m[0], nd++;
    }
    *up = sum_up / nu;
    *down = sum_dn / nd;
    return *up - *down;
}

static void test_lost_motion(void)
{
    hg_params p;
    double v = 0.001, b = 50e-6, up, dn, w, count, want, load;
    hg_params_default(&p);
    count = p.lead_m / p.counts_per_rev;
    load = 9.81 * (p.m_head_kg + 6 * (p.m_bar_kg + p.m_carriage_kg)) / 6;
    /* friction above the weight's share: the train's force turns over, the free play shows */
    w = hysteresis_width(100.0, b, v, &up, &dn);
    want = b + 2 * (100.0 + p.c_visc_ns_per_m * v) / p.k_axial_n_per_m;
    CHECK(fabs(w - want) < count,
          "f_c 100 N > W/6 %.1f N, backlash 50 um, 1 mm/s: lost motion %.3f um = b + 2 (f_c + c v) / k "
          "= %.3f um within one count (%.1f um); offsets %.3f / %.3f um", load, 1e6 * w, 1e6 * want,
          1e6 * count, 1e6 * up, 1e6 * dn);
    /* friction below it: gravity keeps the flanks together, the free play stays hidden */
    w = hysteresis_width(40.0, b, v, &up, &dn);
    want = 2 * (40.0 + p.c_visc_ns_per_m * v) / p.k_axial_n_per_m;
    CHECK(fabs(w - want) < count && up > 0 && dn > 0,
          "f_c 40 N < W/6: the weight preloads the train, lost motion %.3f um = 2 (f_c + c v) / k = %.3f um "
          "(no backlash in it; both offsets on one flank: %.3f / %.3f um)", 1e6 * w, 1e6 * want, 1e6 * up,
          1e6 * dn);
}

/* Heun's longest stable step for the train's mode: the reduced mass of the
 * rotor and the lightest carriage (m_carriage + m_end) on k_axial and
 * c_axial; |1 + z + z^2 / 2| <= 1 at both eigenvalues z = lambda h. */
static double heun_bound(double mass, double k, double c)
{
    double complex lam = (-c + csqrt(c * c - 4 * mass * k + 0 * I)) / (2 * mass);
    double lo = 0, hi = 1e-2;
    int i;
    for (i = 0; i < 200; i++) {
        double h = 0.5 * (lo + hi);
        double complex z = lam * h;
        if (cabs(1 + z + z * z / 2) <= 1)
            lo = h;
        else
            hi = h;
    }
    return lo;
}

static void test_stability(void)
{
    hg_params p;
    hg_stability st;
    const char *field = 0, *why = 0;
    double m_end, mu, want;
    int rc;
    hg_params_default(&p);
    m_end = 2 * p.i_bar_kgm2 / (p.geo.l_m * p.geo.l_m) - 0.5 * p.m_bar_kg;
    mu = 1 / (1 / rotor_mass(&p) + 1 / (p.m_carriage_kg + m_end));
    want = heun_bound(mu, p.k_axial_n_per_m, p.c_axial_ns_per_m);
    rc = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, 1, &st);
    CHECK(rc != 0 && st.param && strcmp(st.param, "k_axial") == 0 && fabs(st.dt_max_s / want - 1) < 1e-3,
          "default trains under Heun at 1 ms, one step: refused naming %s, longest step %.3f us, closed form "
          "(complex eigenvalues of the train's mode, mu %.3f kg) %.3f us", st.param ? st.param : "(none)",
          1e6 * st.dt_max_s, mu, 1e6 * want);
    rc = hg_stability_check(&p, HG_INTEGRATOR_HEUN, 1e-3, 1, 64, &st);
    CHECK(rc == 0 && st.substeps == (unsigned)ceil(1e-3 / want),
          "... with up to 64 substeps: %u, the least with 1 ms / n <= %.3f us", st.substeps, 1e6 * want);
    hg_params_default(&p);
    p.k_axial_n_per_m = 0;
    p.backlash_m = 20e-6;
    rc = hg_params_check(&p, &field, &why);
    CHECK(rc != 0 && field && strcmp(field, "backlash") == 0,
          "backlash on a rigid train refused: %s: %s", field ? field : "(none)", why ? why : "");
    hg_params_default(&p);
    p.backlash_m = 1.0;
    rc = hg_params_check(&p, &field, &why);
    CHECK(rc != 0 && field && strcmp(field, "backlash") == 0,
          "backlash of 1 m refused: %s: %s", field ? field : "(none)", why ? why : "");
    hg_params_default(&p);
    p.k_axial_n_per_m = -1;
    rc = hg_params_check(&p, &field, &why);
    CHECK(rc != 0 && field && strcmp(field, "k_axial") == 0, "k_axial < 0 refused: %s: %s",
          field ? field : "(none)", why ? why : "");
}

int main(void)
{
    int kind;
    test_force_law();
    for (kind = 0; kind < HG_MODEL_COUNT; kind++)
        test_mode((hg_model_kind)kind, 0.0);
    test_mode(HG_MODEL_REDUCED_CARTESIAN, 800.0);
    test_energy(0.0);
    test_energy(20e-6);
    test_lost_motion();
    test_stability();
    return hg_test_exit();
}
