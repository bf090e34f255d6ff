/* hg_params.c - defaults, by-name access and validation of hg_params. */
#include <stddef.h>
#include "hg_math.h"
#include "hg_string.h"
#include "hg_params.h"
#include "hg_errors.h"
#include "hg_guard.h"
#include "hg_units.h"

#define F(field) offsetof(hg_params, field)

static const hg_param_info table[] = {
    {"l", "m", "bar length", F(geo.l_m), "l", "mm", 1000.0, "L"},
    {"lb", "m", "machine axis to guide plane", F(geo.lb_m), "lb", "mm", 1000.0, "LB"},
    {"e", "m", "half spacing of a post's guides", F(geo.e_m), "e", "mm", 1000.0, "E"},
    {"lp", "m", "head joint radius", F(geo.lp_m), "lp", "mm", 1000.0, "LP"},
    {"cone_carriage", "rad", "bar joint range in the carriage (cone half-angle from HOME)", F(geo.cone_carriage_rad), "cone-carriage", "deg", HG_DEG_PER_RAD, "CONE_CARRIAGE"},
    {"cone_head", "rad", "bar joint range in the head (cone half-angle from HOME)", F(geo.cone_head_rad), "cone-head", "deg", HG_DEG_PER_RAD, "CONE_HEAD"},
    {"d_bar", "m", "bar diameter (bars touch when their axes come closer)", F(geo.d_bar_m), "d-bar", "mm", 1000.0, "D_BAR"},
    {"tool_d", "m", "tool tip below Op", F(tool_d_m), "tool-d", "mm", 1000.0, 0},
    {"g", "m/s^2", "gravity", F(g_mps2), "g", "m/s^2", 1.0, 0},
    {"m_head", "kg", "head mass", F(m_head_kg), "m-head", "kg", 1.0, 0},
    {"head_com", "m", "head COM below Op", F(head_com_m), "head-com", "mm", 1000.0, 0},
    {"i_head_xx", "kg m^2", "head inertia about COM, x", F(i_head_xx_kgm2), "i-head-xx", "kg m^2", 1.0, 0},
    {"i_head_yy", "kg m^2", "head inertia about COM, y", F(i_head_yy_kgm2), "i-head-yy", "kg m^2", 1.0, 0},
    {"i_head_zz", "kg m^2", "head inertia about COM, z", F(i_head_zz_kgm2), "i-head-zz", "kg m^2", 1.0, 0},
    {"m_bar", "kg", "bar mass", F(m_bar_kg), "m-bar", "kg", 1.0, 0},
    {"i_bar", "kg m^2", "bar transverse inertia about carriage joint", F(i_bar_kgm2), "i-bar", "kg m^2", 1.0, 0},
    {"m_carriage", "kg", "carriage mass", F(m_carriage_kg), "m-carriage", "kg", 1.0, 0},
    {"lead", "m/rev", "ball-screw lead", F(lead_m), "lead", "mm/rev", 1000.0, 0},
    {"j_rotor", "kg m^2", "rotor + screw inertia", F(j_rotor_kgm2), "j-rotor", "kg m^2", 1.0, 0},
    {"kt", "N m/A", "motor torque constant (= back-EMF constant, V s/rad)", F(kt_nm_per_a), "kt", "N m/A", 1.0, 0},
    {"r_winding", "ohm", "motor winding resistance", F(r_winding_ohm), "r-winding", "ohm", 1.0, 0},
    {"l_winding", "H", "motor winding inductance", F(l_winding_h), "l-winding", "H", 1.0, 0},
    {"amp_mode", "1", "amplifier mode: 0 torque (current), 1 velocity", F(amp_mode), "amp-mode", "1", 1.0, 0},
    {"ka", "A/V", "torque mode: amplifier gain", F(ka_a_per_v), "ka", "A/V", 1.0, 0},
    {"i_max", "A", "amplifier current limit", F(i_max_a), "i-max", "A", 1.0, 0},
    {"v_bus", "V", "amplifier supply (bus) voltage", F(v_bus_v), "v-bus", "V", 1.0, 0},
    {"v_rated", "m/s", "velocity mode: carriage speed at +10 V", F(v_rated_mps), "v-rated", "mm/s", 1000.0, 0},
    {"kp_vel", "A s/m", "velocity mode: velocity-loop proportional gain", F(kp_vel_as_per_m), "kp-vel", "A s/m", 1.0, 0},
    {"ki_vel", "A/m", "velocity mode: velocity-loop integral gain", F(ki_vel_a_per_m), "ki-vel", "A/m", 1.0, 0},
    {"c_visc", "N s/m", "viscous friction per carriage", F(c_visc_ns_per_m), "c-visc", "N s/m", 1.0, 0},
    {"f_coulomb", "N", "sliding (Coulomb) friction per carriage", F(f_coulomb_n), "f-coulomb", "N", 1.0, 0},
    {"f_static", "N", "breakaway (static) friction per carriage", F(f_static_n), "f-static", "N", 1.0, 0},
    {"v_stribeck", "m/s", "Stribeck speed (sliding friction falls from f_static to f_coulomb)", F(v_stribeck_mps), "v-stribeck", "mm/s", 1000.0, 0},
    {"stop_min", "m", "hard stop, bottom", F(stop_min_m), "stop-min", "mm", 1000.0, 0},
    {"stop_max", "m", "hard stop, top", F(stop_max_m), "stop-max", "mm", 1000.0, 0},
    {"k_stop", "N/m", "hard-stop stiffness", F(k_stop_n_per_m), "k-stop", "N/m", 1.0, 0},
    {"c_stop", "N s/m", "hard-stop damping", F(c_stop_ns_per_m), "c-stop", "N s/m", 1.0, 0},
    {"limit_min", "m", "limit switch, bottom", F(limit_min_m), "limit-min", "mm", 1000.0, 0},
    {"limit_max", "m", "limit switch, top", F(limit_max_m), "limit-max", "mm", 1000.0, 0},
    {"home_switch", "m", "home switch on at or above", F(home_switch_m), "home-switch", "mm", 1000.0, 0},
    {"counts_per_rev", "1/rev", "encoder counts per motor revolution", F(counts_per_rev), "counts-per-rev", "1/rev", 1.0, 0},
    {"k_axial", "N/m", "drive train: axial stiffness motor to carriage (0: rigid)", F(k_axial_n_per_m), "k-axial", "N/m", 1.0, 0},
    {"c_axial", "N s/m", "drive train: axial damping", F(c_axial_ns_per_m), "c-axial", "N s/m", 1.0, 0},
    {"backlash", "m", "drive train: total lost motion", F(backlash_m), "backlash", "mm", 1000.0, 0},
};

#undef F

typedef char hg_params_table_fits[(sizeof table / sizeof table[0] <= HG_PARAMS_MAX) ? 1 : -1];

double hg_hold_current(const hg_params *p)
{
    double weight = p->g_mps2 * (p->m_head_kg + 6.0 * (p->m_bar_kg + p->m_carriage_kg));
    return weight / 6.0 / (p->kt_nm_per_a * 2.0 * HG_PI / p->lead_m);
}

const char *hg_params_hal_name(const char *name)
{
    int n;
    const hg_param_info *t = hg_params_table(&n);
    int i = hg_param_find(t, n, name);
    return i >= 0 ? t[i].hal_name : name;
}

int hg_param_is_geometry(int i)
{
    int n;
    const hg_param_info *t = hg_params_table(&n);
    return i >= 0 && i < n && t[i].offset < sizeof(hg_geometry);
}

void hg_params_default(hg_params *p)
{
    memset(p, 0, sizeof *p);
    p->geo.l_m = 1.000;
    p->geo.lb_m = 0.484;
    p->geo.e_m = 0.068254;
    p->geo.lp_m = 0.073085;
    /* assumed hardware (docs/model.md): spherical carriage joints of +-25 deg,
     * cardan head joints of +-40 deg, bars of 30 mm steel tube */
    p->geo.cone_carriage_rad = 25.0 / HG_DEG_PER_RAD;
    p->geo.cone_head_rad = 40.0 / HG_DEG_PER_RAD;
    p->geo.d_bar_m = 0.030;
    p->tool_d_m = 0.09;
    p->g_mps2 = 9.81;
    p->m_head_kg = 6.697;
    p->head_com_m = 0.035572;
    p->i_head_xx_kgm2 = 0.028319;
    p->i_head_yy_kgm2 = 0.028319;
    p->i_head_zz_kgm2 = 0.038045;
    p->m_bar_kg = 2.9369;
    p->i_bar_kgm2 = 1.0435;
    p->m_carriage_kg = 2.867;
    p->lead_m = 0.010;
    p->j_rotor_kgm2 = 1.3168e-4;
    p->kt_nm_per_a = 0.51;
    p->ka_a_per_v = 0.8;
    p->i_max_a = 8.0;
    /* assumed (docs/model.md): an 80 V PWM servo amplifier, a 2 ohm, 5 mH winding */
    p->r_winding_ohm = 2.0;
    p->l_winding_h = 0.005;
    p->amp_mode = 0.0;
    p->v_bus_v = 80.0;
    /* velocity mode: 10 V = 200 mm/s, a velocity loop of about 30 Hz on the carriage */
    p->v_rated_mps = 0.2;
    p->kp_vel_as_per_m = 35.0;
    p->ki_vel_a_per_m = 1600.0;
    p->c_visc_ns_per_m = 5665.6;
    /* assumed (docs/model.md): preloaded ball screw and guides */
    p->f_coulomb_n = 40.0;
    p->f_static_n = 50.0;
    p->v_stribeck_mps = 0.002;
    p->stop_min_m = -0.260;
    p->stop_max_m = 0.260;
    p->k_stop_n_per_m = 5e6;      /* static penetration at the 8 A clamp ~0.5 mm; k dt^2 / m ~ 0.09 at 1 ms */
    p->c_stop_ns_per_m = 2e4;
    p->limit_min_m = -0.250;
    p->limit_max_m = 0.250;
    p->home_switch_m = 0.005;
    p->counts_per_rev = 10000.0;
    /* assumed hardware (docs/model.md): a 16 x 10 mm ground screw, a preloaded
     * nut, angular-contact support bearings and a bellows coupling in series:
     * 30 N/um, the first axial mode at HOME near 353 Hz, damped 3% */
    p->k_axial_n_per_m = 3.0e7;
    p->c_axial_ns_per_m = 800.0;
    p->backlash_m = 0.0;
}

const hg_param_info *hg_params_table(int *count)
{
    if (count)
        *count = (int)(sizeof table / sizeof table[0]);
    return table;
}

double *hg_params_field(hg_params *p, const char *name)
{
    int n;
    const hg_param_info *t = hg_params_table(&n);
    int i = hg_param_find(t, n, name);
    return i >= 0 ? (double *)((char *)p + t[i].offset) : 0;
}

double *hg_params_at(hg_params *p, int i)
{
    int n;
    const hg_param_info *t = hg_params_table(&n);
    return i >= 0 && i < n ? (double *)((char *)p + t[i].offset) : 0;
}

double hg_params_get(const hg_params *p, int i)
{
    const double *f = hg_params_at((hg_params *)p, i); /* read only */
    return f ? *f : 0.0;
}

int hg_params_set(hg_params *p, const char *name, double value)
{
    double *f = hg_params_field(p, name);
    if (!f || !isfinite(value))
        return HG_ERR_BAD_PARAM;
    *f = value;
    return HG_OK;
}

/* The geometry rules, in order; a rule that depends on a failed field is
 * skipped (it would only repeat the cause). */
static void geometry_rules(const hg_geometry *g, hg_check *r)
{
    if (!(isfinite(g->l_m) && g->l_m > 0))
        hg_check_refuse(r, "l", "must be a positive finite length");
    if (!(isfinite(g->lb_m) && g->lb_m > 0))
        hg_check_refuse(r, "lb", "must be a positive finite length");
    /* e = 0: a post's two bars start at one guide point, touching there whatever d_bar */
    if (!hg_check_failed(r, "lb") && !(isfinite(g->e_m) && g->e_m > 0 && g->e_m < g->lb_m))
        hg_check_refuse(r, "e", "must be finite, > 0 (at 0 a post's two bars meet at one guide point) and smaller "
                                "than lb");
    if (!hg_check_failed(r, "lb") && !(isfinite(g->lp_m) && g->lp_m > 0 && g->lp_m < g->lb_m))
        hg_check_refuse(r, "lp", "must be positive and smaller than lb");
    if (!hg_check_failed(r, "l") && !hg_check_failed(r, "lb") && !hg_check_failed(r, "lp") && !(g->l_m > g->lb_m - g->lp_m))
        hg_check_refuse(r, "l", "bars too short to reach the head: need l > lb - lp");
    /* at HOME every bar is at 0 in both joints, but an angle's rounding there is about 1e-8 rad:
     * a cone of a degree at least (a joint that turns less could not move the head) */
    if (!(isfinite(g->cone_carriage_rad) && g->cone_carriage_rad >= HG_CONE_MIN_RAD &&
          g->cone_carriage_rad < HG_PI / 2))
        hg_check_refuse(r, "cone_carriage", "must lie between 1 and 90 deg (0.017453 and 1.570796 rad)");
    if (!(isfinite(g->cone_head_rad) && g->cone_head_rad >= HG_CONE_MIN_RAD && g->cone_head_rad < HG_PI / 2))
        hg_check_refuse(r, "cone_head", "must lie between 1 and 90 deg (0.017453 and 1.570796 rad)");
    if (!(isfinite(g->d_bar_m) && g->d_bar_m > 0))
        hg_check_refuse(r, "d_bar", "must be a positive finite length");
    if (hg_check_any(r))
        return;                        /* the rules below need a valid geometry */
    /* a bar dips below the head's joint plane when its angle in the head
     * joint exceeds 90 deg less its tilt at HOME: the range must exclude that */
    if (!(g->cone_head_rad + asin((g->lb_m - g->lp_m) / g->l_m) < HG_PI / 2))
        hg_check_refuse(r, "cone_head", "plus the bars' tilt at HOME, asin((lb - lp) / l), must stay below 90 deg "
                               "(a bar would touch the head's joint plane)");
    if (!(g->d_bar_m < hg_guard_home_clearance(g)))
        hg_check_refuse(r, "d_bar", "must be below the closest distance between two bar axes at HOME, set by "
                           "l, lb, e and lp (the machine could not stand at HOME)");   /* HAL: within 254 chars */
}

/* Copy the first failure to the caller's outputs; HG_OK or HG_ERR_BAD_PARAM. */
static int first_failure(const hg_check *r, const char **bad_field, const char **why)
{
    if (!r->first_field)
        return HG_OK;
    if (bad_field)
        *bad_field = r->first_field;
    if (why)
        *why = r->first_why;
    return HG_ERR_BAD_PARAM;
}

/* A collector over this table. */
static void check_start(hg_check *r, const char **why)
{
    int n;
    const hg_param_info *t = hg_params_table(&n);
    hg_check_init(r, t, n, why);
}

int hg_geometry_check(const hg_geometry *g, const char **bad_field, const char **why)
{
    hg_check r;
    hg_params p;
    int i, n;
    const hg_param_info *t = hg_params_table(&n);
    check_start(&r, 0);
    geometry_rules(g, &r);
    /* the whole set's bound (params_rules) on the geometry alone, so that the
     * kinematics refuse what the board refuses (l = 1e300 mm passed the rules
     * above, and the forward kinematics then failed without naming it) */
    hg_params_default(&p);
    p.geo = *g;
    for (i = 0; i < n; i++)
        if (hg_param_is_geometry(i) && !hg_check_failed(&r, t[i].name) &&
            !(fabs(hg_params_get(&p, i)) < HG_PARAM_MAX_ABS))
            hg_check_refuse(&r, t[i].name, hg_why_max_abs);
    return first_failure(&r, bad_field, why);
}

void hg_geometry_setting_init(hg_geometry_setting *s)
{
    memset(s, 0, sizeof *s);
}

int hg_geometry_take(hg_geometry_setting *s, const double hal[HG_PARAMS_MAX], const char **field, const char **why,
                     int *set_entry)
{
    hg_params p;
    int i, n, set = -1, same = s->valid;
    const hg_param_info *t = hg_params_table(&n);
    *field = "";
    *why = "";
    *set_entry = -1;
    for (i = 0; i < n; i++)
        if (hg_param_is_geometry(i)) {
            double now = hal[i];
            int kept = hg_param_same(now, s->given[i]);
            if (!kept && set < 0 && s->valid)
                set = i;                 /* the first entry set since the last check */
            same = same && kept;
            s->given[i] = now;
        }
    if (same)
        return 0;                        /* unchanged: s->rc stands */
    hg_params_default(&p);
    for (i = 0; i < n; i++)
        if (hg_param_is_geometry(i))
            *hg_params_at(&p, i) = s->given[i] / t[i].hal_scale;
    s->geo = p.geo;
    s->fingerprint = hg_geometry_fingerprint(&s->geo);
    s->valid = 1;
    s->rc = hg_geometry_check(&s->geo, field, why);
    if (s->rc == HG_OK)
        return 0;
    if (set >= 0 && strcmp(t[set].name, *field) != 0)
        *set_entry = set;
    return 1;
}

/* Every rule of the whole set, in order (geometry first). */
static void params_rules(const hg_params *p, hg_check *r)
{
    /* fields that must be finite and strictly positive */
    static const char *const positive[] = {
        "g", "m_head", "i_head_xx", "i_head_yy", "i_head_zz", "m_bar",
        "i_bar", "m_carriage", "lead", "ka", "kt", "i_max", "k_stop",
        "counts_per_rev", "r_winding", "l_winding", "v_bus", "v_rated", "v_stribeck",
    };
    /* fields that must be finite and >= 0 */
    static const char *const nonneg[] = {
        "tool_d", "head_com", "j_rotor", "c_visc", "f_coulomb", "f_static", "c_stop",
        "kp_vel", "ki_vel", "k_axial", "c_axial", "backlash",
    };
    unsigned i;
    int n;
    hg_params *q = (hg_params *)p; /* read-only use of the by-name lookup */
    const hg_param_info *t = hg_params_table(&n);
    geometry_rules(&p->geo, r);
    /* no machine needs a number of 1e9 SI units; beyond it products overflow */
    for (i = 0; i < (unsigned)n; i++) {
        double v = *hg_params_field(q, t[i].name);
        if (!(fabs(v) < HG_PARAM_MAX_ABS))
            hg_check_refuse(r, t[i].name, hg_why_max_abs);
    }
    for (i = 0; i < sizeof positive / sizeof positive[0]; i++) {
        double v = *hg_params_field(q, positive[i]);
        if (!(isfinite(v) && v >= HG_PARAM_MIN_POSITIVE))
            hg_check_refuse(r, positive[i], hg_why_min_positive);
    }
    for (i = 0; i < sizeof nonneg / sizeof nonneg[0]; i++) {
        double v = *hg_params_field(q, nonneg[i]);
        if (!(isfinite(v) && v >= 0))
            hg_check_refuse(r, nonneg[i], "must be finite and >= 0");
    }
    /* the head's COM lies in the head, which hangs between the bars: a few bar lengths below Op at
     * most (beyond 1e6 m its m_head head_com^2 swamped the rest of the mass matrix: the step failed,
     * "not positive definite", without naming head_com) */
    if (!hg_check_failed(r, "head_com") && !hg_check_failed(r, "l") &&
        !(p->head_com_m <= HG_HEAD_COM_MAX_BARS * p->geo.l_m))
        hg_check_refuse(r, "head_com", "must be at most 2 bar lengths (2 l) below Op: the head's centre of mass "
                                       "lies in the head, between the bars");
    if (!hg_check_failed(r, "counts_per_rev") && !(p->counts_per_rev == floor(p->counts_per_rev)))
        hg_check_refuse(r, "counts_per_rev", "must be a whole number of counts");
    /* a lumped bar needs m_end > 0 and m_mid >= 0: m_bar l^2 / 4 <= i_bar < m_bar l^2 / 2 */
    if (!hg_check_failed(r, "i_bar") && !hg_check_failed(r, "m_bar") && !hg_check_failed(r, "l") &&
        !(p->i_bar_kgm2 >= p->m_bar_kg * p->geo.l_m * p->geo.l_m / 4 &&
          p->i_bar_kgm2 < p->m_bar_kg * p->geo.l_m * p->geo.l_m / 2))
        hg_check_refuse(r, "i_bar", "must lie in [m_bar l^2/4, m_bar l^2/2) for a bar with its COM at mid-length "
                           "(a new l or m_bar needs an i_bar in that range too: a uniform bar's is m_bar l^2/3)");
    if (!hg_check_failed(r, "limit_min") && !(isfinite(p->stop_min_m) && p->stop_min_m < p->limit_min_m))
        hg_check_refuse(r, "stop_min", "must be finite and below limit_min");
    if (!(isfinite(p->limit_min_m) && p->limit_min_m < 0))
        hg_check_refuse(r, "limit_min", "must be finite and below HOME (0)");
    if (!(isfinite(p->limit_max_m) && p->limit_max_m > 0))
        hg_check_refuse(r, "limit_max", "must be finite and above HOME (0)");
    if (!hg_check_failed(r, "limit_max") && !(isfinite(p->stop_max_m) && p->stop_max_m > p->limit_max_m))
        hg_check_refuse(r, "stop_max", "must be finite and above limit_max");
    if (!(p->amp_mode == 0.0 || p->amp_mode == 1.0))
        hg_check_refuse(r, "amp_mode", "must be 0 (torque mode) or 1 (velocity mode)");
    if (!hg_check_failed(r, "f_static") && !hg_check_failed(r, "f_coulomb") && !(p->f_static_n >= p->f_coulomb_n))
        hg_check_refuse(r, "f_static", "must be at least f_coulomb (breakaway below the sliding force)");
    /* the bus must drive, at standstill, the current that holds the machine at HOME */
    if (!hg_check_failed(r, "v_bus") && !hg_check_failed(r, "r_winding") && !hg_check_failed(r, "kt") && !hg_check_failed(r, "lead") &&
        !hg_check_failed(r, "g") && !hg_check_failed(r, "m_head") && !hg_check_failed(r, "m_bar") && !hg_check_failed(r, "m_carriage") &&
        !(p->v_bus_v > p->r_winding_ohm * hg_hold_current(p)))
        hg_check_refuse(r, "v_bus", "must exceed r_winding times the current that holds the machine at HOME "
                           "(W / 6 / (kt 2 pi / lead)): the drives could not hold the head");
    if (!hg_check_failed(r, "limit_min") && !hg_check_failed(r, "limit_max") &&
        !(isfinite(p->home_switch_m) && p->home_switch_m > p->limit_min_m &&
          p->home_switch_m < p->limit_max_m))
        hg_check_refuse(r, "home_switch", "must lie between the limit switches");
    /* lost motion needs a drive train that can open: a rigid one has none */
    if (!hg_check_failed(r, "backlash") && !hg_check_failed(r, "k_axial") && p->backlash_m > 0.0 &&
        !(p->k_axial_n_per_m > 0.0))
        hg_check_refuse(r, "backlash", "needs the flexible drive train: set k_axial > 0 (k_axial 0 is the rigid "
                                       "train, without lost motion)");
    if (!hg_check_failed(r, "backlash") && !hg_check_failed(r, "stop_min") && !hg_check_failed(r, "stop_max") &&
        !(p->backlash_m < p->stop_max_m - p->stop_min_m))
        hg_check_refuse(r, "backlash", "must be shorter than the stroke between the hard stops");
    if (!hg_check_failed(r, "k_axial") && !hg_check_failed(r, "j_rotor") && p->k_axial_n_per_m > 0.0 &&
        !(p->j_rotor_kgm2 >= HG_PARAM_MIN_POSITIVE))
        hg_check_refuse(r, "j_rotor", "must be positive behind a flexible train (k_axial > 0): the rotor is a body "
                                      "of its own");
}

int hg_params_check(const hg_params *p, const char **bad_field, const char **why)
{
    hg_check r;
    check_start(&r, 0);
    params_rules(p, &r);
    return first_failure(&r, bad_field, why);
}

int hg_params_check_all(const hg_params *p, hg_bitset *bad, const char *why[HG_PARAMS_MAX])
{
    hg_check r;
    check_start(&r, why);
    params_rules(p, &r);
    if (bad)
        *bad = r.bad;
    return hg_check_any(&r) ? HG_ERR_BAD_PARAM : HG_OK;
}

int hg_params_check_kinematics(const hg_params *p, hg_bitset *bad, const char *why[HG_PARAMS_MAX])
{
    hg_bitset all, kept;
    hg_params d;
    int i, n;
    hg_params_table(&n);
    hg_params_default(&d);
    hg_bitset_clear(&kept);
    if (hg_params_check_all(p, &all, why))
        for (i = 0; i < n; i++)
            if (hg_bitset_has(&all, i) && (hg_param_is_geometry(i) ||
                                           !hg_param_same(hg_params_get(p, i), hg_params_get(&d, i))))
                hg_bitset_set(&kept, i);
    if (bad)
        *bad = kept;
    return hg_bitset_empty(&kept) ? HG_OK : HG_ERR_BAD_PARAM;
}
