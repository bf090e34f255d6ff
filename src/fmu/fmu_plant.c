/* fmu_plant.c - the adapter: the FMU's every use of the board core
 * (hg_board.h, hg_plant.h: the Hexaglide plant of the board's registry). It drives hg_board exactly as
 * `hexaglide sim` does (src/cli/cmd_sim.c): the board's own load-time
 * inputs (hg_board_inputs_default), the E-STOP loop closed by amp_enable,
 * the DAC volts of the period, one hg_board_step per servo period; and it
 * refuses a parameter set with the core's rule for each field, as the HAL
 * component motenc_hexaglide_dyns_virtual does. It checks the bytes of a
 * plant of unknown origin (a deserialized FMU state) against the core's
 * own build of the same parameters. */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fmu_plant.h"
#include "hg_compiler.h"
#include "hg_board.h"
#include "hg_errors.h"
#include "hg_scheme.h"
#include "hg_dynamics.h"          /* hg_model_names: the Hexaglide's parametrizations */
#include "hg_params.h"            /* HG_CONE_MIN_RAD; HG_PARAM_MAX_ABS, HG_PARAM_MIN_POSITIVE (hg_param_table.h) */
#include "hg_plant_hexaglide.h"   /* hg_hexaglide_data: the machine's state */
#include "hg_units.h"             /* HG_PI */

/* The servo period of configs/hexaglide.ini (SERVO_PERIOD) and of `hexaglide sim --dt`. */
#define PERIOD_DEFAULT_NS 1000000L

/* The names of the plant's extra outputs that are the head pose X Y Z A B C. */
static const char *const pose_names[6] = {"head-x", "head-y", "head-z", "head-a", "head-b", "head-c"};

typedef struct {
    hg_board b;
    hg_board_inputs in;               /* the board's inputs, kept from period to period */
    long period_ns;
    int pose_extra[6];                /* index of each pose output in the plant's extra outputs, -1 none */
} plant;

/* The board first (fmu_plant.h: the tests that forge states rely on it). */
typedef char board_first[offsetof(plant, b) == 0 ? 1 : -1];

/* The single-field rules of the Hexaglide's parameters (src/hg_params.c:
 * params_rules, geometry_rules): a rule on one value alone, whatever the
 * others, as the inclusive bounds FMI can declare. Every parameter lies
 * below HG_PARAM_MAX_ABS in magnitude (declared as the double below it); RULE_POSITIVE is at least
 * HG_PARAM_MIN_POSITIVE, RULE_MIN0 >= 0 (a strict > 0 too: its limit 0
 * then passes fmi3Set and the core refuses it with the rules between
 * fields, at fmi3ExitInitializationMode), RULE_MAX0 <= 0, RULE_CONE in
 * [1, 90 deg] (HG_CONE_MIN_RAD), RULE_BINARY 0 or 1. These bounds are what fmi3Set refuses
 * and modelDescription.xml declares; test_fmu_description checks each
 * against the core's check (hexaglide sim --set just outside it). */
enum { RULE_ANY, RULE_POSITIVE, RULE_MIN0, RULE_MAX0, RULE_CONE, RULE_BINARY };
static const struct {
    const char *name;
    int rule;
} single_rules[] = {
    {"l", RULE_MIN0}, {"lb", RULE_MIN0}, {"e", RULE_MIN0}, {"lp", RULE_MIN0},
    {"cone_carriage", RULE_CONE}, {"cone_head", RULE_CONE}, {"d_bar", RULE_MIN0},
    {"g", RULE_POSITIVE}, {"m_head", RULE_POSITIVE}, {"i_head_xx", RULE_POSITIVE}, {"i_head_yy", RULE_POSITIVE},
    {"i_head_zz", RULE_POSITIVE}, {"m_bar", RULE_POSITIVE}, {"i_bar", RULE_POSITIVE},
    {"m_carriage", RULE_POSITIVE}, {"lead", RULE_POSITIVE}, {"ka", RULE_POSITIVE}, {"kt", RULE_POSITIVE},
    {"i_max", RULE_POSITIVE}, {"k_stop", RULE_POSITIVE}, {"counts_per_rev", RULE_POSITIVE},
    {"r_winding", RULE_POSITIVE}, {"l_winding", RULE_POSITIVE}, {"v_bus", RULE_POSITIVE},
    {"v_rated", RULE_POSITIVE}, {"v_stribeck", RULE_POSITIVE},
    {"tool_d", RULE_MIN0}, {"head_com", RULE_MIN0}, {"j_rotor", RULE_MIN0}, {"c_visc", RULE_MIN0},
    {"f_coulomb", RULE_MIN0}, {"f_static", RULE_MIN0}, {"c_stop", RULE_MIN0}, {"kp_vel", RULE_MIN0},
    {"ki_vel", RULE_MIN0}, {"k_axial", RULE_MIN0}, {"c_axial", RULE_MIN0}, {"backlash", RULE_MIN0},
    {"limit_min", RULE_MAX0}, {"limit_max", RULE_MIN0}, {"amp_mode", RULE_BINARY},
};

/* The single-field rule of the parameter called name (RULE_ANY: the magnitude alone). */
static int single_rule(const char *name)
{
    size_t i;
    for (i = 0; i < sizeof single_rules / sizeof single_rules[0]; i++)
        if (!strcmp(single_rules[i].name, name))
            return single_rules[i].rule;
    return RULE_ANY;
}

/* The plant of the FMU in the board's registry. */
static const hg_plant *the_plant(void)
{
    return hg_plant_at(hg_plant_find(fmu_plant_name()));
}

const char *fmu_plant_name(void)
{
    return "hexaglide";
}

/* One line about the plant. */
const char *fmu_plant_description(void)
{
    return "The virtual Hexaglide: the multibody dynamics of the six-guide parallel machine behind a virtual "
           "MOTENC-100 board (DACs, encoders with index, switches, amplifiers), one servo period per step";
}

size_t fmu_plant_size(void)
{
    return sizeof(plant);
}

int fmu_plant_param_count(void)
{
    return the_plant()->nparams(the_plant()->default_variant);
}

int fmu_plant_param(int i, fmu_param *p)
{
    const hg_plant *pl = the_plant();
    const int v = pl->default_variant;  /* the Hexaglide's table is every parametrization's */
    hg_plant_params d;
    hg_param_info t;
    if (hg_plant_param(pl, v, i, &t))
        return -1;
    pl->defaults(v, &d);
    p->name = t.name;
    p->unit = t.unit;
    p->description = t.what;
    p->display_unit = t.hal_unit;
    p->display_factor = t.hal_scale;
    p->start = d.v[i];
    p->max = nextafter(HG_PARAM_MAX_ABS, 0.0);   /* the rule is strict, FMI's max inclusive */
    p->min = -p->max;
    p->quantum = 0;
    switch (single_rule(t.name)) {
    case RULE_POSITIVE: p->min = HG_PARAM_MIN_POSITIVE; break;
    case RULE_MIN0: p->min = 0; break;
    case RULE_MAX0: p->max = 0; break;
    case RULE_CONE: p->min = HG_CONE_MIN_RAD; p->max = HG_PI / 2; break;
    case RULE_BINARY: p->min = 0; p->max = 1; p->quantum = 1; break;
    default: break;
    }
    return 0;
}

const char *fmu_plant_param_why(int i, const double *params, double x)
{
    const hg_plant *pl = the_plant();
    const int v = pl->default_variant;
    const char *why[HG_PLANT_PARAMS_MAX];
    hg_plant_params block;
    hg_bitset bad;
    int k, n = fmu_plant_param_count();
    if (i < 0 || i >= n)
        return 0;
    memset(&block, 0, sizeof block);
    memset(why, 0, sizeof why);
    for (k = 0; k < n; k++)
        block.v[k] = params[k];
    block.v[i] = x;
    hg_bitset_clear(&bad);
    pl->check(v, &block, &bad, why);
    return hg_bitset_has(&bad, i) ? (why[i] ? why[i] : "invalid") : 0;
}

int fmu_plant_model_count(void)
{
    char name[64];
    int n = 0;
    while (n < 64 && the_plant()->variant_name(n, name, (int)sizeof name) == 0)
        n++;                           /* the Hexaglide's variants are 0..n-1 */
    return n;
}

const char *fmu_plant_model_name(int i)
{
    return i >= 0 && i < fmu_plant_model_count() ? hg_model_names[i] : 0;
}

int fmu_plant_model_default(void)
{
    return the_plant()->default_variant;
}

int fmu_plant_integrator_count(void)
{
    return HG_INTEGRATOR_COUNT;
}

const char *fmu_plant_integrator_name(int i)
{
    return i >= 0 && i < HG_INTEGRATOR_COUNT ? hg_integrator_name((hg_integrator)i) : 0;
}

int fmu_plant_defaults(long long *substeps, long long *integrator, double *enc_scale)
{
    plant *p = malloc(sizeof *p);     /* a board is too big for a stack */
    int rc = p ? hg_board_init(&p->b, hg_plant_find(fmu_plant_name()), the_plant()->default_variant, 0) : -1;
    if (rc == 0) {
        hg_board_inputs_default(&p->b, &p->in);   /* the block in force: HAL's load-time values */
        *substeps = p->in.params.substeps;
        *integrator = p->in.params.integrator;
        *enc_scale = p->in.enc_scale[0];
    }
    free(p);
    return rc ? -1 : 0;
}

long long fmu_plant_substeps_max(void)
{
    return HG_SUBSTEPS_MAX;
}

double fmu_plant_period_default_s(void)
{
    return (double)PERIOD_DEFAULT_NS * 1e-9;
}

double fmu_plant_period_min_s(void)
{
    return 1e-9;
}

double fmu_plant_period_max_s(void)
{
    return (double)HG_PERIOD_MAX_NS * 1e-9;
}

/* Say one message, printf-style. */
static void sayf(fmu_say_fn *say, void *env, int level, const char *fmt, ...)
    HG_PRINTF_LIKE(4, 5);
static void sayf(fmu_say_fn *say, void *env, int level, const char *fmt, ...)
{
    char text[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    say(env, level, text);
}

/* The parametrizations as "0 (standard), 1 (reduced-joints), ..." for a message. */
static void model_choices(char *buf, size_t len)
{
    int i, n = 0, count = fmu_plant_model_count();
    buf[0] = 0;
    for (i = 0; i < count && n >= 0 && (size_t)n < len; i++)
        n += snprintf(buf + n, len - (size_t)n, "%s%d (%s)", i ? (i + 1 < count ? ", " : " or ") : "", i,
                      fmu_plant_model_name(i));
}

/* How far a period's ns may lie from a whole number: the rounding of the double (of ns <= 1e7). */
#define PERIOD_NS_SLACK 1e-6

/* 1 when period_s lies in the declared range [min, max] s, to the bit. */
static int period_in_range(double period_s)
{
    return period_s >= fmu_plant_period_min_s() && period_s <= fmu_plant_period_max_s();
}

/* The period in whole ns, or -1: not a whole number of ns, or outside the board's range. */
static long period_ns_of(double period_s)
{
    double ns = period_s * 1e9, whole = floor(ns + 0.5);
    return period_in_range(period_s) && fabs(ns - whole) <= PERIOD_NS_SLACK ? (long)whole : -1;
}

int fmu_plant_period_why(double period_s, char *why, size_t len)
{
    double ns = period_s * 1e9, below = floor(ns), above = below + 1;
    if (period_ns_of(period_s) > 0)
        return 0;
    if (!period_in_range(period_s))
        snprintf(why, len, "must lie in [%g, %g] s (the board's servo period, whole nanoseconds)",
                 fmu_plant_period_min_s(), fmu_plant_period_max_s());
    else if (below < 1.0)
        snprintf(why, len, "is not a whole number of nanoseconds (the board's servo period is); the nearest is "
                 "%.9g s (%.0f ns)", above * 1e-9, above);
    else if (above > (double)HG_PERIOD_MAX_NS)
        snprintf(why, len, "is not a whole number of nanoseconds (the board's servo period is); the nearest is "
                 "%.9g s (%.0f ns)", below / 1e9, below);
    else
        snprintf(why, len, "is not a whole number of nanoseconds (the board's servo period is); the nearest are "
                 "%.9g s (%.0f ns) and %.9g s (%.0f ns)", below / 1e9, below, above / 1e9, above);
    return -1;
}

/* The board's rule for an encoder scale (hg_board.c, encoders()), refused here instead of replaced by 1.0. */
int fmu_plant_enc_scale_why(double enc_scale, char *why, size_t len)
{
    if (isfinite(enc_scale) && fabs(enc_scale) >= HG_ENC_SCALE_MIN)
        return 0;
    snprintf(why, len, "must be finite and at least %g in magnitude (counts per unit)", HG_ENC_SCALE_MIN);
    return -1;
}

double fmu_plant_period_in_force_s(double period_s)
{
    long ns = period_ns_of(period_s);
    return ns > 0 ? (double)ns / 1e9 : period_s;
}

/* hg_board_params of setup s (a value out of a field's range becomes one the core's check refuses). */
static void block_of(const fmu_plant_setup *s, hg_board_params *bp)
{
    int i, n = fmu_plant_param_count();
    memset(bp, 0, sizeof *bp);
    for (i = 0; i < n; i++)
        bp->plant.v[i] = s->params[i];
    bp->substeps = s->substeps >= 1 && s->substeps <= HG_SUBSTEPS_MAX ? (unsigned)s->substeps : 0u;
    bp->integrator = s->integrator >= 0 && s->integrator < HG_INTEGRATOR_COUNT ? (unsigned)s->integrator
                                                                                 : (unsigned)HG_INTEGRATOR_COUNT;
}

/* Every field the core's check refuses (the board b knows its plant): name = value unit: the rule. */
static void report_refused(const hg_board *b, const fmu_plant_setup *s, const hg_board_params *bp, fmu_say_fn *say,
                           void *env)
{
    static const char *const none[HG_BOARD_WHY_LEN];
    const char *why[HG_BOARD_WHY_LEN];
    hg_bitset bad;
    int i, n = hg_board_plant(b)->nparams(b->variant);
    memcpy(why, none, sizeof why);
    hg_bitset_clear(&bad);
    hg_board_params_check(b, bp, &bad, why);
    for (i = 0; i < HG_BOARD_WHY_LEN; i++) {
        if (!hg_bitset_has(&bad, i))
            continue;
        if (i < n) {
            hg_param_info t;
            hg_plant_param(hg_board_plant(b), b->variant, i, &t);
            sayf(say, env, FMU_SAY_ERROR, "parameter %s = %.9g%s%s refused: %s", t.name, bp->plant.v[i],
                 strcmp(t.unit, "1") ? " " : "", strcmp(t.unit, "1") ? t.unit : "", why[i] ? why[i] : "invalid");
        } else {
            sayf(say, env, FMU_SAY_ERROR, "parameter %s = %lld refused: %s",
                 i == HG_BOARD_BIT_SUBSTEPS ? "substeps" : "integrator",
                 i == HG_BOARD_BIT_SUBSTEPS ? s->substeps : s->integrator, why[i] ? why[i] : "invalid");
        }
    }
}

int fmu_plant_init(void *plant_bytes, const fmu_plant_setup *s, fmu_say_fn *say, void *env)
{
    plant *p = plant_bytes;
    const hg_plant *pl = the_plant();
    hg_board_params bp;
    long ns = period_ns_of(s->period_s);
    int rc, k, j, bad = 0;
    char why_scale[120];
    if (!(s->model >= 0 && s->model < fmu_plant_model_count())) {
        char choices[160];
        model_choices(choices, sizeof choices);
        sayf(say, env, FMU_SAY_ERROR, "parameter model = %lld refused: must be %s", s->model, choices);
        bad = 1;
    }
    if (ns < 0) {
        char why[200];
        fmu_plant_period_why(s->period_s, why, sizeof why);
        sayf(say, env, FMU_SAY_ERROR, "parameter period = %.17g s refused: %s", s->period_s, why);
        bad = 1;
    }
    if (fmu_plant_enc_scale_why(s->enc_scale, why_scale, sizeof why_scale)) {
        sayf(say, env, FMU_SAY_ERROR, "parameter enc_scale = %.9g refused: %s", s->enc_scale, why_scale);
        bad = 1;
    }
    block_of(s, &bp);
    memset(&p->b, 0, sizeof p->b);
    p->b.plant = hg_plant_find(fmu_plant_name());   /* the check needs the plant */
    if (hg_board_params_check(&p->b, &bp, 0, 0)) {
        report_refused(&p->b, s, &bp, say, env);
        bad = 1;
    }
    if (bad)
        return -1;
    rc = hg_board_init(&p->b, p->b.plant, (int)s->model, &bp);
    if (rc == 0 && p->b.sense.channels != FMU_JOINTS)
        rc = HG_ERR_BAD_PARAM;
    if (rc) {
        sayf(say, env, FMU_SAY_ERROR, "cannot build the machine: %s (code %d); change the parameters", hg_strerror(rc),
             rc);
        return -1;
    }
    hg_board_inputs_default(&p->b, &p->in);
    p->in.dac_written = 1;            /* the FMU's inputs are the DAC write of each period */
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        p->in.enc_scale[k] = s->enc_scale;
    p->period_ns = ns;
    for (k = 0; k < 6; k++)
        for (p->pose_extra[k] = -1, j = 0; j < pl->noutputs; j++)
            if (strcmp(pl->outputs[j].hal_name, pose_names[k]) == 0)
                p->pose_extra[k] = j;
    return 0;
}

double fmu_plant_period_s(const void *plant_bytes)
{
    const plant *p = plant_bytes;
    return (double)p->period_ns / 1e9;    /* the board integrates period_ns itself (as hexaglide sim) */
}

/* The board's outputs as the FMU shows them. */
static void convert(const plant *p, const hg_board_outputs *b, fmu_plant_outputs *o)
{
    int k;
    for (k = 0; k < FMU_JOINTS; k++) {
        const unsigned char *in = &b->in[HG_INPUTS_PER_CHANNEL * k];
        o->count[k] = b->count[k];
        o->position[k] = b->position[k];
        o->index[k] = b->index[k] != 0;
        o->limit_min[k] = in[HG_IN_LIMIT_MIN] != 0;
        o->limit_max[k] = in[HG_IN_LIMIT_MAX] != 0;
        o->home[k] = in[HG_IN_HOME] != 0;
        o->z_m[k] = b->pos[k];
        o->zd_mps[k] = b->vel[k];
        o->current_a[k] = b->current_a[k];
        o->force_n[k] = b->force[k];
    }
    for (k = 0; k < 6; k++)
        o->pose[k] = p->pose_extra[k] >= 0 ? b->extra[p->pose_extra[k]] : 0.0;
    o->fault = b->fault != 0;
    o->fault_code = b->fault_code;
    o->amps_on = b->amps_on != 0;
}

void fmu_plant_peek(const void *plant_bytes, fmu_plant_outputs *o)
{
    const plant *p = plant_bytes;
    hg_board_outputs out;
    hg_board_peek(&p->b, &out);
    convert(p, &out, o);
}

/* The board's events of one step (the period from the FMU's time t_s) as messages; the gravest level. */
static int report(const plant *p, const hg_board_outputs *out, double t_s, fmu_say_fn *say, void *env)
{
    const double t_end = t_s + fmu_plant_period_s(p);
    char why[HG_BOARD_TEXT_LEN];
    int k, level = FMU_SAY_INFO;
    if (out->events & HG_EV_SUBSTEPS_AUTO) {
        hg_board_describe_stiffness(&p->b, out, p->period_ns, 0, why);
        sayf(say, env, FMU_SAY_INFO, "%s: running %u substeps per period instead of %u", why, out->substeps_run,
             out->params.substeps);
    }
    if ((out->events & HG_EV_FAULT_LATCHED) && out->fault_cause == HG_FAULT_STIFF) {
        char remedy[HG_BOARD_TEXT_LEN];
        hg_board_describe_stiffness(&p->b, out, p->period_ns, 0, why);
        hg_board_stiff_remedy(out, "integrator", "period", remedy);
        sayf(say, env, FMU_SAY_WARNING, "the period from t = %.6f s to %.6f s failed: %s: %s even with "
             "%u substeps; give %s", t_s, t_end, why, hg_strerror(out->fault_code), HG_SUBSTEPS_MAX, remedy);
        level = FMU_SAY_WARNING;
    } else if (out->events & HG_EV_FAULT_LATCHED) {
        char what[HG_PLANT_TEXT_LEN];
        hg_board_plant(&p->b)->describe(&out->fault_report, 0, what);
        sayf(say, env, FMU_SAY_WARNING, "the period from t = %.6f s to %.6f s failed: %s (code %d)%s%s; "
             "the board latches the fault (state frozen, drives off) until a rising edge of reset", t_s, t_end,
             hg_strerror(out->fault_code), out->fault_code, what[0] ? ": " : "", what);
        level = FMU_SAY_WARNING;
    }
    for (k = 0; k < FMU_JOINTS; k++)
        if ((out->dac_nan_new >> k) & 1u) {
            sayf(say, env, FMU_SAY_WARNING, "dac_%d is NaN: the board outputs 0 V until it is a number again", k);
            level = FMU_SAY_WARNING;
        }
    for (k = 0; k < FMU_JOINTS; k++)
        if ((out->enc_scale_odd >> k) & 1u) {     /* one enc_scale for every channel: said of the first */
            hg_board_describe_enc_scale(&p->b, k, out->enc_scale[k], why);
            sayf(say, env, FMU_SAY_WARNING, "enc_scale = %.9g (channel %d) %s; position_k reads counts / enc_scale",
                 out->enc_scale[k], k, why);
            level = FMU_SAY_WARNING;
            break;
        }
    if (out->events & HG_EV_RESET_DONE)
        say(env, FMU_SAY_INFO, "reset: machine at HOME at rest, counters 0, fault cleared");
    return level;
}

int fmu_plant_step(void *plant_bytes, const fmu_plant_inputs *in, double t_s, fmu_plant_outputs *o, fmu_say_fn *say,
                   void *env)
{
    plant *p = plant_bytes;
    hg_board_outputs out;
    int k;
    for (k = 0; k < FMU_JOINTS; k++)
        p->in.dac_v[k] = in->dac_v[k];
    p->in.estop_button = in->estop != 0;
    p->in.reset = in->reset != 0;
    p->in.dout_values = in->amp_enable ? 1u << p->in.estop_loop_out : 0u;   /* as hexaglide sim closes it */
    hg_board_step(&p->b, &p->in, &out, p->period_ns);
    convert(p, &out, o);
    return report(p, &out, t_s, say, env);
}

/* A sink for the messages of a build that only checks (fmu_plant_check). */
static void quiet(void *env, int level, const char *text)
{
    (void)env, (void)level, (void)text;
}

/* 1 if x is 0 or 1. */
static int is_bit(int x)
{
    return x == 0 || x == 1;
}

/* Bitwise equality of two objects (doubles included: a NaN equals itself). */
#define SAME(a, b) (memcmp(&(a), &(b), sizeof(a)) == 0) // NOLINT(bugprone-suspicious-memory-comparison): bitwise on purpose

/* 1 when the n doubles of v are all finite. */
static int finite_all(const double *v, int n)
{
    int i;
    for (i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

/* What is wrong with plant p against ref, a fresh build of the same
 * setup (enc_scale the FMU's encoder scale), or 0. */
static const char *plant_wrong(const plant *p, const plant *ref, double enc_scale)
{
    const hg_board *b = &p->b, *r = &ref->b;
    const hg_plant *pl;
    const hg_data *d;
    hg_plant_sense sense;
    hg_board_inputs in;
    int k, n;
    /* what the build fixes: the plant and its variant first (everything else goes through them) */
    if (b->plant != r->plant || b->variant != r->variant)
        return "its board's plant or parametrization is not the parameters' (plant index, variant)";
    if (!SAME(b->m, r->m))
        return "its model is not the core's build of its parameters";
    if (b->integrator != r->integrator || b->substeps != r->substeps || !SAME(b->in_force, r->in_force) ||
        (!SAME(b->last_in, r->last_in) && !SAME(b->last_in, r->in_force)) || b->skip_tool_error != r->skip_tool_error)
        return "its board's parameter block is not the parameters'";
    if (p->period_ns != ref->period_ns || !SAME(p->pose_extra, ref->pose_extra))
        return "its period or its outputs' layout is not the parameters'";
    memcpy(&in, &p->in, sizeof in);    /* the inputs: the build's but for the four fmu_plant_step sets */
    memcpy(in.dac_v, ref->in.dac_v, sizeof in.dac_v);
    in.estop_button = ref->in.estop_button;
    in.reset = ref->in.reset;
    in.dout_values = ref->in.dout_values;
    if (!SAME(in, ref->in) || !is_bit(p->in.estop_button) || !is_bit(p->in.reset) ||
        (p->in.dout_values != 0 && p->in.dout_values != 1u << ref->in.estop_loop_out))
        return "its board's inputs are none the FMU gives";
    /* what the steps change: in range, and consistent with the machine's state */
    pl = hg_board_plant(b);
    n = pl->nparams(b->variant);
    if (b->substeps_run < b->substeps || b->substeps_run > HG_SUBSTEPS_MAX ||
        (b->stab_period_ns != 0 && b->stab_period_ns != p->period_ns) || b->stiff_param < -1 || b->stiff_param >= n)
        return "its substeps are out of range";
    d = hg_hexaglide_data(&b->d);
    if (!isfinite(d->t_s) || d->t_s < 0 || d->broken_bars != 0)
        return "its machine's time is not finite, or a bar is broken (the FMU breaks none)";
    if (!finite_all(d->z_m, 6) || !finite_all(d->zd_mps, 6) || !finite_all(d->zdd_mps2, 6) ||
        !finite_all(d->pose, 6) || !finite_all(d->posed, 6) || !finite_all(d->bar_rad, 12) ||
        !finite_all(d->bar_radps, 12) || !finite_all(d->current_a, 6) || !finite_all(d->vloop_int_m, 6) ||
        !finite_all(d->fric_n, 6) || !finite_all(d->force_n, 6) || !finite_all(&d->residual_m, 1) ||
        !finite_all(d->zr_m, 6) || !finite_all(d->zrd_mps, 6))
        return "its machine's state is not finite (a step never leaves a NaN or an infinity in it)";
    if (d->trig_valid) {              /* the state's sin/cos of the head's angles: the core's of them */
        double sc[6];
        hg_head_trig(d->pose, sc);
        if (d->trig_valid != 1 ||
            memcmp(d->trig_key_rad, d->pose + 3, sizeof d->trig_key_rad) != 0 || // NOLINT(bugprone-suspicious-memory-comparison): bitwise on purpose
            !SAME(d->trig_sc, sc))
            return "its head's sin and cos are not its angles'";
    }
    pl->sense(&b->m, &b->d, &sense);
    if (!SAME(sense, b->sense))
        return "its sensors do not show its machine's state";
    for (k = 0; k < HG_BOARD_ENCODERS; k++) {
        const hg_encoder *e = &b->enc[k];
        int used = k < sense.channels;
        double turns = used ? sense.turns[k] : 0.0, cpr = used ? sense.counts_per_rev[k] : 0.0;
        if (e->raw_counts != hg_encoder_raw_counts(turns, cpr) || e->revolution != hg_encoder_revolution(turns) ||
            !(e->offset_counts >= -(1LL << 53) && e->offset_counts <= 1LL << 53) || e->latch_armed ||
            e->latch_hit || !is_bit(e->index_pulse) || (!used && (e->index_pulse || e->offset_counts)))
            return "its encoders are not at its machine's motors";
        if (!SAME(b->enc_scale[k], b->enc_scale_in[k]) ||
            (b->enc_scale[k] != 1.0 && !SAME(b->enc_scale[k], enc_scale)))
            return "its encoder scale is not the parameter enc_scale";
        if (b->switches[k] != (used ? sense.switches[k] : 0u))
            return "its switches are not where its machine is";
    }
    if (!SAME(b->wd, r->wd) && !(b->wd.control == 0 && is_bit(b->wd.expired) && isfinite(b->wd.remaining_s)))
        return "its watchdog is in a state the FMU never sets";
    if (b->adc_state != r->adc_state || !SAME(b->adc_sample_v, r->adc_sample_v) || !SAME(b->adc_value, r->adc_value) ||
        !SAME(b->adc_volts_per_amp, r->adc_volts_per_amp) || !SAME(b->adc_volts_per_amp_in, r->adc_volts_per_amp_in))
        return "its ADCs are in a state the FMU never sets";
    if (b->estop_loop_out != r->estop_loop_out || b->estop_loop_out_in != r->estop_loop_out_in)
        return "its E-STOP loop's output is not the one the FMU sets";
    if (b->dac_nan >> FMU_JOINTS || !is_bit(b->prev_reset) || !is_bit(b->fault) || (b->fault != 0) != (b->fault_code != 0) ||
        !is_bit(b->param_error) || b->order_bad_run < 0 || b->order_bad_run > 2 || !is_bit(b->order_reported) ||
        !isfinite(b->tool_error) || b->tool_error < -1.0)
        return "its board's latches or counters are out of range";
    return 0;
}

int fmu_plant_check(const void *plant_bytes, const fmu_plant_setup *s, char *why, size_t len)
{
    const plant *p = plant_bytes;
    plant *ref = malloc(sizeof *ref);      /* a board is too big for a stack */
    const char *wrong;
    if (!ref)
        wrong = "not checked: out of memory";
    else if (fmu_plant_init(ref, s, quiet, 0))
        wrong = "of parameters the core refuses";
    else
        wrong = plant_wrong(p, ref, s->enc_scale);
    free(ref);
    if (!wrong)
        return 0;
    snprintf(why, len, "%s", wrong);
    return -1;
}

void fmu_plant_forget(void *plant_bytes)
{
    hg_board_forget(&((plant *)plant_bytes)->b);
}

unsigned long long fmu_plant_layout(void)
{
    const unsigned long long sizes[] = {
        sizeof(plant), offsetof(plant, in), offsetof(plant, period_ns), offsetof(plant, pose_extra),
        sizeof(hg_board), offsetof(hg_board, variant), offsetof(hg_board, in_force), offsetof(hg_board, m),
        offsetof(hg_board, d), offsetof(hg_board, d_saved), offsetof(hg_board, sense), offsetof(hg_board, enc),
        offsetof(hg_board, wd), offsetof(hg_board, fault), offsetof(hg_board, steps), offsetof(hg_board, tool_error),
        sizeof(hg_board_inputs), sizeof(hg_plant_model), sizeof(hg_plant_data), sizeof(hg_plant_sense),
        the_plant()->model_bytes, the_plant()->data_bytes, the_plant()->state_bytes,
    };
    const unsigned char *c = (const unsigned char *)sizes;
    unsigned long long h = 14695981039346656037ull;   /* FNV-1a 64 */
    size_t i;
    for (i = 0; i < sizeof sizes; i++) {
        h ^= c[i];
        h *= 1099511628211ull;
    }
    return h;
}
