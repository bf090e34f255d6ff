/* hg_plant_hexaglide.c - the Hexaglide as a plant of the virtual board
 * (hg_plant.h): its parameter table (hg_params.h), its model and state
 * (hg_model.h, hg_dynamics.h), its stability check (hg_stability.h), its
 * mechanical limits (hg_guard.h) and what its sensors read: six channels,
 * the motor encoders on the ball screws (turns = z / lead), the limit and
 * home switches on the carriages, the head pose and the bars. */
#include <float.h>
#include "hg_math.h"
#include "hg_string.h"
#include "hg_plant_hexaglide.h"
#include "hg_dynamics.h"
#include "hg_kinematics.h"
#include "hg_stability.h"
#include "hg_guard_text.h"
#include "hg_errors.h"
#include "hg_units.h"

#define CHANNELS 6
#define TOOL_FK_ITERATIONS 8         /* Newton from the present pose: quadratic, 1e-12 m in 2-3 */

/* The plant's model: the dynamics' and what the sensors derive from the
 * parameters once per build (not per period). */
typedef struct {
    hg_model m;
    unsigned geometry_fp;            /* hg_geometry_fingerprint of m.p.geo */
} hexaglide_model;

typedef char hg_hexaglide_fits[(sizeof(hexaglide_model) <= sizeof(hg_plant_model) &&
                                sizeof(hg_data) <= sizeof(hg_plant_data) &&
                                HG_PARAMS_MAX <= HG_PLANT_PARAMS_MAX && CHANNELS <= HG_CHANNELS_MAX) ? 1 : -1];

/* sense.extra[] of the Hexaglide, in this order */
enum { X_HEAD = 0, X_RESIDUAL = 6, X_BARS_BROKEN = 7, X_GEOMETRY = 8, X_COUNT = 9 };
static const hg_plant_output outputs[X_COUNT] = {
    {"head-x", "mm", HG_MM_PER_M, 0, "pose-x", "x_mm", "head reference point Op, X"},
    {"head-y", "mm", HG_MM_PER_M, 0, "pose-y", "y_mm", "head reference point Op, Y"},
    {"head-z", "mm", HG_MM_PER_M, 0, "pose-z", "z_mm", "head reference point Op, Z"},
    {"head-a", "deg", HG_DEG_PER_RAD, 0, "pose-a", "a_deg", "head orientation A (Euler 3-2-1, about x)"},
    {"head-b", "deg", HG_DEG_PER_RAD, 0, "pose-b", "b_deg", "head orientation B (about y)"},
    {"head-c", "deg", HG_DEG_PER_RAD, 0, "pose-c", "c_deg", "head orientation C (about z)"},
    {"residual", "m", 1.0, 0, 0, 0, "largest bar-length error after the last stabilization"},
    {"bars-broken", "", 1.0, 1, "bars-broken", 0, "bit k: bar k is broken (joint-N.bar-broken)"},
    {"geometry-fingerprint", "", 1.0, 1, 0, 0, "fingerprint of the geometry in force (hexaglidekins.board-geometry)"},
};

static const hg_plant_injection injections[1] = {
    {"bar-broken", 1, "broke: the head hangs on the other bars; the fault latches when it leaves the "
                      "volume the model represents"},
};

/* The model and data laid over the board's storage. */
static const hexaglide_model *hmodel_of(const hg_plant_model *m) { return (const hexaglide_model *)m->store; }
static const hg_model *model_of(const hg_plant_model *m) { return &hmodel_of(m)->m; }
const hg_model *hg_hexaglide_model(const hg_plant_model *m) { return model_of(m); }
const hg_data *hg_hexaglide_data(const hg_plant_data *d) { return (const hg_data *)d->store; }
static hg_data *data_of(hg_plant_data *d) { return (hg_data *)d->store; }
static const hg_data *cdata_of(const hg_plant_data *d) { return (const hg_data *)d->store; }

/* A block as the typed parameter set, and back. */
static void params_from(const hg_plant_params *v, hg_params *p)
{
    int i, n;
    memset(p, 0, sizeof *p);
    hg_params_table(&n);
    for (i = 0; i < n; i++)
        *hg_params_at(p, i) = v->v[i];
}

/* The typed parameter set as a block. */
static void params_to(const hg_params *p, hg_plant_params *v)
{
    int i, n;
    memset(v, 0, sizeof *v);
    hg_params_table(&n);
    for (i = 0; i < n; i++)
        v->v[i] = hg_params_get(p, i);
}

/* The variants are the parametrizations (hg_model_names). */
static int variant_of(const char *name)
{
    return hg_model_from_name(name);
}

/* hg_plant.variant_name: the parametrization's name. */
static int variant_name(int variant, char *buf, int len)
{
    const char *n = hg_model_name((hg_model_kind)variant);
    int k;
    if (!n || len < 1)
        return -1;
    for (k = 0; k < len - 1 && n[k]; k++)
        buf[k] = n[k];
    buf[k] = '\0';
    return 0;
}

/* hg_plant.channels: six carriages, whatever the parametrization. */
static int channels(int variant)
{
    (void)variant;
    return CHANNELS;
}

/* hg_plant.nparams: entries of the Hexaglide's parameter table (hg_params.c). */
static int nparams(int variant)
{
    int n;
    (void)variant;
    hg_params_table(&n);
    return n;
}

/* hg_plant.param: entry i of that table. */
static int param(int variant, int i, hg_param_info *out)
{
    int n;
    const hg_param_info *t = hg_params_table(&n);
    (void)variant;
    if (i < 0 || i >= n)
        return -1;
    *out = t[i];
    return 0;
}

/* hg_plant.defaults: docs/model.md's machine (hg_params_default). */
static void defaults(int variant, hg_plant_params *v)
{
    hg_params p;
    (void)variant;
    hg_params_default(&p);
    params_to(&p, v);
}

/* Format 1 (d20d9e5 and before) knew no drive train: it was rigid. */
static void legacy(int format, int variant, hg_plant_params *v)
{
    hg_params p;
    (void)variant;
    params_from(v, &p);
    if (format == 1) {
        p.k_axial_n_per_m = 0.0;
        p.c_axial_ns_per_m = 0.0;
        p.backlash_m = 0.0;
    }
    params_to(&p, v);
}

/* hg_plant.check: every rule of hg_params_check_all, each bad field named. */
static int check(int variant, const hg_plant_params *v, hg_bitset *bad, const char *why[HG_PLANT_PARAMS_MAX])
{
    hg_params p;
    (void)variant;
    params_from(v, &p);
    return hg_params_check_all(&p, bad, why);
}

/* hg_plant.build: the dynamics model of the set (hg_model_init) with the scheme, and the geometry's fingerprint. */
static int build(hg_plant_model *m, const hg_plant_params *v, int variant, int integrator,
                 const char **field, const char **why)
{
    hexaglide_model *hm = (hexaglide_model *)m->store;
    hg_params p;
    int rc;
    params_from(v, &p);
    rc = hg_model_init(&hm->m, &p, (hg_model_kind)variant, field, why);
    if (rc == 0 && hg_model_set_integrator(&hm->m, integrator)) {
        *field = "integrator";
        *why = "must be 0 (improved-euler), 1 (heun) or 2 (rk4)";
        rc = HG_ERR_BAD_PARAM;
    }
    hm->geometry_fp = hg_geometry_fingerprint(&p.geo);
    return rc;
}

/* hg_plant.params_of: the set the model was built from. */
static void params_of(const hg_plant_model *m, hg_plant_params *v)
{
    params_to(&model_of(m)->p, v);
}

/* hg_plant.reset: at rest at HOME. */
static int reset(const hg_plant_model *m, hg_plant_data *d)
{
    return hg_data_reset(model_of(m), data_of(d));
}

/* 1 when x and y differ by at most 4 ulps of the larger. */
static int within_rounding(double x, double y)
{
    const double ax = fabs(x), ay = fabs(y);
    return fabs(x - y) <= 4.0 * DBL_EPSILON * (ax > ay ? ax : ay);
}

/* hg_plant.change: the machine's shape (l, lb, e, lp: where HOME is)
 * restarts it; the joints' ranges and the bar diameter are limits, not
 * shape. A new lead or counts-per-rev rescales the encoders. */
static unsigned change(int variant, const hg_plant_params *a, const hg_plant_params *b)
{
    hg_params p, q;
    unsigned c = 0;
    (void)variant;
    params_from(a, &p);
    params_from(b, &q);
    if (p.geo.l_m != q.geo.l_m || p.geo.lb_m != q.geo.lb_m || p.geo.e_m != q.geo.e_m || p.geo.lp_m != q.geo.lp_m)
        c |= HG_PLANT_CHANGE_RESTART;
    if ((c & HG_PLANT_CHANGE_RESTART) && within_rounding(p.geo.l_m, q.geo.l_m) &&
        within_rounding(p.geo.lb_m, q.geo.lb_m) && within_rounding(p.geo.e_m, q.geo.e_m) &&
        within_rounding(p.geo.lp_m, q.geo.lp_m))
        c |= HG_PLANT_CHANGE_ROUNDING;
    if (p.lead_m != q.lead_m || p.counts_per_rev != q.counts_per_rev)
        c |= HG_PLANT_CHANGE_RESCALE;
    return c;
}

/* The Hexaglide's carriage as the stability check's axis (every carriage
 * alike): a rigid train moves the rotor with its carriage; behind a
 * flexible one the carriage with its bar end is the least inertia any
 * carriage has (the machine's carriage-space mass matrix is at least
 * (m_carriage + m_end) I). */
static void stability_axis(const hg_params *p, hg_stability_axis *a)
{
    static const char *const names[HG_STAB_NAMES] = {"c_visc", "k_stop", "c_stop", "r_winding", "kp_vel",
                                                      "ki_vel", "k_axial", "c_axial", "backlash"};
    const double k = 2.0 * HG_PI / p->lead_m;
    const double m_end = 2.0 * p->i_bar_kgm2 / (p->geo.l_m * p->geo.l_m) - 0.5 * p->m_bar_kg;
    int i;
    a->m_rotor = p->j_rotor_kgm2 * k * k;
    a->m_rigid = p->m_carriage_kg + a->m_rotor;
    a->m_load = p->m_carriage_kg + m_end;
    a->c_visc = p->c_visc_ns_per_m;
    a->k_stop = p->k_stop_n_per_m;
    a->c_stop = p->c_stop_ns_per_m;
    a->force_per_amp = p->kt_nm_per_a * k;
    a->r_winding = p->r_winding_ohm;
    a->l_winding = p->l_winding_h;
    a->velocity_mode = p->amp_mode == 1.0;
    a->kp_vel = p->kp_vel_as_per_m;
    a->ki_vel = p->ki_vel_a_per_m;
    a->k_axial = p->k_axial_n_per_m;
    a->c_axial = p->c_axial_ns_per_m;
    a->backlash = p->backlash_m;
    a->f_max = p->i_max_a * a->force_per_amp;
    for (i = 0; i < HG_STAB_NAMES; i++)
        a->name[i] = names[i];
}

int hg_stability_check(const hg_params *p, hg_integrator scheme, double period_s, unsigned substeps_min,
                       unsigned substeps_max, hg_stability *out)
{
    hg_stability_axis a;
    stability_axis(p, &a);
    return hg_stability_check_axes(&a, 1, scheme, period_s, substeps_min, substeps_max, out);
}

/* hg_plant.stability: the substeps the set needs at the period (hg_stability), naming the limiting parameter. */
static int stability(int variant, const hg_plant_params *v, int integrator, double period_s,
                     unsigned substeps_min, unsigned substeps_max, unsigned *substeps, int *limit,
                     double *dt_max_s)
{
    hg_stability st;
    hg_params p;
    int n, rc;
    const hg_param_info *t = hg_params_table(&n);
    (void)variant;
    params_from(v, &p);
    rc = hg_stability_check(&p, (hg_integrator)integrator, period_s, substeps_min, substeps_max, &st);
    *substeps = st.substeps;
    *limit = hg_param_find(t, n, st.param);
    *dt_max_s = st.dt_max_s;
    return rc;
}

/* hg_plant.inject: a bar broken on a channel's bar-broken pin. */
static void inject(const hg_plant_model *m, hg_plant_data *d, const unsigned in[HG_CHANNELS_MAX],
                   unsigned acted[HG_PLANT_INJECT_MAX])
{
    hg_data *hd = data_of(d);
    int k;
    (void)m;
    for (k = 0; k < CHANNELS; k++) {   /* a broken bar stays broken until a reset */
        unsigned bit = 1u << k;
        if (!(in[k] & 1u) || (hd->broken_bars & bit))
            continue;
        hd->broken_bars |= bit;
        acted[0] |= bit;
    }
}

/* 1 if every state number that reaches an output is finite. */
static int state_finite(const hg_data *d)
{
    int k, ok = isfinite(d->t_s) && isfinite(d->residual_m);
    for (k = 0; k < 6; k++)
        ok = ok && isfinite(d->z_m[k]) && isfinite(d->zd_mps[k]) && isfinite(d->pose[k]) &&
             isfinite(d->posed[k]) && isfinite(d->current_a[k]) && isfinite(d->force_n[k]) &&
             isfinite(d->zr_m[k]) && isfinite(d->zrd_mps[k]);
    return ok;
}

/* hg_plant.step: one (sub)step of the dynamics under the DAC volts (hg_step). */
static int step(const hg_plant_model *m, hg_plant_data *d, const double volts[HG_CHANNELS_MAX],
                unsigned enabled, double dt_s, hg_plant_report *r)
{
    hg_data *hd = data_of(d);
    int rc;
    hd->amp_enabled = enabled & HG_BARS_ALL;   /* a disabled amplifier passes no current */
    rc = hg_step(model_of(m), hd, volts, dt_s);
    if (rc == 0 && !state_finite(hd))
        rc = HG_ERR_STATE_NONFINITE;
    if (rc && r) {                    /* what was struck (guard) */
        r->kind = hd->guard.kind;
        r->channel = hd->guard.bar;
        r->other = hd->guard.other;
        r->value = hd->guard.value;
        r->limit = hd->guard.limit;
    }
    return rc;
}

/* Finite x, or 0. */
static double finite_or_zero(double x) { return isfinite(x) ? x : 0.0; }

/* hg_plant.sense: encoders' turns, carriages, currents, switches and the head pose after a step. */
static void sense(const hg_plant_model *m, const hg_plant_data *d, hg_plant_sense *s)
{
    const hg_model *hm = model_of(m);
    const hg_params *p = &hm->p;
    const hg_data *hd = cdata_of(d);
    int k;
    memset(s, 0, sizeof *s);
    s->channels = CHANNELS;
    for (k = 0; k < CHANNELS; k++) {
        /* the motor on the screw: its height / lead revolutions, the carriage's when rigid */
        double motor = hm->flexible ? hd->zr_m[k] : hd->z_m[k];
        s->turns[k] = motor / p->lead_m;
        s->turns_per_unit[k] = 1.0 / p->lead_m;
        s->counts_per_rev[k] = p->counts_per_rev;
        s->motor_pos[k] = finite_or_zero(motor);
        s->pos[k] = finite_or_zero(hd->z_m[k]);
        s->vel[k] = finite_or_zero(hd->zd_mps[k]);
        s->current_a[k] = finite_or_zero(hd->current_a[k]);
        s->force[k] = finite_or_zero(hd->force_n[k]);
        s->switches[k] = hg_plant_switches(hd->z_m[k], p->limit_min_m, p->limit_max_m, p->home_switch_m);
    }
    for (k = 0; k < 6; k++)
        s->extra[X_HEAD + k] = finite_or_zero(hd->pose[k]);
    s->extra[X_RESIDUAL] = finite_or_zero(hd->residual_m);
    s->extra[X_BARS_BROKEN] = (double)hd->broken_bars;
    s->extra[X_GEOMETRY] = (double)hmodel_of(m)->geometry_fp;
    s->sim_time_s = finite_or_zero(hd->t_s);
}

/* The tool tip's distance from where the commanded carriages put it: their
 * forward kinematics by Newton from the present pose (unguarded: a measure,
 * not a move), the tips tool_d below Op. */
static double tool_error(const hg_plant_model *m, const hg_plant_data *d, const double pos_cmd[HG_CHANNELS_MAX])
{
    const hg_model *hm = model_of(m);
    const hg_data *hd = cdata_of(d);
    hg_fk_options o;
    double pose[6], tip[3], tip_cmd[3], e = 0.0;
    int k;
    hg_fk_options_default(&o);
    o.max_iterations = TOOL_FK_ITERATIONS;
    memcpy(pose, hd->pose, sizeof pose);
    if (hg_forward_solve(&hm->p.geo, pos_cmd, pose, &o, 0, 0))   /* a measure near the pose held: no guard */
        return -1.0;
    hg_tool_tip(hd->pose, hm->p.tool_d_m, tip);
    hg_tool_tip(pose, hm->p.tool_d_m, tip_cmd);
    for (k = 0; k < 3; k++)
        e += (tip_cmd[k] - tip[k]) * (tip_cmd[k] - tip[k]);
    e = sqrt(e);
    return isfinite(e) ? e : -1.0;
}

/* hg_plant.describe: what a failed step struck, as one sentence (hg_guard_text). */
static void describe(const hg_plant_report *r, int hal, char buf[HG_PLANT_TEXT_LEN])
{
    hg_guard_report g;
    typedef char fits[HG_GUARD_TEXT_LEN <= HG_PLANT_TEXT_LEN ? 1 : -1];
    g.kind = r->kind;
    g.bar = r->channel;
    g.other = r->other;
    g.value = r->value;
    g.limit = r->limit;
    hg_guard_describe(&g, hal, buf);
    (void)sizeof(fits);
}

const hg_plant hg_plant_hexaglide = {
    "hexaglide",
    "the UPNa Hexaglide: six ball-screw carriages on three posts, six bars, a head",
    "HEXAGLIDE",
    "configs/hexaglide.hal",
    "hexaglidekins.%s and motenc-hexaglide.0.%s",
    "standard, reduced-joints, reduced-cartesian (the default) or fused-cartesian",
    HG_MODEL_REDUCED_CARTESIAN,
    outputs,
    X_COUNT,
    injections,
    1,
    sizeof(hexaglide_model),
    sizeof(hg_data),
    HG_DATA_STATE_BYTES,
    variant_of,
    variant_name,
    channels,
    nparams,
    param,
    defaults,
    legacy,
    check,
    build,
    params_of,
    reset,
    change,
    stability,
    inject,
    step,
    sense,
    tool_error,
    describe,
};

unsigned long hg_hexaglide_sizeof(int which)
{
    switch (which) {
    case 4: return sizeof(hg_model);
    case 5: return sizeof(hg_data);
    case 6: return sizeof(hg_params);
    case 12: return HG_DATA_STATE_BYTES;
    default: return 0;
    }
}
