/* fmu_plant.c - the adapter: the FMU's every use of the board core
 * (hg_board.h, hg_plant.h: the Hexaglide plant of the board's registry). It drives hg_board exactly as
 * `hexaglide sim` does (src/cli/cmd_sim.c): the board's own load-time
 * inputs (hg_board_inputs_default), the E-STOP loop closed by amp_enable,
 * the DAC volts of the period, one hg_board_step per servo period; and it
 * refuses a parameter set with the core's rule for each field, as the HAL
 * component motenc_hexaglide_dyns_virtual does. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fmu_plant.h"
#include "hg_board.h"
#include "hg_errors.h"
#include "hg_scheme.h"
#include "hg_dynamics.h"          /* hg_model_names: the Hexaglide's parametrizations */

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
    return 0;
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
    __attribute__((format(printf, 4, 5)));
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

/* The period in whole ns (as `hexaglide sim --dt` rounds it), or -1 outside the board's range. */
static long period_ns_of(double period_s)
{
    double ns = period_s * 1e9;
    return ns >= 1.0 && ns <= (double)HG_PERIOD_MAX_NS ? (long)(ns + 0.5) : -1;
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
            sayf(say, env, FMU_SAY_ERROR, "parameter %s = %.9g %s refused: %s", t.name, bp->plant.v[i], t.unit,
                 why[i] ? why[i] : "invalid");
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
    if (!(s->model >= 0 && s->model < fmu_plant_model_count())) {
        char choices[160];
        model_choices(choices, sizeof choices);
        sayf(say, env, FMU_SAY_ERROR, "parameter model = %lld refused: must be %s", s->model, choices);
        bad = 1;
    }
    if (ns < 0) {
        sayf(say, env, FMU_SAY_ERROR, "parameter period = %.9g s refused: must lie in [1e-9, %g] s (the board's "
             "servo period, whole nanoseconds)", s->period_s, (double)HG_PERIOD_MAX_NS * 1e-9);
        bad = 1;
    }
    /* the board's rule for an encoder scale (hg_board.c, encoders()), refused here instead of replaced by 1.0 */
    if (!isfinite(s->enc_scale) || (s->enc_scale < 1e-20 && s->enc_scale > -1e-20)) {
        sayf(say, env, FMU_SAY_ERROR, "parameter enc_scale = %.9g refused: must be a finite non-zero number of "
             "counts per unit", s->enc_scale);
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
    return (double)p->period_ns * 1e-9;   /* what the board integrates (as hexaglide sim) */
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

/* The board's events of one step as messages; the gravest level. */
static int report(const plant *p, const hg_board_outputs *out, fmu_say_fn *say, void *env)
{
    char why[HG_BOARD_TEXT_LEN];
    int k, level = FMU_SAY_INFO;
    if (out->events & HG_EV_SUBSTEPS_AUTO) {
        hg_board_describe_stiffness(&p->b, out, p->period_ns, 0, why);
        sayf(say, env, FMU_SAY_INFO, "%s: running %u substeps per period instead of %u", why, out->substeps_run,
             out->params.substeps);
    }
    if ((out->events & HG_EV_FAULT_LATCHED) && out->fault_cause == HG_FAULT_STIFF) {
        hg_board_describe_stiffness(&p->b, out, p->period_ns, 0, why);
        sayf(say, env, FMU_SAY_WARNING, "the period from t = %.6f s to %.6f s (board time) failed: %s: %s even with "
             "%u substeps; give a softer value, another integrator or a shorter period", out->sim_time_s,
             out->sim_time_s + (double)p->period_ns * 1e-9, why, hg_strerror(out->fault_code), HG_SUBSTEPS_MAX);
        level = FMU_SAY_WARNING;
    } else if (out->events & HG_EV_FAULT_LATCHED) {
        char what[HG_PLANT_TEXT_LEN];
        hg_board_plant(&p->b)->describe(&out->fault_report, 0, what);
        sayf(say, env, FMU_SAY_WARNING, "the period from t = %.6f s to %.6f s (board time) failed: %s (code %d)%s%s; "
             "the board latches the fault (state frozen, drives off) until a rising edge of reset", out->sim_time_s,
             out->sim_time_s + (double)p->period_ns * 1e-9, hg_strerror(out->fault_code), out->fault_code,
             what[0] ? ": " : "", what);
        level = FMU_SAY_WARNING;
    }
    for (k = 0; k < FMU_JOINTS; k++)
        if ((out->dac_nan_new >> k) & 1u) {
            sayf(say, env, FMU_SAY_WARNING, "dac_%d is NaN: the board outputs 0 V until it is a number again", k);
            level = FMU_SAY_WARNING;
        }
    if (out->events & HG_EV_RESET_DONE)
        say(env, FMU_SAY_INFO, "reset: machine at HOME at rest, counters 0, fault cleared");
    return level;
}

int fmu_plant_step(void *plant_bytes, const fmu_plant_inputs *in, fmu_plant_outputs *o, fmu_say_fn *say,
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
    return report(p, &out, say, env);
}
