/* motenc_hexaglide_dyns_virtual.c - HAL glue: a virtual Vital Systems
 * MOTENC-100 board with a machine (a plant: the Hexaglide by default,
 * hg_plant.h) behind its pins.
 *
 * Exports exactly hal_motenc's pins, parameters and functions under
 * motenc.<board>. (LinuxCNC 2.9 src/hal/drivers/hal_motenc.c), plus the
 * function motenc.<board>.dynamics and the inspection / fault-injection
 * pins and the plant's parameters under motenc-hexaglide.<board>.
 * (docs/driver.md). The board itself is hg_board.h: this file only copies
 * pins into hg_board_inputs, calls hg_board_step once per period (in
 * dynamics), copies hg_board_outputs back to pins (each hal_motenc function
 * publishes its own pins) and turns the board's events into RTAPI messages.
 * Pins and parameters live in one hal_malloc'd struct, the core's state in
 * the module's memory (the_core); no malloc, no stdio. */
#include "rtapi.h"
#include "rtapi_app.h"
#include "rtapi_math.h"
#include "rtapi_string.h"
#include "rtapi_errno.h"
#include "hal.h"

#include "hg_errors.h"
#include "hg_board.h"
#include "hg_board_rec.h"
#include "hg_text.h"
#include "hg_units.h"

MODULE_AUTHOR("Virtual Hexaglide project");
MODULE_DESCRIPTION("Virtual MOTENC-100 board driving a simulated machine, the Hexaglide by default (drop-in for hal_motenc)");
MODULE_LICENSE("GPL");

/* Module parameters (RTAPI needs them at file scope; read only at load). */
static char *plant = "hexaglide";
RTAPI_MP_STRING(plant, "the machine behind the board: hexaglide (default) or serial");
static char *model = 0;
RTAPI_MP_STRING(model, "the plant's model: hexaglide standard, reduced-joints, reduced-cartesian (default), fused-cartesian; "
                "serial the axes, 1 to 8 letters of XYZUVW (linear) and ABC (rotary), XYZ the default");
static int board = 0;
RTAPI_MP_INT(board, "board id 0..3, the <board> in motenc.<board>. names");
static int record = 0;
RTAPI_MP_INT(record, "1: also export the record pins motenc-hexaglide.<board>.rec.* and the record parameter (tools/hg_record.py)");

#define MODNAME "motenc_hexaglide_dyns_virtual"
#define XP "motenc-hexaglide"          /* prefix of the pins the real board lacks */
#define SW3(a, b, c) (((a) ? HG_SW_MIN : 0u) | ((b) ? HG_SW_MAX : 0u) | ((c) ? HG_SW_HOME : 0u))

typedef struct {
    hal_s32_t *count; hal_float_t *position; hal_bit_t *index, *index_enable, *reset;
    hal_float_t scale;
} enc_hal;
typedef struct { hal_float_t *value; hal_float_t offset, gain; } analog_hal;
typedef struct {
    hal_float_t *pos, *vel, *motor_pos, *volts, *current, *force, *pos_cmd;
    hal_bit_t *amp_fail, *stuck[3], *tripped[3], *index_lost, *inject[HG_PLANT_INJECT_MAX];
    hal_s32_t *enc_glitch;
} joint_hal;

typedef union { hal_float_t *f; hal_u32_t *u; } extra_pin;

typedef union { hal_float_t *f; hal_s32_t *s; hal_u32_t *u; hal_bit_t *b; } rec_pin;

/* What the core keeps for a board: its state, inputs and outputs, the
 * record tables, a refusal's reasons and the parameter table (about 100 KB). */
typedef struct {
    hg_board b;
    hg_board_inputs ins;
    hg_board_outputs o;
    hg_board_rec_field rec[HG_BOARD_REC_MAX]; /* the record pin set (docs/replay.md; nrec 0 without record=1) */
    hg_board_rec_stream stream;       /* the parameters' events on the rec pins */
    const char *why[HG_BOARD_WHY_LEN]; /* a refusal's reasons (too large for the stack) */
    hg_param_info info[HG_PLANT_PARAMS_MAX]; /* the plant's parameter table as the loaded model has it (units) */
} board_core;

typedef struct {
    enc_hal enc[HG_BOARD_ENCODERS];
    analog_hal dac[HG_BOARD_DACS], adc[HG_BOARD_ADCS];
    hal_bit_t *din[HG_BOARD_INPUTS], *din_not[HG_BOARD_INPUTS];
    hal_bit_t *out[HG_BOARD_OUTPUTS];
    hal_bit_t out_invert[HG_BOARD_OUTPUTS];
    hal_bit_t *estop_in, *estop_in_not, *watchdog_reset;
    hal_u32_t watchdog_control;
    joint_hal joint[HG_CHANNELS_MAX];
    extra_pin extra[HG_PLANT_EXTRA_MAX]; /* the plant's own outputs (its table: head pose, ...) */
    hal_float_t *sim_time, *tool_error;
    hal_u32_t *steps, *step_ns, *step_max_ns, *dout_word, *substeps_run;
    hal_bit_t *fault, *reset, *amps_on, *estop_button, *watchdog_expired, *param_error, *dac_nan;
    hal_s32_t *fault_code;
    hal_s32_t estop_loop_out;
    hal_float_t adc_volts_per_amp;
    hal_float_t par[HG_PLANT_PARAMS_MAX]; /* the plant's parameters in HAL units */
    double shadow[HG_PLANT_PARAMS_MAX]; /* what the glue last wrote there */
    hal_u32_t substeps, integrator;
    hal_bit_t record;                 /* XP.<board>.record: write the rec pins (the recorder sets it;
                                         exists with loadrt record=1 only, else stays 0) */
    board_core *c;                    /* the core's state, in module memory */
    int id;
    rec_pin rec_pin[HG_BOARD_REC_MAX]; /* XP.<board>.rec.<name>, type as c->rec[i].type */
    int nrec;
    int recording;                    /* record was TRUE in the last period */
    hg_board_rate rate;               /* encoder-read's and dynamics' calls (hg_board_rate_read, _step) */
    int nparams;                      /* entries of the plant's parameter table */
} board_t;

/* The board's one core (one board per loadrt): in the module's own memory,
 * not in HAL's shared memory (1 MB in all, which unloadrt never gives
 * back), where only what HAL needs lives: pins, parameters, the board_t. */
static board_core the_core;

static int comp_id;

/* --- hal_motenc's functions: each publishes its pins from the last step --- */

static void encoder_read(void *arg, long period)
{
    board_t *b = arg;
    int ch;
    b->c->ins.dac_stale |= b->c->ins.dac_written;   /* read after the volts were written: wrong addf order */
    if (hg_board_rate_read(&b->rate, period)) { /* two messages: LinuxCNC's error channel keeps
                                                            255 characters of each (EMCMOT_ERROR_LEN) */
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: motenc.%d.dynamics has not run for 1 s while "
                        "motenc.%d.encoder-read runs: nothing moves the machine, the encoders stand still and "
                        "LinuxCNC will trip on following error\n", b->id, b->id, b->id);
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: addf motenc.%d.dynamics servo-thread right after "
                        "motenc.%d.dac-write (the virtual board's own function: hal_motenc has none)\n",
                        b->id, b->id, b->id);
    }
    for (ch = 0; ch < HG_BOARD_ENCODERS; ch++) {
        if (b->c->o.index_latched[ch])
            *b->enc[ch].index_enable = 0; /* the latch fired: cancel index-enable */
        *b->enc[ch].count = b->c->o.count[ch];
        *b->enc[ch].position = b->c->o.position[ch];
        *b->enc[ch].index = b->c->o.index[ch];
    }
}

/* motenc.N.dac-write: the DAC pins through gain and offset into the next step's inputs. */
static void dac_write(void *arg, long period)
{
    board_t *b = arg;
    int ch;
    (void)period;
    for (ch = 0; ch < HG_BOARD_DACS; ch++)
        b->c->ins.dac_v[ch] = (*b->dac[ch].value - b->dac[ch].offset) * b->dac[ch].gain;
    b->c->ins.dac_written = 1;
    b->c->ins.dac_stale = 0;
}

/* motenc.N.adc-read: the last step's current-monitor voltages onto the ADC pins. */
static void adc_read(void *arg, long period)
{
    board_t *b = arg;
    int ch;
    (void)period;
    for (ch = 0; ch < HG_BOARD_ADCS; ch++)
        *b->adc[ch].value = b->c->o.adc[ch];
    b->c->ins.adc_read = 1;
}

/* motenc.N.digital-in-read: the switches and inputs of the last step onto in-NN and in-NN-not. */
static void digital_in_read(void *arg, long period)
{
    board_t *b = arg;
    int i;
    (void)period;
    for (i = 0; i < HG_BOARD_INPUTS; i++) {
        *b->din[i] = b->c->o.in[i];
        *b->din_not[i] = !b->c->o.in[i];
    }
}

/* motenc.N.digital-out-write: the outputs' word as the board read it onto motenc-hexaglide.N.digital-out-word. */
static void digital_out_write(void *arg, long period)
{
    board_t *b = arg;
    (void)period;
    *b->dout_word = b->c->o.dout_word;
}

/* motenc.N.misc-update: the E-STOP input as the board holds it. */
static void misc_update(void *arg, long period)
{
    board_t *b = arg;
    (void)period;
    *b->estop_in = b->c->o.estop_in;
    *b->estop_in_not = !b->c->o.estop_in;
}

/* --- the extra function: one servo period of the board --- */

/* HAL model parameters that changed since the glue wrote them -> in.params
 * (SI); 1 if any did (a setp since the last period). */
static int read_params(board_t *b)
{
    const hg_param_info *t = b->c->info;
    int i, n = b->nparams, changed = 0;
    for (i = 0; i < n; i++) {
        double v = b->par[i];
        if (memcmp(&v, &b->shadow[i], sizeof v) != 0) { // NOLINT(bugprone-suspicious-memory-comparison): bitwise, a NaN a user set equals itself
            b->c->ins.params.plant.v[i] = v / t[i].hal_scale;
            changed = 1;
        }
    }
    changed |= b->c->ins.params.substeps != b->substeps || b->c->ins.params.integrator != b->integrator;
    b->c->ins.params.substeps = b->substeps;
    b->c->ins.params.integrator = b->integrator;
    return changed;
}

/* Show the block in force: every field the board holds differently is written back. */
static void write_params(board_t *b)
{
    const hg_param_info *t = b->c->info;
    int i, n = b->nparams;
    for (i = 0; i < n; i++) {
        double *want = &b->c->ins.params.plant.v[i];
        double got = b->c->o.params.plant.v[i];
        if (memcmp(want, &got, sizeof got) != 0) { // NOLINT(bugprone-suspicious-memory-comparison): bitwise
            *want = got;
            b->par[i] = got * t[i].hal_scale;
        }
        b->shadow[i] = b->par[i];
    }
    b->c->ins.params.substeps = b->substeps = b->c->o.params.substeps;
    b->c->ins.params.integrator = b->integrator = b->c->o.params.integrator;
}

/* Field i of block p as HAL shows it (table units). */
static void field_value(const board_t *b, const hg_board_params *p, int i, char v[HG_TEXT_VALUE_LEN])
{
    hg_text_value(v, hg_board_param_value(p, i) * (i < b->nparams ? b->c->info[i].hal_scale : 1.0));
}

/* One line per field the refused set changed that is not in *said: a rule
 * that names another field may fail because of it (lb 1e-300 fails "e ...
 * smaller than lb"). */
static void report_changed(board_t *b, const hg_bitset *said)
{
    char v[HG_TEXT_VALUE_LEN], was[HG_TEXT_VALUE_LEN];
    int i;
    for (i = 0; i < HG_BOARD_WHY_LEN; i++) {
        const int plant = i < b->nparams;
        if ((!plant && i < HG_BOARD_BIT_SUBSTEPS) || hg_bitset_has(said, i))
            continue;
        if (hg_param_same(hg_board_param_value(&b->c->ins.params, i), hg_board_param_value(&b->c->o.params, i)))
            continue;                  /* unchanged (a NaN kept too) */
        field_value(b, &b->c->ins.params, i, v);
        field_value(b, &b->c->o.params, i, was);
        if (strcmp(v, was) == 0)
            continue;                  /* within the 9 digits shown: the INI's 68.254 mm is 0.068254 m + 1 ulp */
        /* the unit HAL shows: none for a dimensionless one, substeps or the integrator */
        const char *u = plant && strcmp(b->c->info[i].hal_unit, "1") != 0 ? b->c->info[i].hal_unit : "";
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: refused with it: " XP ".%d.%s = %s%s%s, changed from "
                        "%s%s%s in this set\n", b->id, b->id, hg_board_param_hal_name(&b->c->b, i), v, u[0] ? " " : "",
                        u, was, u[0] ? " " : "", u);
    }
}

/* Say, once, why the parameter change was refused: every field, its value, the rule (the set in force
 * stays, and write_params shows it again). */
static void report_refusal(board_t *b, long period)
{
    hg_bitset bad;
    char v[HG_TEXT_VALUE_LEN], why[HG_BOARD_TEXT_LEN];
    const hg_param_info *t = b->c->info;
    int i, n = b->nparams;
    if (b->c->o.param_rc != HG_ERR_BAD_PARAM) {
        char what[HG_BOARD_TEXT_LEN];
        hg_board_describe_stiffness(&b->c->b, &b->c->o, period, 1, what);
        /* two messages: LinuxCNC's error channel keeps 255 characters of each (EMCMOT_ERROR_LEN) */
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: parameter set refused: the step cannot integrate it at "
                        "this period even with %u substeps (code %d); keeping the set in force (halcmd show param "
                        "displays it again)\n", b->id, HG_SUBSTEPS_MAX, b->c->o.param_rc);
        if (what[0]) { /* the parameter by its whole HAL name, and what to change */
            char remedy[HG_BOARD_TEXT_LEN];
            hg_board_stiff_remedy(&b->c->o, "integrator", "period", remedy);
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: refused because " XP ".%d.%s; give %s\n", b->id,
                            b->id, what, remedy);
        }
        hg_bitset_clear(&bad);
        if (b->c->o.stiff_param >= 0)
            hg_bitset_set(&bad, b->c->o.stiff_param);    /* named in the sentence above */
        report_changed(b, &bad);
        return;
    }
    hg_board_params_check(&b->c->b, &b->c->ins.params, &bad, b->c->why);
    /* one message per field, each whole: LinuxCNC shows each as an error of its own */
    for (i = 0; i < HG_BOARD_WHY_LEN; i++) {
        if (!hg_bitset_has(&bad, i))
            continue;
        const int unit = i < n && strcmp(t[i].hal_unit, "1") != 0; /* a dimensionless one has none */
        field_value(b, &b->c->ins.params, i, v);
        why[0] = '\0';
        hg_param_hal_reason(why, sizeof why, b->c->why[i] ? b->c->why[i] : "", i < n ? &t[i] : 0);
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: refused " XP ".%d.%s = %s%s%s: %s\n", b->id, b->id,
                        hg_board_param_hal_name(&b->c->b, i), v, unit ? " " : "", unit ? t[i].hal_unit : "", why);
    }
    report_changed(b, &bad);
}

/* The board's events as RTAPI messages (the same ones as before the core existed). */
static void report(board_t *b, long period)
{
    const hg_board_outputs *o = &b->c->o;
    const hg_plant *pl = hg_board_plant(&b->c->b);
    int k, i, id = b->id;
    if (o->events & HG_EV_PARAM_REFUSED)
        report_refusal(b, period);
    if ((o->events & HG_EV_GEOMETRY_RESTART) && o->steps > 1) /* not the power-up set's, in the first period */
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: new geometry in force: the machine restarted at "
                        "HOME at rest, and the encoders moved with it (a notice, not a fault)\n", id);
    if (o->events & HG_EV_RESET_REFUSED)
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: reset refused: " XP ".%d.joint-%d.%s "
                        "is TRUE; set it FALSE, then reset again\n", id, id, o->reset_refused_channel,
                        pl->injections[o->reset_refused_injection].hal_name);
    if (o->events & HG_EV_PERIOD_BAD)
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: thread period %ld ns outside (0, %ld]: not "
                        "integrating; put motenc.%d.dynamics in a servo thread of about 1 ms\n",
                        id, period, HG_PERIOD_MAX_NS, id);
    for (i = 0; i < pl->ninjections; i++)
        for (k = 0; k < HG_CHANNELS_MAX; k++)
            if ((o->injected[i] >> k) & 1u)
                rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: joint %d (" XP ".%d.joint-%d.%s) %s\n",
                                id, k, id, k, pl->injections[i].hal_name, pl->injections[i].what);
    for (k = 0; k < HG_BOARD_DACS; k++)
        if ((o->dac_nan_new >> k) & 1u)
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: dac-%02d: (value - offset) * gain is NaN; "
                            "output 0 V until it is a number again\n", id, k);
    if (o->events & HG_EV_WATCHDOG_EXPIRED)
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: the watchdog expired (motenc.%d.watchdog-control "
                        "%u: no watchdog-reset within its %d ms): amplifiers and outputs off until "
                        "motenc.%d.watchdog-reset is set TRUE (or a dac-write, with control bit 16)\n", id, id,
                        b->c->ins.watchdog_control, (int)(1e3 * hg_watchdog_timeout_s(b->c->ins.watchdog_control)
                                                      + 0.5), id);
    for (k = 0; k < HG_CHANNELS_MAX; k++)
        if ((o->pos_cmd_bad_new >> k) & 1u)
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: " XP ".%d.joint-%d.pos-cmd is NaN or inf: "
                            "tool-error reads -1 until motion's command is a number again (net it to "
                            "joint.%d.pos-cmd)\n", id, id, k, k);
    for (k = 0; k < HG_BOARD_ADCS; k++)
        if ((o->adc_nan_new >> k) & 1u)
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: adc-%02d: (current x " XP ".%d.adc-volts-per-amp) "
                            "x gain - offset is not a finite number; adc-%02d-value reads 0 until it is\n",
                            id, k, id, k);
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        if ((o->enc_scale_bad >> k) & 1u)
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: enc-%02d-scale must be finite and at least "
                            HG_ENC_SCALE_MIN_TEXT " counts per unit in magnitude; set to 1.0 (as hal_motenc)\n", id, k);
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        if ((o->enc_scale_odd >> k) & 1u) {    /* (the real board cannot know; the scale is kept) */
            char why[HG_BOARD_TEXT_LEN], v[HG_TEXT_VALUE_LEN];
            hg_board_describe_enc_scale(&b->c->b, k, o->enc_scale[k], why);
            hg_text_value(v, o->enc_scale[k]);
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: motenc.%d.enc-%02d-scale = %s %s; fix "
                            "[JOINT_%d]INPUT_SCALE\n", id, id, k, v, why, k);
        }
    if (o->events & HG_EV_ESTOP_OUT_BAD)
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: " XP ".%d.estop-loop-out = %d refused: the E-STOP loop "
                        "runs through a digital output, 0..31 (out-07 in motenc_io.hal), or -1 for none; keeping "
                        "%d in the loop\n", id, id, b->c->ins.estop_loop_out, o->estop_loop_out);
    if (o->events & HG_EV_ADC_VPA_BAD) {
        char got[HG_TEXT_VALUE_LEN], kept[HG_TEXT_VALUE_LEN];
        hg_text_value(got, b->c->ins.adc_volts_per_amp);
        hg_text_value(kept, o->adc_volts_per_amp);
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: " XP ".%d.adc-volts-per-amp = %s refused: the drives' "
                        "current monitors give a finite, positive number of volts per amp; keeping %s\n", id, id,
                        got, kept);
    }
    if (o->events & HG_EV_ADDF_ORDER)
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: motenc.%d.dynamics ran without a motenc.%d.dac-write "
                        "before it: the machine gets the volts a period late or never; addf motenc.%d.dac-write, "
                        "then motenc.%d.dynamics, after the PIDs in one thread\n", id, id, id, id, id);
    if (o->events & HG_EV_SUBSTEPS_AUTO) {
        char what[HG_BOARD_TEXT_LEN];
        hg_board_describe_stiffness(&b->c->b, o, period, 1, what);
        /* the default 1 asks for what the step needs: said at INFO; more asked and not enough: WARN */
        rtapi_print_msg(o->params.substeps > 1 ? RTAPI_MSG_WARN : RTAPI_MSG_INFO,
                        MODNAME ": board %d: %s: running %u integration steps per period "
                        "(" XP ".%d.substeps-run) instead of the %u asked for\n", id, what, o->substeps_run,
                        id, o->params.substeps);
    }
    if (o->events & HG_EV_FAULT_LATCHED && o->fault_cause == HG_FAULT_STIFF) {
        char what[HG_BOARD_TEXT_LEN], remedy[HG_BOARD_TEXT_LEN];
        hg_board_describe_stiffness(&b->c->b, o, period, 1, what);
        hg_board_stiff_remedy(o, "integrator", 0, remedy);   /* the thread's period is not the board's to change */
        /* two messages: LinuxCNC's error channel keeps 255 characters of each (EMCMOT_ERROR_LEN) */
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: %s (code %d)\n", id, what, o->fault_code);
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: the step cannot integrate these parameters at this "
                        "period even with %u substeps: drives off; set %s, then " XP ".%d.reset\n",
                        id, HG_SUBSTEPS_MAX, remedy, id);
    } else if (o->events & HG_EV_FAULT_LATCHED && o->fault_cause == HG_FAULT_PERIOD) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: bad thread period (code %d): drives off, state "
                        "frozen; run motenc.%d.dynamics in a thread of at most %ld ns, then set " XP ".%d.reset\n",
                        id, o->fault_code, id, HG_PERIOD_MAX_NS, id);
    } else if (o->events & HG_EV_FAULT_LATCHED) {
        static const char tail[] = "; drives off, state frozen; set " XP ".00.reset to restart at HOME";
        const char *cause = o->fault_cause == HG_FAULT_HOME ? "reset at HOME failed"
                            : o->fault_report.kind ? "the machine struck a mechanical limit" : "dynamics step failed";
        char what[HG_PLANT_TEXT_LEN];
        pl->describe(&o->fault_report, 1, what);
        /* what struck says more than the code's text, but LinuxCNC's error
         * channel keeps only the first 255 characters of a message: a long
         * one is said in two (the length with two-digit board numbers and a
         * three-digit code) */
        if (strlen(MODNAME ": board 00:  (code -00): ") + strlen(cause) + strlen(what) + sizeof tail > 255) {
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: %s (code %d): %s\n", id, cause, o->fault_code,
                            what);
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: drives off, state frozen; set " XP ".%d.reset to "
                            "restart at HOME\n", id, id);
        } else {
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: %s (code %d): %s; drives off, state frozen; "
                            "set " XP ".%d.reset to restart at HOME\n", id, cause,
                            o->fault_code, what[0] ? what : hg_strerror(o->fault_code), id);
        }
    }
}

/* The extra pins from the last outputs (mm, mm/s, degrees on HAL). */
static void publish(board_t *b)
{
    const hg_board_outputs *o = &b->c->o;
    const hg_plant *pl = hg_board_plant(&b->c->b);
    int k;
    for (k = 0; k < o->channels; k++) {
        joint_hal *j = &b->joint[k];
        double unit = (o->rotary >> k) & 1u ? HG_DEG_PER_RAD : HG_MM_PER_M; /* machine units */
        *j->pos = o->pos[k] * unit;
        *j->vel = o->vel[k] * unit;
        *j->motor_pos = o->motor_pos[k] * unit;
        *j->volts = o->volts[k];
        *j->current = o->current_a[k];
        *j->force = o->force[k];
    }
    for (k = 0; k < pl->noutputs; k++) {
        if (pl->outputs[k].is_u32)
            *b->extra[k].u = (hal_u32_t)o->extra[k];
        else
            *b->extra[k].f = o->extra[k] * pl->outputs[k].hal_scale;
    }
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        b->enc[k].scale = o->enc_scale[k];
    *b->sim_time = o->sim_time_s;
    *b->tool_error = o->tool_error < 0.0 ? -1.0 : o->tool_error * HG_MM_PER_M;
    *b->steps = o->steps;
    *b->substeps_run = o->substeps_run;
    *b->fault = o->fault;
    *b->fault_code = o->fault_code;
    *b->amps_on = o->amps_on;
    *b->watchdog_expired = o->watchdog_expired;
    *b->param_error = o->param_error;
    *b->dac_nan = o->dac_nan;
    /* a refused value is shown replaced by the one in force; only then, so that a setp landing
     * between the step's read and here is not overwritten */
    if (o->events & HG_EV_ESTOP_OUT_BAD)
        b->estop_loop_out = o->estop_loop_out;
    if (o->events & HG_EV_ADC_VPA_BAD)
        b->adc_volts_per_amp = o->adc_volts_per_amp;
}

/* The record pins: this step's inputs, period and outputs, exactly. */
static void write_rec(board_t *b, long period)
{
    hg_board_rec_ctx c;
    int i;
    if (!b->recording)                /* record rose: the parameters' stream starts again */
        hg_board_rec_stream_start(&b->c->stream, b->c->b.plant, b->c->b.variant);
    hg_board_rec_stream_step(&b->c->stream, &b->c->ins.params, b->nparams);
    c.in = &b->c->ins;
    c.out = &b->c->o;
    c.period_ns = period;
    c.plant = b->c->b.plant;
    c.variant = b->c->b.variant;
    c.stream = &b->c->stream;
    for (i = 0; i < b->nrec; i++) {
        double v = hg_board_rec_get(b->c->rec, b->nrec, i, &c);
        switch (b->c->rec[i].type) {
        case HG_BRF_F64: *b->rec_pin[i].f = v; break;
        case HG_BRF_S32: *b->rec_pin[i].s = (hal_s32_t)v; break;
        case HG_BRF_BIT: *b->rec_pin[i].b = v != 0.0; break;
        default: *b->rec_pin[i].u = (hal_u32_t)v; break;
        }
    }
}

/* motenc.N.dynamics: one servo period of the board (hg_board_step) and what it reports. */
static void dynamics(void *arg, long period)
{
    board_t *b = arg;
    hg_board_inputs *in = &b->c->ins;
    long long t0 = rtapi_get_time(), dt_ns;
    int k, changed;
    if (hg_board_rate_step(&b->rate)) { /* two messages: LinuxCNC's error channel keeps 255
                                                          characters of each (EMCMOT_ERROR_LEN) */
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: motenc.%d.dynamics runs less often than "
                        "motenc.%d.encoder-read (its thread is slower): the encoders move every few periods and "
                        "the volts between are lost; the PID loops will trip on following error\n",
                        b->id, b->id, b->id);
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: addf motenc.%d.dynamics to the servo thread, right "
                        "after motenc.%d.dac-write (a thread of its own may be faster, not slower)\n",
                        b->id, b->id, b->id);
    }
    if (hg_board_rate_unread(&b->rate, period)) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: motenc.%d.encoder-read has not run for 1 s while "
                        "motenc.%d.dynamics runs: the machine moves but the encoder counts and switches on the "
                        "pins stand still, and LinuxCNC will trip on following error\n", b->id, b->id, b->id);
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: addf motenc.%d.encoder-read servo-thread first, "
                        "before motion-command-handler (as hal_motenc's)\n", b->id, b->id);
    }
    in->dout_values = in->dout_inverts = 0;
    for (k = 0; k < HG_BOARD_OUTPUTS; k++) {
        in->dout_values |= (*b->out[k] ? 1u : 0u) << k;
        in->dout_inverts |= (b->out_invert[k] ? 1u : 0u) << k;
    }
    in->estop_loop_out = b->estop_loop_out;
    in->estop_button = *b->estop_button;
    in->reset = *b->reset;
    in->watchdog_control = b->watchdog_control;
    in->watchdog_reset = *b->watchdog_reset;
    for (k = 0; k < HG_BOARD_ENCODERS; k++) {
        in->index_enable[k] = *b->enc[k].index_enable;
        in->enc_reset[k] = *b->enc[k].reset;
        in->enc_scale[k] = b->enc[k].scale;
    }
    for (k = 0; k < HG_BOARD_ADCS; k++) {
        in->adc_gain[k] = b->adc[k].gain;
        in->adc_offset[k] = b->adc[k].offset;
    }
    in->adc_volts_per_amp = b->adc_volts_per_amp;
    for (k = 0; k < b->c->o.channels; k++) {
        joint_hal *j = &b->joint[k];
        int i;
        in->amp_fail[k] = *j->amp_fail;
        in->stuck[k] = SW3(*j->stuck[0], *j->stuck[1], *j->stuck[2]);
        in->tripped[k] = SW3(*j->tripped[0], *j->tripped[1], *j->tripped[2]);
        in->index_lost[k] = *j->index_lost;
        in->enc_glitch[k] = *j->enc_glitch;
        in->pos_cmd[k] = *j->pos_cmd / ((b->c->o.rotary >> k) & 1u ? HG_DEG_PER_RAD : HG_MM_PER_M);
        in->inject[k] = 0;
        for (i = 0; i < hg_board_plant(&b->c->b)->ninjections; i++)
            in->inject[k] |= (*j->inject[i] ? 1u : 0u) << i;
    }
    changed = read_params(b);

    hg_board_step(&b->c->b, in, &b->c->o, period);
    if (b->record)
        write_rec(b, period);
    b->recording = b->record;

    in->dac_written = in->dac_stale = in->adc_read = 0;
    for (k = 0; k < b->c->o.channels; k++)
        if (in->enc_glitch[k])
            *b->joint[k].enc_glitch = 0;  /* applied once */
    if (b->c->o.events & HG_EV_WATCHDOG_KICKED)
        *b->watchdog_reset = 0;
    if (b->c->o.events & HG_EV_RESET_DONE) {
        *b->step_max_ns = 0;
        memset(&b->rate, 0, sizeof b->rate); /* said again after a reset, as the addf order */
    }
    report(b, period);
    if (changed || (b->c->o.events & (HG_EV_PARAM_REFUSED | HG_EV_PARAM_APPLIED | HG_EV_RESET_DONE)))
        write_params(b);              /* show the block in force only when it may differ */
    publish(b);

    dt_ns = rtapi_get_time() - t0;
    dt_ns = dt_ns < 0 ? 0 : dt_ns > 0xffffffffLL ? 0xffffffffLL : dt_ns;
    *b->step_ns = (hal_u32_t)dt_ns;
    if (*b->step_ns > *b->step_max_ns)
        *b->step_max_ns = *b->step_ns;
}

/* --- export --- */

#define TRY(call) do { if ((rc = (call)) != 0) return rc; } while (0)
#define PIN(type, dir, ptr, ...) TRY(hal_pin_##type##_newf(dir, ptr, comp_id, __VA_ARGS__))
#define PAR(type, ptr, ...) TRY(hal_param_##type##_newf(HAL_RW, ptr, comp_id, __VA_ARGS__))

/* n analog channels <kind>-CC-value (pin, dir) with -offset and -gain. */
static int export_analog(int id, analog_hal *a, int n, hal_pin_dir_t dir, const char *kind)
{
    int rc, ch;
    for (ch = 0; ch < n; ch++) {
        PIN(float, dir, &a[ch].value, "motenc.%d.%s-%02d-value", id, kind, ch);
        PAR(float, &a[ch].offset, "motenc.%d.%s-%02d-offset", id, kind, ch);
        PAR(float, &a[ch].gain, "motenc.%d.%s-%02d-gain", id, kind, ch);
        a[ch].offset = 0.0;
        a[ch].gain = 1.0;
    }
    return 0;
}

/* Export function motenc.<board>.<what>. */
static int export_funct(board_t *b, const char *what, void (*f)(void *, long), int uses_fp)
{
    char name[HAL_NAME_LEN + 1];
    rtapi_snprintf(name, sizeof name, "motenc.%d.%s", b->id, what);
    return hal_export_funct(name, f, b, uses_fp, 0, comp_id);
}

/* hal_motenc's pins, parameters and functions, in its order. */
static int export_motenc(board_t *b)
{
    int rc, ch, id = b->id;
    for (ch = 0; ch < HG_BOARD_ENCODERS; ch++) {
        enc_hal *p = &b->enc[ch];
        PIN(s32, HAL_OUT, &p->count, "motenc.%d.enc-%02d-count", id, ch);
        PIN(float, HAL_OUT, &p->position, "motenc.%d.enc-%02d-position", id, ch);
        PIN(bit, HAL_OUT, &p->index, "motenc.%d.enc-%02d-index", id, ch);
        PIN(bit, HAL_IO, &p->index_enable, "motenc.%d.enc-%02d-index-enable", id, ch);
        PIN(bit, HAL_IN, &p->reset, "motenc.%d.enc-%02d-reset", id, ch);
        PAR(float, &p->scale, "motenc.%d.enc-%02d-scale", id, ch);
        p->scale = 1.0;
    }
    TRY(export_funct(b, "encoder-read", encoder_read, 1));
    TRY(export_analog(id, b->dac, HG_BOARD_DACS, HAL_IN, "dac"));
    TRY(export_funct(b, "dac-write", dac_write, 1));
    TRY(export_analog(id, b->adc, HG_BOARD_ADCS, HAL_OUT, "adc"));
    TRY(export_funct(b, "adc-read", adc_read, 1));
    for (ch = 0; ch < HG_BOARD_INPUTS; ch++) {
        PIN(bit, HAL_OUT, &b->din[ch], "motenc.%d.in-%02d", id, ch);
        PIN(bit, HAL_OUT, &b->din_not[ch], "motenc.%d.in-%02d-not", id, ch);
    }
    TRY(export_funct(b, "digital-in-read", digital_in_read, 0));
    for (ch = 0; ch < HG_BOARD_OUTPUTS; ch++) {
        PIN(bit, HAL_IN, &b->out[ch], "motenc.%d.out-%02d", id, ch);
        PAR(bit, &b->out_invert[ch], "motenc.%d.out-%02d-invert", id, ch);
    }
    TRY(export_funct(b, "digital-out-write", digital_out_write, 0));
    PIN(bit, HAL_OUT, &b->estop_in, "motenc.%d.estop-in", id);
    PIN(bit, HAL_OUT, &b->estop_in_not, "motenc.%d.estop-in-not", id);
    PIN(bit, HAL_IO, &b->watchdog_reset, "motenc.%d.watchdog-reset", id);
    PAR(u32, &b->watchdog_control, "motenc.%d.watchdog-control", id);
    TRY(export_funct(b, "misc-update", misc_update, 0));
    return 0;
}

/* One OUT pin XP.<board>.rec.<name> per record field (hg_board_rec.h). */
static int export_rec(board_t *b)
{
    int rc, i;
    b->nrec = hg_board_rec_fields(b->c->rec, HG_BOARD_REC_MAX, b->c->b.plant, b->c->b.variant, HG_BOARD_REC_FORMAT);
    if (b->nrec < 0)
        return -EINVAL;
    for (i = 0; i < b->nrec; i++) {
        const char *n = b->c->rec[i].name;
        rec_pin *p = &b->rec_pin[i];
        switch (b->c->rec[i].type) {
        case HG_BRF_F64: TRY(hal_pin_float_newf(HAL_OUT, &p->f, comp_id, XP ".%d.rec.%s", b->id, n)); break;
        case HG_BRF_S32: TRY(hal_pin_s32_newf(HAL_OUT, &p->s, comp_id, XP ".%d.rec.%s", b->id, n)); break;
        case HG_BRF_BIT: TRY(hal_pin_bit_newf(HAL_OUT, &p->b, comp_id, XP ".%d.rec.%s", b->id, n)); break;
        default: TRY(hal_pin_u32_newf(HAL_OUT, &p->u, comp_id, XP ".%d.rec.%s", b->id, n)); break;
        }
    }
    return 0;
}

/* The extra pins, the plant's parameters (its table: HAL name and unit) and dynamics. */
static int export_extra(board_t *b)
{
    static const char *const sw[3] = {"min", "max", "home"};
    const hg_plant *pl = hg_board_plant(&b->c->b);
    int rc, k, i, n = pl->nparams(b->c->b.variant), id = b->id;
    const hg_param_info *t = b->c->info;
    for (k = 0; k < n; k++)
        pl->param(b->c->b.variant, k, &b->c->info[k]);
    for (k = 0; k < b->c->o.channels; k++) {
        joint_hal *j = &b->joint[k];
        PIN(float, HAL_OUT, &j->pos, XP ".%d.joint-%d.pos", id, k);
        PIN(float, HAL_OUT, &j->vel, XP ".%d.joint-%d.vel", id, k);
        PIN(float, HAL_OUT, &j->motor_pos, XP ".%d.joint-%d.motor-pos", id, k);
        PIN(float, HAL_IN, &j->pos_cmd, XP ".%d.joint-%d.pos-cmd", id, k);
        PIN(float, HAL_OUT, &j->volts, XP ".%d.joint-%d.volts", id, k);
        PIN(float, HAL_OUT, &j->current, XP ".%d.joint-%d.current", id, k);
        PIN(float, HAL_OUT, &j->force, XP ".%d.joint-%d.force", id, k);
        PIN(bit, HAL_IN, &j->amp_fail, XP ".%d.joint-%d.amp-fail", id, k);
        for (i = 0; i < 3; i++)
            PIN(bit, HAL_IN, &j->stuck[i], XP ".%d.joint-%d.stuck-%s", id, k, sw[i]);
        for (i = 0; i < 3; i++)
            PIN(bit, HAL_IN, &j->tripped[i], XP ".%d.joint-%d.tripped-%s", id, k, sw[i]);
        PIN(bit, HAL_IN, &j->index_lost, XP ".%d.joint-%d.index-lost", id, k);
        PIN(s32, HAL_IO, &j->enc_glitch, XP ".%d.joint-%d.enc-glitch", id, k);
        for (i = 0; i < pl->ninjections && i < HG_PLANT_INJECT_MAX; i++)
            PIN(bit, HAL_IN, &j->inject[i], XP ".%d.joint-%d.%s", id, k, pl->injections[i].hal_name);
    }
    for (k = 0; k < pl->noutputs && k < HG_PLANT_EXTRA_MAX; k++) {
        if (pl->outputs[k].is_u32)
            PIN(u32, HAL_OUT, &b->extra[k].u, XP ".%d.%s", id, pl->outputs[k].hal_name);
        else
            PIN(float, HAL_OUT, &b->extra[k].f, XP ".%d.%s", id, pl->outputs[k].hal_name);
    }
    PIN(float, HAL_OUT, &b->sim_time, XP ".%d.sim-time", id);
    PIN(float, HAL_OUT, &b->tool_error, XP ".%d.tool-error", id);
    PIN(u32, HAL_OUT, &b->steps, XP ".%d.steps", id);
    PIN(u32, HAL_OUT, &b->substeps_run, XP ".%d.substeps-run", id);
    PIN(u32, HAL_OUT, &b->step_ns, XP ".%d.step-time-ns", id);
    PIN(u32, HAL_IO, &b->step_max_ns, XP ".%d.step-time-max-ns", id);
    PIN(bit, HAL_OUT, &b->fault, XP ".%d.fault", id);
    PIN(s32, HAL_OUT, &b->fault_code, XP ".%d.fault-code", id);
    PIN(bit, HAL_IN, &b->reset, XP ".%d.reset", id);
    PIN(bit, HAL_OUT, &b->amps_on, XP ".%d.amps-on", id);
    PIN(bit, HAL_IN, &b->estop_button, XP ".%d.estop-button", id);
    PIN(bit, HAL_OUT, &b->watchdog_expired, XP ".%d.watchdog-expired", id);
    PIN(bit, HAL_OUT, &b->param_error, XP ".%d.param-error", id);
    PIN(bit, HAL_OUT, &b->dac_nan, XP ".%d.dac-nan", id);
    PIN(u32, HAL_OUT, &b->dout_word, XP ".%d.digital-out-word", id);
    PAR(float, &b->adc_volts_per_amp, XP ".%d.adc-volts-per-amp", id);
    PAR(s32, &b->estop_loop_out, XP ".%d.estop-loop-out", id);
    b->estop_loop_out = b->c->ins.estop_loop_out;
    b->adc_volts_per_amp = b->c->ins.adc_volts_per_amp;
    for (k = 0; k < n; k++) {
        PAR(float, &b->par[k], XP ".%d.%s", id, t[k].hal_name);
        b->par[k] = b->shadow[k] = b->c->o.params.plant.v[k] * t[k].hal_scale;
    }
    b->nparams = n;
    PAR(u32, &b->substeps, XP ".%d.substeps", id);
    PAR(u32, &b->integrator, XP ".%d.integrator", id);
    b->substeps = b->c->o.params.substeps;
    b->integrator = b->c->o.params.integrator;
    if (record) {                     /* asked for at loadrt: the recorder's pins */
        PAR(bit, &b->record, XP ".%d.record", id);
        TRY(export_rec(b));
    }
    TRY(export_funct(b, "dynamics", dynamics, 1));
    return 0;
}

int rtapi_app_main(void)
{
    board_t *b;
    int rc, k, pi = hg_plant_find(plant), kind;
    const hg_plant *pl = hg_plant_at(pi);

    if (!pl) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": plant=%s unknown; use", plant);
        for (k = 0; hg_plant_at(k); k++)
            rtapi_print_msg(RTAPI_MSG_ERR, "%s %s", k ? "," : "", hg_plant_at(k)->name);
        rtapi_print_msg(RTAPI_MSG_ERR, "\n");
        return -EINVAL;
    }
    kind = hg_plant_variant(pl, model);
    if (kind < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": model=%s unknown for plant=%s; use %s\n", model, pl->name,
                        pl->variants_help);
        return -EINVAL;
    }
    if (board < 0 || board > 3) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board=%d: a MOTENC board id is 0..3\n", board);
        return -EINVAL;
    }
    if (record != 0 && record != 1) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": record=%d: use record=1 to export the record pins, "
                        "or leave it out\n", record);
        return -EINVAL;
    }
    comp_id = hal_init(MODNAME);
    if (comp_id < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": hal_init() failed\n");
        return -EINVAL;
    }
    b = hal_malloc(sizeof *b);
    if (!b) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": hal_malloc(%lu) failed\n", (unsigned long)sizeof *b);
        hal_exit(comp_id);
        return -ENOMEM;
    }
    memset(b, 0, sizeof *b);
    memset(&the_core, 0, sizeof the_core);
    b->c = &the_core;
    b->id = board;
    rc = hg_board_init(&b->c->b, pi, kind, 0);
    if (rc) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": default model refused: %s\n", hg_strerror(rc));
        hal_exit(comp_id);
        return -EINVAL;
    }
    hg_board_inputs_default(&b->c->b, &b->c->ins);
    hg_board_peek(&b->c->b, &b->c->o);
    rc = export_motenc(b);
    if (!rc)
        rc = export_extra(b);
    if (rc) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": exporting pins failed (%d)\n", rc);
        hal_exit(comp_id);
        return rc;
    }
    publish(b);                       /* power-up values of every pin */
    encoder_read(b, 0);
    digital_in_read(b, 0);
    misc_update(b, 0);
    {
        char vn[HG_PLANT_TEXT_LEN];
        pl->variant_name(kind, vn, (int)sizeof vn);
        rtapi_print_msg(RTAPI_MSG_INFO, MODNAME ": board %d, plant %s, model %s, ready\n", board, pl->name, vn);
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    hal_exit(comp_id);
}
