/* hg_params.c - defaults, by-name access and validation of hg_params. */
#include "hg_math.h"
#include <stddef.h>
#include "hg_string.h"
#include "hg_params.h"
#include "hg_errors.h"

#define F(field) offsetof(hg_params, field)

static const hg_param_info table[] = {
    {"l",          "m",      "bar length",                              F(geo.l_m)},
    {"lb",         "m",      "machine axis to guide plane",             F(geo.lb_m)},
    {"e",          "m",      "half spacing of a post's guides",         F(geo.e_m)},
    {"lp",         "m",      "head joint radius",                       F(geo.lp_m)},
    {"h",          "m",      "carriage height above head joints at HOME", F(geo.h_m)},
    {"tool_d",     "m",      "tool tip below Op",                       F(tool_d_m)},
    {"g",          "m/s^2",  "gravity",                                 F(g_mps2)},
    {"m_head",     "kg",     "head mass",                               F(m_head_kg)},
    {"head_com",   "m",      "head COM below Op",                       F(head_com_m)},
    {"i_head_xx",  "kg m^2", "head inertia about COM, x",               F(i_head_xx_kgm2)},
    {"i_head_yy",  "kg m^2", "head inertia about COM, y",               F(i_head_yy_kgm2)},
    {"i_head_zz",  "kg m^2", "head inertia about COM, z",               F(i_head_zz_kgm2)},
    {"m_bar",      "kg",     "bar mass",                                F(m_bar_kg)},
    {"i_bar",      "kg m^2", "bar transverse inertia about carriage joint", F(i_bar_kgm2)},
    {"m_carriage", "kg",     "carriage mass",                           F(m_carriage_kg)},
    {"lead",       "m/rev",  "ball-screw lead",                         F(lead_m)},
    {"j_rotor",    "kg m^2", "rotor + screw inertia",                   F(j_rotor_kgm2)},
    {"ka",         "A/V",    "amplifier gain",                          F(ka_a_per_v)},
    {"kt",         "N m/A",  "motor torque constant",                   F(kt_nm_per_a)},
    {"i_max",      "A",      "amplifier current limit",                 F(i_max_a)},
    {"c_visc",     "N s/m",  "viscous friction per carriage",           F(c_visc_ns_per_m)},
    {"f_coulomb",  "N",      "Coulomb friction per carriage",           F(f_coulomb_n)},
    {"v_coulomb",  "m/s",    "Coulomb smoothing speed",                 F(v_coulomb_mps)},
    {"stop_min",   "m",      "hard stop, bottom",                       F(stop_min_m)},
    {"stop_max",   "m",      "hard stop, top",                          F(stop_max_m)},
    {"k_stop",     "N/m",    "hard-stop stiffness",                     F(k_stop_n_per_m)},
    {"c_stop",     "N s/m",  "hard-stop damping",                       F(c_stop_ns_per_m)},
    {"limit_min",  "m",      "limit switch, bottom",                    F(limit_min_m)},
    {"limit_max",  "m",      "limit switch, top",                       F(limit_max_m)},
    {"home_switch","m",      "home switch on at or above",              F(home_switch_m)},
    {"counts_per_rev", "1/rev", "encoder counts per motor revolution",  F(counts_per_rev)},
};

#undef F

double hg_home_height(const hg_geometry *g)
{
    double d = g->lb_m - g->lp_m;
    return sqrt(g->l_m * g->l_m - d * d);
}

void hg_params_keep_home(hg_params *p, const hg_params *before)
{
    if (p->geo.h_m == before->geo.h_m &&
        (p->geo.l_m != before->geo.l_m || p->geo.lb_m != before->geo.lb_m ||
         p->geo.lp_m != before->geo.lp_m))
        p->geo.h_m = hg_home_height(&p->geo);
}

void hg_params_default(hg_params *p)
{
    memset(p, 0, sizeof *p);
    p->geo.l_m = 1.000;
    p->geo.lb_m = 0.484;
    p->geo.e_m = 0.068254;
    p->geo.lp_m = 0.073085;
    p->geo.h_m = hg_home_height(&p->geo);
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
    p->ka_a_per_v = 0.8;
    p->kt_nm_per_a = 0.51;
    p->i_max_a = 8.0;
    p->c_visc_ns_per_m = 5665.6;
    p->f_coulomb_n = 0.0;
    p->v_coulomb_mps = 1e-3;
    p->stop_min_m = -0.260;
    p->stop_max_m = 0.260;
    p->k_stop_n_per_m = 5e6;      /* static penetration at the 8 A clamp ~0.5 mm; k dt^2 / m ~ 0.09 at 1 ms */
    p->c_stop_ns_per_m = 2e4;
    p->limit_min_m = -0.250;
    p->limit_max_m = 0.250;
    p->home_switch_m = 0.005;
    p->counts_per_rev = 10000.0;
}

const hg_param_info *hg_params_table(int *count)
{
    if (count)
        *count = (int)(sizeof table / sizeof table[0]);
    return table;
}

double *hg_params_field(hg_params *p, const char *name)
{
    int i, n;
    const hg_param_info *t = hg_params_table(&n);
    for (i = 0; i < n; i++)
        if (strcmp(t[i].name, name) == 0)
            return (double *)((char *)p + t[i].offset);
    return 0;
}

int hg_params_set(hg_params *p, const char *name, double value)
{
    double *f = hg_params_field(p, name);
    if (!f || !isfinite(value))
        return HG_ERR_BAD_PARAM;
    *f = value;
    return HG_OK;
}

/* Report a failed check: set the outputs and return HG_ERR_BAD_PARAM. */
static int refuse(const char **bad_field, const char *field,
                  const char **why, const char *reason)
{
    if (bad_field)
        *bad_field = field;
    if (why)
        *why = reason;
    return HG_ERR_BAD_PARAM;
}

int hg_geometry_check(const hg_geometry *g, const char **bad_field, const char **why)
{
    if (!(isfinite(g->l_m) && g->l_m > 0))
        return refuse(bad_field, "l", why, "must be a positive finite length");
    if (!(isfinite(g->lb_m) && g->lb_m > 0))
        return refuse(bad_field, "lb", why, "must be a positive finite length");
    if (!(isfinite(g->e_m) && g->e_m >= 0 && g->e_m < g->lb_m))
        return refuse(bad_field, "e", why, "must be finite, >= 0 and smaller than lb");
    if (!(isfinite(g->lp_m) && g->lp_m > 0 && g->lp_m < g->lb_m))
        return refuse(bad_field, "lp", why, "must be positive and smaller than lb");
    if (!(g->l_m > g->lb_m - g->lp_m))
        return refuse(bad_field, "l", why, "bars too short to reach the head: need l > lb - lp");
    if (!(isfinite(g->h_m) && g->h_m > 0 && g->h_m < 2 * g->l_m))
        return refuse(bad_field, "h", why, "must be positive and below 2 l");
    return HG_OK;
}

int hg_params_check(const hg_params *p, const char **bad_field, const char **why)
{
    /* fields that must be finite and strictly positive */
    static const char *const positive[] = {
        "g", "m_head", "i_head_xx", "i_head_yy", "i_head_zz", "m_bar",
        "i_bar", "m_carriage", "lead", "ka", "kt", "i_max", "k_stop",
        "counts_per_rev", "v_coulomb",
    };
    /* fields that must be finite and >= 0 */
    static const char *const nonneg[] = {
        "tool_d", "head_com", "j_rotor", "c_visc", "f_coulomb", "c_stop",
    };
    unsigned i;
    int rc = hg_geometry_check(&p->geo, bad_field, why), n;
    hg_params *q = (hg_params *)p; /* read-only use of the by-name lookup */
    const hg_param_info *t = hg_params_table(&n);
    if (rc)
        return rc;
    /* no machine needs a number of 1e9 SI units; beyond it products overflow */
    for (i = 0; i < (unsigned)n; i++) {
        double v = *hg_params_field(q, t[i].name);
        if (!(fabs(v) < HG_PARAM_MAX_ABS))
            return refuse(bad_field, t[i].name, why, "must be finite and below 1e9 in magnitude (SI units)");
    }
    for (i = 0; i < sizeof positive / sizeof positive[0]; i++) {
        double v = *hg_params_field(q, positive[i]);
        if (!(isfinite(v) && v >= HG_PARAM_MIN_POSITIVE))
            return refuse(bad_field, positive[i], why, "must be positive (at least 1e-9 in SI units)");
    }
    for (i = 0; i < sizeof nonneg / sizeof nonneg[0]; i++) {
        double v = *hg_params_field(q, nonneg[i]);
        if (!(isfinite(v) && v >= 0))
            return refuse(bad_field, nonneg[i], why, "must be finite and >= 0");
    }
    /* a lumped bar needs m_end > 0 and m_mid >= 0: m_bar l^2 / 4 <= i_bar < m_bar l^2 / 2 */
    if (!(p->i_bar_kgm2 >= p->m_bar_kg * p->geo.l_m * p->geo.l_m / 4 &&
          p->i_bar_kgm2 < p->m_bar_kg * p->geo.l_m * p->geo.l_m / 2))
        return refuse(bad_field, "i_bar", why,
                      "must lie in [m_bar l^2/4, m_bar l^2/2) for a bar with its COM at mid-length");
    if (!(isfinite(p->stop_min_m) && p->stop_min_m < p->limit_min_m))
        return refuse(bad_field, "stop_min", why, "must be finite and below limit_min");
    if (!(isfinite(p->limit_min_m) && p->limit_min_m < 0))
        return refuse(bad_field, "limit_min", why, "must be finite and below HOME (0)");
    if (!(isfinite(p->limit_max_m) && p->limit_max_m > 0))
        return refuse(bad_field, "limit_max", why, "must be finite and above HOME (0)");
    if (!(isfinite(p->stop_max_m) && p->stop_max_m > p->limit_max_m))
        return refuse(bad_field, "stop_max", why, "must be finite and above limit_max");
    if (!(isfinite(p->home_switch_m) && p->home_switch_m > p->limit_min_m &&
          p->home_switch_m < p->limit_max_m))
        return refuse(bad_field, "home_switch", why, "must lie between the limit switches");
    return HG_OK;
}
