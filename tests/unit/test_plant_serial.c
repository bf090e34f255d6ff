/* test_plant_serial.c - the serial-axis plant (hg_plant_serial.h) against
 * closed forms of one axis, and the board (hg_board.h) driving a trivial
 * plant written here, through nothing but the plant interface (hg_plant.h).
 *
 * Closed forms (independent of the code: Newton's law of one body):
 * - a vertical axis with its drive off sinks at the speed where viscous
 *   friction carries what sliding friction leaves of the weight:
 *   v = (m g - counterbalance - F_c) / c;
 * - at full command in torque mode the bus voltage limits the speed:
 *   v_bus = R i + kt k v and kt k i = c v + F_c (k = 2 pi / lead) give
 *   v = (v_bus kt k / R - F_c) / (c + kt^2 k^2 / R);
 * - a horizontal axis with only viscous friction coasts from v0 to rest
 *   in the distance m v0 / c, m the load plus the rotor reflected through
 *   the screw, J k^2;
 * - a rotary axis in degrees: the same top speed with the gear ratio n,
 *   k = n (motor radians per axis radian).
 * Bad input: an unknown plant or axes string, contradictory parameters
 * (breakaway below sliding friction, switches outside the stops), more
 * axes than channels; each refused naming the field. */
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_board.h"
#include "hg_plant.h"
#include "hg_plant_serial.h"
#include "hg_errors.h"

#define PERIOD_S 1e-3
#define TWO_PI 6.283185307179586

static hg_plant_model model;
static hg_plant_data data;
static const hg_plant *P = &hg_plant_serial;

/* Field f of axis k of variant in v. */
static double *fld(int variant, hg_plant_params *v, int k, int f)
{
    static double none;
    int i = hg_serial_entry(variant, k, f);
    return i >= 0 ? &v->v[i] : &none;
}

/* Build v into the model and reset: 0 or a code; the substeps the period
 * needs (the plant's stability check) into *sub. */
static int start(int variant, const hg_plant_params *v, unsigned *sub)
{
    const char *field = 0, *why = 0;
    int lim, rc;
    double dtm;
    rc = P->build(&model, v, variant, 1, &field, &why);
    if (rc) {
        printf("# build: %s: %s\n", field ? field : "?", why ? why : "?");
        return rc;
    }
    rc = P->stability(variant, v, 1, PERIOD_S, 1, 64, sub, &lim, &dtm);
    return rc ? rc : P->reset(&model, &data);
}

/* Run for t seconds in periods of PERIOD_S/sub with volts on channel 0
 * (enabled: its amplifier on): 0 or the first step's code. */
static int run(double t, unsigned sub, double volts0, unsigned enabled)
{
    double volts[HG_CHANNELS_MAX] = {0};
    long n = (long)floor(t / PERIOD_S + 0.5) * (long)sub, i;
    volts[0] = volts0;
    for (i = 0; i < n; i++) {
        int rc = P->step(&model, &data, volts, enabled, PERIOD_S / sub, 0);
        if (rc)
            return rc;
    }
    return 0;
}

static hg_plant_sense sense_now(void)
{
    hg_plant_sense s;
    P->sense(&model, &data, &s);
    return s;
}

/* Reflected rotor of axis 0: J (2 pi / lead)^2. */
static double reflected(int variant, hg_plant_params *v)
{
    double k = TWO_PI / *fld(variant, v, 0, HG_SF_LEAD);
    return *fld(variant, v, 0, HG_SF_J_ROTOR) * k * k;
}

static void test_sink(void)
{
    const int var = P->variant_of("Z");
    hg_plant_params v;
    unsigned sub;
    double m, g, cb, fc, c, want;
    hg_plant_sense s;
    P->defaults(var, &v);
    *fld(var, &v, 0, HG_SF_K_AXIAL) = 0.0;               /* rigid train */
    *fld(var, &v, 0, HG_SF_COUNTERBALANCE) = 100.0;      /* a weak one: the head sinks */
    *fld(var, &v, 0, HG_SF_C_VISC) = 2000.0;
    *fld(var, &v, 0, HG_SF_STOP_MIN) = -2.0;
    *fld(var, &v, 0, HG_SF_LIMIT_MIN) = -1.9;
    m = *fld(var, &v, 0, HG_SF_MASS), g = *fld(var, &v, 0, HG_SF_G);
    cb = *fld(var, &v, 0, HG_SF_COUNTERBALANCE), fc = *fld(var, &v, 0, HG_SF_F_COULOMB);
    c = *fld(var, &v, 0, HG_SF_C_VISC);
    want = -(m * g - cb - fc) / c;
    CHECK(start(var, &v, &sub) == 0, "sink: Z builds (rigid train, counterbalance %.0f N of %.1f N weight)", cb,
          m * g);
    CHECK(run(1.5, sub, 0.0, 0) == 0, "sink: 1.5 s (15 time constants (m + J k^2)/c) with the drive off");
    s = sense_now();
    CHECK(fabs(s.vel[0] - want) < 1e-3 * fabs(want) && s.pos[0] < -0.05,
          "sink: (m g - counterbalance - F_c)/c = %.6f m/s, measured %.6f m/s at %.1f mm", want, s.vel[0],
          s.pos[0] * 1e3);
    /* behind the default flexible train (the rotor a body of its own) the same speed */
    {
        hg_plant_params fv = v;
        hg_plant_params d0;
        P->defaults(var, &d0);
        *fld(var, &fv, 0, HG_SF_K_AXIAL) = *fld(var, &d0, 0, HG_SF_K_AXIAL);
        CHECK(start(var, &fv, &sub) == 0 && run(1.5, sub, 0.0, 0) == 0, "sink: flexible train (k_axial %.3g N/m), "
              "%u substeps at 1 ms", *fld(var, &fv, 0, HG_SF_K_AXIAL), sub);
        s = sense_now();
        CHECK(fabs(s.vel[0] - want) < 1e-3 * fabs(want), "sink: flexible train sinks at %.6f m/s too", s.vel[0]);
    }
    /* the same head fully balanced stays put: static friction and no net weight */
    *fld(var, &v, 0, HG_SF_COUNTERBALANCE) = m * g;
    start(var, &v, &sub);
    run(0.5, sub, 0.0, 0);
    s = sense_now();
    CHECK(s.pos[0] == 0.0 && s.vel[0] == 0.0, "sink: fully counterbalanced it does not move (%.3g m)", s.pos[0]);
    /* weight below breakaway friction: held, not sinking */
    *fld(var, &v, 0, HG_SF_COUNTERBALANCE) = m * g - 0.9 * *fld(var, &v, 0, HG_SF_F_STATIC);
    start(var, &v, &sub);
    run(0.5, sub, 0.0, 0);
    s = sense_now();
    CHECK(s.pos[0] == 0.0, "sink: a net weight of 90%% of the breakaway force is held (%.3g m)", s.pos[0]);
}

/* Top speed of axis 0 of a one-axis variant in torque mode at -10 V. */
static void top_speed(const char *axes, double t)
{
    const int var = P->variant_of(axes), rot = axes[0] >= 'A' && axes[0] <= 'C';
    hg_plant_params v;
    unsigned sub;
    double kt, k, r, vb, c, fc, want, i_need;
    hg_plant_sense s;
    P->defaults(var, &v);
    *fld(var, &v, 0, HG_SF_K_AXIAL) = 0.0;
    *fld(var, &v, 0, HG_SF_AMP_MODE) = 0.0;                  /* torque mode, 2 A/V: 20 A asked */
    *fld(var, &v, 0, HG_SF_I_MAX) = 50.0;                    /* far above what the bus can push */
    kt = *fld(var, &v, 0, HG_SF_KT), r = *fld(var, &v, 0, HG_SF_R_WINDING);
    vb = *fld(var, &v, 0, HG_SF_V_BUS), c = *fld(var, &v, 0, HG_SF_C_VISC);
    fc = *fld(var, &v, 0, HG_SF_F_COULOMB);
    k = rot ? *fld(var, &v, 0, HG_SF_LEAD) : TWO_PI / *fld(var, &v, 0, HG_SF_LEAD);
    want = -(vb * kt * k / r - fc) / (c + kt * kt * k * k / r);
    i_need = (c * fabs(want) + fc) / (kt * k);
    CHECK(start(var, &v, &sub) == 0, "top speed %s: builds (%u substeps at 1 ms)", axes, sub);
    CHECK(run(t, sub, -10.0, 1u) == 0, "top speed %s: %.1f s at -10 V", axes, t);
    s = sense_now();
    CHECK(fabs(s.vel[0] - want) < 1e-3 * fabs(want) && i_need < 20.0,
          "top speed %s: (v_bus kt k/R - F_c)/(c + kt^2 k^2/R) = %.6f %s, measured %.6f (current %.3f A < the 20 A "
          "asked)", axes, rot ? want * 57.29577951308232 : want, rot ? "deg/s" : "m/s",
          rot ? s.vel[0] * 57.29577951308232 : s.vel[0], fabs(s.current_a[0]));
    CHECK(fabs(fabs(s.current_a[0]) - i_need) < 1e-3 * i_need, "top speed %s: the current carries the friction: %.4f "
          "A, (c v + F_c)/(kt k) = %.4f A", axes, fabs(s.current_a[0]), i_need);
}

static void test_coast(void)
{
    const int var = P->variant_of("X");
    hg_plant_params v;
    unsigned sub;
    double m, c, x0, v0, want;
    hg_plant_sense s;
    P->defaults(var, &v);
    *fld(var, &v, 0, HG_SF_K_AXIAL) = 0.0;
    *fld(var, &v, 0, HG_SF_F_COULOMB) = 0.0;
    *fld(var, &v, 0, HG_SF_F_STATIC) = 0.0;
    c = *fld(var, &v, 0, HG_SF_C_VISC);
    m = *fld(var, &v, 0, HG_SF_MASS) + reflected(var, &v);
    CHECK(start(var, &v, &sub) == 0, "coast: X builds without sliding friction");
    run(1.0, sub, -10.0, 1u);                                 /* velocity mode: -50.8 mm/s */
    s = sense_now();
    x0 = s.pos[0], v0 = s.vel[0];
    CHECK(fabs(v0 + *fld(var, &v, 0, HG_SF_V_RATED)) < 1e-4, "coast: the velocity loop holds -v_rated at -10 V "
          "(%.4f mm/s)", v0 * 1e3);
    run(6.0, sub, -10.0, 0u);                                 /* 26 time constants m/c with the drive off */
    s = sense_now();
    want = m * v0 / c;
    CHECK(fabs((s.pos[0] - x0) - want) < 1e-3 * fabs(want) && fabs(s.vel[0]) < 1e-9,
          "coast: m v0/c = %.6f mm (m = load + J (2 pi/lead)^2 = %.2f kg), measured %.6f mm", want * 1e3, m,
          (s.pos[0] - x0) * 1e3);
}

static void test_encoder_sign(void)
{
    const int var = P->variant_of("XY");
    hg_plant_params v;
    unsigned sub;
    hg_plant_sense s;
    P->defaults(var, &v);
    *fld(var, &v, 1, HG_SF_COUNTS_PER_REV) = -*fld(var, &v, 1, HG_SF_COUNTS_PER_REV);
    CHECK(start(var, &v, &sub) == 0 && sense_now().channels == 2, "encoder: XY builds, 2 channels");
    {
        double volts[HG_CHANNELS_MAX] = {-5.0, -5.0};
        long i, n = 500L * (long)sub;
        for (i = 0; i < n; i++)
            P->step(&model, &data, volts, 3u, PERIOD_S / sub, 0);
    }
    s = sense_now();
    CHECK(fabs(s.turns[0] - s.motor_pos[0] / *fld(var, &v, 0, HG_SF_LEAD)) < 1e-12 &&
              fabs(s.turns[1] + s.motor_pos[1] / *fld(var, &v, 1, HG_SF_LEAD)) < 1e-12 && s.counts_per_rev[1] > 0,
          "encoder: turns = motor position / lead (%.3f), a negative counts_per_rev counts the other way (%.3f)",
          s.turns[0], s.turns[1]);
}

/* The entry's spec name of the first refused bit of check, or "". */
static const char *first_refused(int var, const hg_plant_params *v, const char **why)
{
    hg_bitset bad;
    const char *w[HG_PLANT_PARAMS_MAX];
    hg_param_info e;
    int i;
    if (P->check(var, v, &bad, w) == 0)
        return "";
    for (i = 0; i < P->nparams(var); i++)
        if (hg_bitset_has(&bad, i)) {
            P->param(var, i, &e);
            *why = w[i];
            return e.name;
        }
    return "?";
}

static void test_refusals(void)
{
    const int var = P->variant_of("XYZ");
    hg_plant_params v;
    hg_board bd;
    const char *why = "", *name, *field = 0, *w2 = 0;
    hg_param_info e;
    int i;
    CHECK(hg_plant_find("lathe") < 0 && hg_plant_find("serial") == 1 && hg_plant_find("hexaglide") == 0,
          "refuse: an unknown plant name is not found; serial is plant 1, hexaglide 0");
    CHECK(hg_board_init(&bd, 7, 0, 0) == HG_ERR_BAD_PARAM, "refuse: a board of an unknown plant index");
    CHECK(P->variant_of("XYQ") < 0 && P->variant_of("") < 0, "refuse: an axes string with a letter not of "
          "XYZABCUVW, or empty");
    CHECK(P->variant_of("XYZABCUV") > 0 && P->variant_of("XYZABCUVW") < 0 && P->channels(P->variant_of("XYZABCUV")) ==
          HG_CHANNELS_MAX, "refuse: 8 axes are the board's 8 channels; 9 are refused");
    CHECK(strstr(P->variants_help, "1 to 8") != 0, "refuse: the help names the bound: %s", P->variants_help);
    P->defaults(var, &v);
    CHECK(P->check(var, &v, 0, 0) == 0, "refuse: the defaults pass");
    *fld(var, &v, 1, HG_SF_F_STATIC) = 0.5 * *fld(var, &v, 1, HG_SF_F_COULOMB);
    name = first_refused(var, &v, &why);
    CHECK(strcmp(name, "f_static_1") == 0 && strstr(why, "f_coulomb"), "refuse: breakaway below sliding friction "
          "names %s: %s", name, why);
    P->defaults(var, &v);
    *fld(var, &v, 2, HG_SF_LIMIT_MIN) = *fld(var, &v, 2, HG_SF_STOP_MIN) - 0.001;
    name = first_refused(var, &v, &why);
    CHECK(strcmp(name, "stop_min_2") == 0 && strstr(why, "limit_min"), "refuse: a limit switch beyond its stop "
          "names %s: %s", name, why);
    i = hg_plant_param_find(P, var, "stop_min_2");
    CHECK(i >= 0 && P->param(var, i, &e) == 0 && strcmp(e.hal_name, "joint-2.stop-min") == 0 &&
              strcmp(e.ini_key, "STOP_MIN_2") == 0 && e.hal_scale == 1000.0 && strcmp(e.hal_unit, "mm") == 0,
          "refuse: its HAL name %s (mm) and INI key [%s]%s", e.hal_name, P->ini_section, e.ini_key);
    P->defaults(var, &v);
    *fld(var, &v, 0, HG_SF_BACKLASH) = 1e-5;
    *fld(var, &v, 0, HG_SF_K_AXIAL) = 0.0;
    name = first_refused(var, &v, &why);
    CHECK(strcmp(name, "backlash_0") == 0, "refuse: backlash on a rigid train names %s: %s", name, why);
    P->defaults(var, &v);
    *fld(var, &v, 2, HG_SF_COUNTERBALANCE) = 0.0;
    *fld(var, &v, 2, HG_SF_V_BUS) = 0.5;
    name = first_refused(var, &v, &why);
    CHECK(strcmp(name, "v_bus_2") == 0, "refuse: a bus that cannot hold Z's weight names %s: %s", name, why);
    CHECK(P->build(&model, &v, var, 1, &field, &w2) == HG_ERR_BAD_PARAM && field && strcmp(field, "v_bus_2") == 0,
          "refuse: build names the same field (%s)", field ? field : "none");
    {
        hg_board_params bp;
        hg_bitset bad;
        int ok = hg_board_params_default(1, var, &bp) == 0 && hg_board_init(&bd, 1, var, &bp) == 0;
        bp.plant = v;
        CHECK(ok && hg_board_params_check(&bd, &bp, &bad, 0) == HG_ERR_BAD_PARAM &&
                  strcmp(hg_board_param_hal_name(&bd, hg_plant_param_find(P, var, "v_bus_2")), "joint-2.v-bus") == 0 &&
                  hg_bitset_has(&bad, hg_plant_param_find(P, var, "v_bus_2")),
              "refuse: the board refuses the block, bit of joint-2.v-bus set");
    }
}

/* ---- a trivial plant: one channel, a mass pushed by force_per_volt V ----
 * Everything a plant must provide and nothing else; the board does the rest. */

enum { TP_MASS, TP_FORCE_PER_VOLT, TP_LEAD, TP_CPR, TP_LIMIT, TP_N };
static const hg_param_info tp_table[TP_N] = {
    {"mass", "kg", "moving mass", 0 * sizeof(double), "mass", "kg", 1.0, "MASS"},
    {"force_per_volt", "N/V", "force per DAC volt", 1 * sizeof(double), "force-per-volt", "N/V", 1.0, "FORCE_PER_VOLT"},
    {"lead", "m/rev", "travel per encoder revolution", 2 * sizeof(double), "lead", "mm", 1000.0, "LEAD"},
    {"counts_per_rev", "1/rev", "encoder counts per revolution", 3 * sizeof(double), "counts-per-rev", "1/rev", 1.0,
     "COUNTS_PER_REV"},
    {"limit", "m", "limit switches at -limit and +limit, home at 0", 4 * sizeof(double), "limit", "mm", 1000.0,
     "LIMIT"},
};
typedef struct { double p[TP_N]; } tp_model;
typedef struct { double t, x, v; } tp_data;

static int tp_variant_of(const char *name) { return strcmp(name, "one") == 0 ? 0 : -1; }
static int tp_variant_name(int var, char *buf, int len)
{
    if (var != 0 || len < 4)
        return -1;
    strcpy(buf, "one");
    return 0;
}
static int tp_channels(int var) { return var == 0 ? 1 : 0; }
static int tp_nparams(int var) { return var == 0 ? TP_N : 0; }
static int tp_param(int var, int i, hg_param_info *out)
{
    if (var != 0 || i < 0 || i >= TP_N)
        return -1;
    *out = tp_table[i];
    return 0;
}
static void tp_defaults(int var, hg_plant_params *v)
{
    (void)var;
    memset(v, 0, sizeof *v);
    v->v[TP_MASS] = 2.0, v->v[TP_FORCE_PER_VOLT] = 1.0, v->v[TP_LEAD] = 0.001, v->v[TP_CPR] = 1000.0;
    v->v[TP_LIMIT] = 0.05;
}
static void tp_legacy(int f, int var, hg_plant_params *v) { (void)f, (void)var, (void)v; }
static int tp_check(int var, const hg_plant_params *v, hg_bitset *bad, const char *why[HG_PLANT_PARAMS_MAX])
{
    int i, rc = 0;
    (void)var;
    if (bad)
        hg_bitset_clear(bad);
    for (i = 0; i < TP_N; i++)
        if (!(v->v[i] > 0.0 && v->v[i] < 1e9)) {
            rc = HG_ERR_BAD_PARAM;
            if (bad)
                hg_bitset_set(bad, i);
            if (why)
                why[i] = "must be positive";
        }
    return rc;
}
static int tp_build(hg_plant_model *m, const hg_plant_params *v, int var, int integ, const char **f, const char **w)
{
    (void)integ;
    if (tp_check(var, v, 0, 0)) {
        *f = "mass";
        *w = "must be positive";
        return HG_ERR_BAD_PARAM;
    }
    memcpy(((tp_model *)m->store)->p, v->v, sizeof(tp_model));
    return 0;
}
static void tp_params_of(const hg_plant_model *m, hg_plant_params *v)
{
    memset(v, 0, sizeof *v);
    memcpy(v->v, ((const tp_model *)m->store)->p, sizeof(tp_model));
}
static int tp_reset(const hg_plant_model *m, hg_plant_data *d)
{
    (void)m;
    memset(d->store, 0, sizeof(tp_data));
    return 0;
}
static unsigned tp_change(int var, const hg_plant_params *a, const hg_plant_params *b)
{
    (void)var;
    return a->v[TP_LEAD] != b->v[TP_LEAD] || a->v[TP_CPR] != b->v[TP_CPR] ? HG_PLANT_CHANGE_RESCALE : 0u;
}
static int tp_stability(int var, const hg_plant_params *v, int integ, double period, unsigned smin, unsigned smax,
                        unsigned *sub, int *param, double *dtm)
{
    (void)var, (void)v, (void)integ, (void)period, (void)smax;
    *sub = smin, *param = -1, *dtm = 1.0;
    return 0;
}
static void tp_inject(const hg_plant_model *m, hg_plant_data *d, const unsigned in[HG_CHANNELS_MAX],
                      unsigned acted[HG_PLANT_INJECT_MAX])
{
    (void)m, (void)d, (void)in, (void)acted;
}
/* exact for the force held over the step: x += v dt + a dt^2/2 */
static int tp_step(const hg_plant_model *pm, hg_plant_data *pd, const double volts[HG_CHANNELS_MAX],
                   unsigned enabled, double dt, hg_plant_report *r)
{
    const tp_model *m = (const tp_model *)pm->store;
    tp_data *d = (tp_data *)pd->store;
    double a = (enabled & 1u ? volts[0] * m->p[TP_FORCE_PER_VOLT] : 0.0) / m->p[TP_MASS];
    (void)r;
    d->x += d->v * dt + 0.5 * a * dt * dt;
    d->v += a * dt;
    d->t += dt;
    return 0;
}
static void tp_sense(const hg_plant_model *pm, const hg_plant_data *pd, hg_plant_sense *s)
{
    const tp_model *m = (const tp_model *)pm->store;
    const tp_data *d = (const tp_data *)pd->store;
    memset(s, 0, sizeof *s);
    s->channels = 1;
    s->turns[0] = d->x / m->p[TP_LEAD];
    s->counts_per_rev[0] = m->p[TP_CPR];
    s->motor_pos[0] = s->pos[0] = d->x;
    s->vel[0] = d->v;
    s->switches[0] = hg_plant_switches(d->x, -m->p[TP_LIMIT], m->p[TP_LIMIT], 0.0);
    s->sim_time_s = d->t;
}
static double tp_tool_error(const hg_plant_model *m, const hg_plant_data *pd, const double pos_cmd[HG_CHANNELS_MAX])
{
    (void)m;
    return fabs(pos_cmd[0] - ((const tp_data *)pd->store)->x);
}
static void tp_describe(const hg_plant_report *r, int hal, char buf[HG_PLANT_TEXT_LEN])
{
    (void)r, (void)hal;
    buf[0] = '\0';
}
static const hg_plant test_plant = {
    "test-mass", "a mass pushed by its DAC", "TEST", 0, 0, "one", 0, 0, 0, 0, 0,
    sizeof(tp_model), sizeof(tp_data), sizeof(tp_data),
    tp_variant_of, tp_variant_name, tp_channels, tp_nparams, tp_param, tp_defaults, tp_legacy, tp_check,
    tp_build, tp_params_of, tp_reset, tp_change, tp_stability, tp_inject, tp_step, tp_sense, tp_tool_error,
    tp_describe,
};

static void test_board_with_test_plant(void)
{
    static hg_board bd;
    hg_board_inputs in;
    hg_board_outputs out;
    int idx = hg_plant_register(&test_plant), i, hit_max = 0, latched = 0;
    double t, x_want;
    long want_counts;
    CHECK(idx >= 2 && hg_plant_find("test-mass") == idx && hg_plant_register(&test_plant) < 0,
          "test plant: registered as plant %d (its name once only)", idx);
    CHECK(hg_board_init(&bd, idx, 0, 0) == 0, "test plant: a board of it initializes");
    hg_board_inputs_default(&bd, &in);
    in.dout_values = 1u << 7;                                  /* close the E-STOP loop */
    in.dac_v[0] = 2.0;                                         /* 2 N on 2 kg: 1 m/s^2 */
    for (i = 0; i < 200; i++) {
        in.dac_written = 1;
        hg_board_step(&bd, &in, &out, 1000000L);
    }
    t = 0.2, x_want = 0.5 * 1.0 * t * t;                       /* the DAC's 13 bits: 2 V within 2.5 mV */
    want_counts = (long)floor(hg_dac_output(2.0) / 2.0 * x_want / 0.001 * 1000.0);
    CHECK(out.amps_on && fabs(out.sim_time_s - t) < 1e-12 && labs(out.count[0] - want_counts) <= 1,
          "test plant: x = a t^2/2 at 0.2 s: %ld counts, %ld from a = DAC volts / mass", (long)out.count[0],
          want_counts);
    CHECK(out.in[0] == 0 && out.in[1] == 0 && out.in[2] == 1, "test plant: home switch on at x >= 0, limits off");
    for (i = 0; i < 400 && !hit_max; i++) {
        in.dac_written = 1;
        hg_board_step(&bd, &in, &out, 1000000L);
        hit_max = out.in[HG_IN_LIMIT_MAX];
    }
    CHECK(hit_max && fabs(out.pos[0] - 0.05) < 0.001, "test plant: the + limit input trips at its 50 mm (%.2f mm)",
          out.pos[0] * 1e3);
    in.index_enable[0] = 1;
    for (i = 0; i < 10 && !latched; i++) {
        in.dac_written = 1;
        hg_board_step(&bd, &in, &out, 1000000L);
        latched = out.index_latched[0];
    }
    CHECK(latched && abs(out.count[0]) < 1000, "test plant: the index (every 1 mm revolution) latches and zeroes "
          "the counter (%d counts after)", out.count[0]);
    in.dout_values = 0;                                        /* E-STOP: amplifiers off, the mass coasts */
    in.dac_written = 1;
    hg_board_step(&bd, &in, &out, 1000000L);
    {
        double v0 = out.vel[0];
        for (i = 0; i < 10; i++) {
            in.dac_written = 1;
            hg_board_step(&bd, &in, &out, 1000000L);
        }
        CHECK(!out.amps_on && out.estop_in && out.vel[0] == v0, "test plant: E-STOP opens the loop, the amps go "
              "off, the mass coasts at %.4f m/s", v0);
    }
    in.params.plant.v[TP_MASS] = -1.0;
    in.dac_written = 1;
    hg_board_step(&bd, &in, &out, 1000000L);
    CHECK((out.events & HG_EV_PARAM_REFUSED) && hg_bitset_has(&out.refused, TP_MASS) &&
              strcmp(hg_board_param_hal_name(&bd, TP_MASS), "mass") == 0 && bd.in_force.plant.v[TP_MASS] == 2.0,
          "test plant: the board refuses its bad mass by the plant's table, the 2 kg stays");
}

int main(void)
{
    test_sink();
    top_speed("X", 0.2);
    top_speed("C", 0.5);
    test_coast();
    test_encoder_sign();
    test_refusals();
    test_board_with_test_plant();
    return hg_test_exit();
}
