/* motenc_hexaglide_dyns_virtual.c - HAL glue: a virtual Vital Systems
 * MOTENC-100 board with the Hexaglide behind its pins.
 *
 * Exports exactly hal_motenc's pins, parameters and functions under
 * motenc.<board>. (LinuxCNC 2.9 src/hal/drivers/hal_motenc.c), plus the
 * function motenc.<board>.dynamics, which drives joints 0..5 with DAC
 * channels 0..5 and integrates one step of the machine per servo period,
 * and inspection / fault-injection pins and the model parameters under
 * motenc-hexaglide.<board>. (docs/driver.md).
 *
 * Thin glue: the dynamics are hg_dynamics.h, the board's converters and
 * sensors hg_sensors.h. All state lives in one hal_malloc'd struct; the
 * thread functions have no malloc, no stdio and fixed loop bounds. */
#include "rtapi.h"
#include "rtapi_app.h"
#include "rtapi_string.h"
#include "rtapi_errno.h"
#include "hal.h"

#include <math.h>
#include <stddef.h>
#include "hg_errors.h"
#include "hg_params.h"
#include "hg_dynamics.h"
#include "hg_sensors.h"
#include "hg_units.h"

MODULE_AUTHOR("Virtual Hexaglide project");
MODULE_DESCRIPTION("Virtual MOTENC-100 board driving a simulated Hexaglide (drop-in for hal_motenc)");
MODULE_LICENSE("GPL");

/* Module parameters (RTAPI needs them at file scope; read only at load). */
static char *model = "reduced-cartesian";
RTAPI_MP_STRING(model, "parametrization: standard, reduced-joints, reduced-cartesian, fused-cartesian");
static int board = 0;
RTAPI_MP_INT(board, "board id 0..3, the <board> in motenc.<board>. names");

#define MODNAME "motenc_hexaglide_dyns_virtual"
#define XP "motenc-hexaglide"          /* prefix of the pins the real board lacks */
#define MAX_PERIOD_NS ((long)(HG_DT_MAX_S * 1e9)) /* longest step hg_step takes */

/* --- hal_motenc's pins and parameters, same names, types, directions --- */
typedef struct {
    hal_s32_t *count;
    hal_float_t *position;
    hal_bit_t *index;
    hal_bit_t *index_enable;          /* IO: motion sets it, the index clears it */
    hal_bit_t *reset;
    hal_float_t scale;
    double old_scale, scale_recip;
} enc_hal;

typedef struct { hal_float_t *value; hal_float_t offset, gain; } analog_hal;
typedef struct { hal_bit_t *value, *value_not; } din_hal;
typedef struct { hal_bit_t *value; hal_bit_t invert; } dout_hal;

/* --- pins of one joint under motenc-hexaglide.<board>.joint-N. --- */
typedef struct {
    hal_float_t *pos_mm, *vel_mmps;   /* true carriage position and velocity */
    hal_float_t *volts, *current_a, *force_n; /* drive volts applied, motor current, net force */
    hal_bit_t *amp_fail;              /* IN: amplifier of this joint failed */
    hal_bit_t *stuck_min, *stuck_max, *stuck_home; /* IN: switch frozen at its reading */
    hal_bit_t *tripped_min, *tripped_max, *tripped_home; /* IN: switch reads tripped anywhere */
    hal_bit_t *index_lost;            /* IN: index pulses not seen */
    hal_s32_t *enc_glitch;            /* IO: counts added once, then cleared */
    hal_bit_t *bar_broken;            /* IN: bar N breaks (its constraint is removed) */
} joint_hal;

typedef struct {
    /* hal_motenc interface */
    enc_hal enc[HG_BOARD_ENCODERS];
    analog_hal dac[HG_BOARD_DACS];
    analog_hal adc[HG_BOARD_ADCS];
    din_hal in[HG_BOARD_INPUTS];
    dout_hal out[HG_BOARD_OUTPUTS];
    hal_bit_t *estop_in, *estop_in_not, *watchdog_reset;
    hal_u32_t watchdog_control;
    /* extra pins and parameters */
    joint_hal joint[HG_BOARD_JOINTS];
    hal_float_t *head[6];             /* X Y Z (mm) A B C (deg) */
    hal_float_t *sim_time_s, *residual_m;
    hal_u32_t *steps, *step_ns, *step_max_ns;
    hal_bit_t *fault, *reset, *amps_on, *estop_button, *watchdog_expired;
    hal_bit_t *param_error, *dac_garbage;
    hal_s32_t *fault_code;
    hal_u32_t *dout_word;
    hal_u32_t *bars_broken;           /* OUT: bit N = bar N broken in the model */
    hal_s32_t estop_loop_out;         /* output in the E-STOP loop, -1 none */
    hal_float_t adc_volts_per_amp;
    hg_params hal_p;                  /* the model parameters as HAL sees them */
    /* private state */
    hg_model m, m_new;
    hg_data d, d_saved;
    hg_params refused;                /* last parameter set refused (logged once) */
    hg_params candidate;              /* the set being checked */
    hg_encoder encoder[HG_BOARD_ENCODERS];
    hg_watchdog wd;
    unsigned switches[HG_BOARD_JOINTS];
    double dac_out_v[HG_BOARD_DACS];  /* what the DACs output after dac-write */
    double adc_sample_v[HG_BOARD_ADCS];
    int adc_state;
    int have_refused, prev_reset, dac_nan_logged[HG_BOARD_DACS];
    int id;
} board_t;

static int comp_id;

/* Finite x, or 0 (nothing non-finite reaches a pin). */
static double finite_or_zero(double x) { return isfinite(x) ? x : 0.0; }

/* Latch the fault with code rc and say why on the RTAPI log (once). */
static void latch_fault(board_t *b, int rc, const char *what)
{
    if (!*b->fault)
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: %s: %s (code %d); drives off, "
                        "state frozen; set " XP ".%d.reset to restart at HOME\n",
                        b->id, what, hg_strerror(rc), rc, b->id);
    *b->fault = 1;
    *b->fault_code = rc;
}

/* Machine at HOME at rest, counters at 0, fault and timing cleared. */
static void reinit_at_home(board_t *b)
{
    int k, rc = hg_data_reset(&b->m, &b->d);
    *b->fault = 0;
    *b->fault_code = 0;
    *b->step_max_ns = 0;
    *b->param_error = b->have_refused;
    if (rc)
        latch_fault(b, rc, "reset at HOME failed");
    for (k = 0; k < HG_BOARD_ENCODERS; k++) {
        double z = k < HG_BOARD_JOINTS ? b->d.z_m[k] : 0.0;
        hg_encoder_init(&b->encoder[k], z, b->m.p.lead_m, b->m.p.counts_per_rev);
    }
    for (k = 0; k < HG_BOARD_JOINTS; k++)
        b->switches[k] = hg_switches(&b->m.p, b->d.z_m[k]);
}

/* Apply changed HAL model parameters if hg_params_check accepts them;
 * refuse (log once, param-error) otherwise. New geometry restarts at HOME;
 * h follows l, lb, lp (as in the command line) unless it was set too. */
static void apply_params(board_t *b)
{
    const char *field = "?", *why = "?";
    int k, rc, geometry_changed;
    double old_lead = b->m.p.lead_m, old_cpr = b->m.p.counts_per_rev;
    /* bitwise on purpose: a NaN a user set must compare equal to itself;
     * hg_params is all doubles, no padding */
    if (b->have_refused && memcmp(&b->hal_p, &b->refused, sizeof b->hal_p) == 0) // NOLINT(bugprone-suspicious-memory-comparison)
        return;                       /* same refused set: already said so */
    b->candidate = b->hal_p;
    hg_params_keep_home(&b->candidate, &b->m.p);
    rc = hg_model_init(&b->m_new, &b->candidate, b->m.kind, &field, &why);
    if (rc) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: parameter %s refused: %s (%s); "
                        "keeping the previous parameter set\n", b->id,
                        rc == HG_ERR_BAD_PARAM ? field : "set", rc == HG_ERR_BAD_PARAM ? why : "",
                        hg_strerror(rc));
        b->refused = b->hal_p;
        b->have_refused = 1;
        *b->param_error = 1;
        return;
    }
    geometry_changed = memcmp(&b->m_new.p.geo, &b->m.p.geo, sizeof b->m.p.geo) != 0; // NOLINT(bugprone-suspicious-memory-comparison): bitwise change test, all doubles
    b->m = b->m_new;
    b->hal_p = b->m.p;                /* as the model holds them: no re-apply next cycle */
    b->have_refused = 0;
    *b->param_error = 0;
    if (geometry_changed) {
        rtapi_print_msg(RTAPI_MSG_INFO, MODNAME ": board %d: new geometry, machine restarted at HOME\n", b->id);
        reinit_at_home(b);
    } else if (old_lead != b->m.p.lead_m || old_cpr != b->m.p.counts_per_rev) {
        for (k = 0; k < HG_BOARD_JOINTS; k++)
            hg_encoder_rescale(&b->encoder[k], b->d.z_m[k], b->m.p.lead_m, b->m.p.counts_per_rev);
    }
}

/* 1 when the board's E-STOP loop is open: the E-STOP button is pressed, or
 * the loop output (estop-loop-out, iocontrol's user-enable-out in the stock
 * motenc_io.hal) is off. The commanded output (pin xor invert) counts, so
 * the loop can close although an open loop switches the outputs off. */
static int estop_active(const board_t *b)
{
    int o = b->estop_loop_out;
    if (*b->estop_button)
        return 1;
    return o >= 0 && o < HG_BOARD_OUTPUTS && *b->out[o].value == b->out[o].invert;
}

/* --- hal_motenc's functions --- */

static void encoder_read(void *arg, long period)
{
    board_t *b = arg;
    int ch;
    (void)period;
    for (ch = 0; ch < HG_BOARD_ENCODERS; ch++) {
        enc_hal *p = &b->enc[ch];
        hg_encoder *e = &b->encoder[ch];
        if (*p->reset)
            hg_encoder_zero(e);
        *p->index = e->index_pulse;
        if (e->latch_hit)
            *p->index_enable = 0;     /* the latch fired: cancel index-enable */
        hg_encoder_arm(e, *p->index_enable);
        *p->count = hg_encoder_count(e);
        if (p->scale != p->old_scale) {
            if (!isfinite(p->scale) || (p->scale < 1e-20 && p->scale > -1e-20)) {
                rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: enc-%02d-scale must be a finite "
                                "non-zero number of counts per unit; set to 1.0 (as hal_motenc)\n",
                                b->id, ch);
                p->scale = 1.0;
                *b->param_error = 1;
            }
            p->old_scale = p->scale;
            p->scale_recip = 1.0 / p->scale;
        }
        *p->position = *p->count * p->scale_recip;
    }
}

static void dac_write(void *arg, long period)
{
    board_t *b = arg;
    int ch, garbage, any = 0;
    (void)period;
    for (ch = 0; ch < HG_BOARD_DACS; ch++) {
        double v = hg_dac_volts(*b->dac[ch].value, b->dac[ch].offset, b->dac[ch].gain, &garbage);
        if (garbage && !b->dac_nan_logged[ch])
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: dac-%02d: (value - offset) * gain "
                            "is NaN; output 0 V until it is a number again\n", b->id, ch);
        b->dac_nan_logged[ch] = garbage;
        any |= garbage;
        b->dac_out_v[ch] = hg_dac_output(v);
    }
    *b->dac_garbage = any;
    hg_watchdog_dac_write(&b->wd);
}

/* Signal at ADC channel ch: motor current monitors of joints 0..5. */
static double adc_signal(const board_t *b, int ch)
{
    return ch < HG_BOARD_JOINTS ? b->d.current_a[ch] * b->adc_volts_per_amp : 0.0;
}

/* Publish the 4 channels converted last call, start the other 4 (as the
 * real board: each group of 4 takes two calls). */
static void adc_read(void *arg, long period)
{
    board_t *b = arg;
    int i, done = b->adc_state == 1 ? 0 : 4, next = b->adc_state == 1 ? 4 : 0;
    (void)period;
    if (b->adc_state != 0)
        for (i = done; i < done + 4; i++)
            *b->adc[i].value = hg_adc_value(b->adc_sample_v[i], b->adc[i].gain, b->adc[i].offset);
    for (i = next; i < next + 4; i++)
        b->adc_sample_v[i] = hg_adc_sample(adc_signal(b, i));
    b->adc_state = b->adc_state == 1 ? 2 : 1;
}

static void digital_in_read(void *arg, long period)
{
    board_t *b = arg;
    int i;
    (void)period;
    for (i = 0; i < HG_BOARD_INPUTS; i++) {
        int k = i / HG_INPUTS_PER_JOINT, bit = i % HG_INPUTS_PER_JOINT, v = 0;
        if (k < HG_BOARD_JOINTS)
            v = bit == HG_IN_AMP_FAULT ? (*b->joint[k].amp_fail != 0)
                                       : ((b->switches[k] >> bit) & 1u);
        *b->in[i].value = v;
        *b->in[i].value_not = !v;
    }
}

static void digital_out_write(void *arg, long period)
{
    board_t *b = arg;
    hal_u32_t word = 0;
    int j;
    (void)period;
    for (j = 0; j < HG_BOARD_OUTPUTS; j++)
        if (*b->out[j].value != b->out[j].invert)
            word |= (hal_u32_t)1 << j;
    /* E-STOP and an expired watchdog switch the outputs off in hardware */
    *b->dout_word = (estop_active(b) || b->wd.expired) ? 0 : word;
}

static void misc_update(void *arg, long period)
{
    board_t *b = arg;
    (void)period;
    hg_watchdog_set_control(&b->wd, b->watchdog_control);
    if (*b->watchdog_reset) {
        *b->watchdog_reset = 0;
        hg_watchdog_kick(&b->wd);
    }
    *b->estop_in = estop_active(b);
    *b->estop_in_not = !*b->estop_in;
}

/* --- the extra function: one step of the machine --- */

static void publish(board_t *b, const double volts[6])
{
    double user[6];
    int k;
    for (k = 0; k < HG_BOARD_JOINTS; k++) {
        joint_hal *j = &b->joint[k];
        *j->pos_mm = finite_or_zero(b->d.z_m[k] * HG_MM_PER_M);
        *j->vel_mmps = finite_or_zero(b->d.zd_mps[k] * HG_MM_PER_M);
        *j->volts = finite_or_zero(volts[k]);
        *j->current_a = *b->fault ? 0.0 : finite_or_zero(b->d.current_a[k]); /* drives off */
        *j->force_n = finite_or_zero(b->d.force_n[k]);
    }
    hg_pose_to_user(b->d.pose, user);
    for (k = 0; k < 6; k++)
        *b->head[k] = finite_or_zero(user[k]);
    *b->sim_time_s = finite_or_zero(b->d.t_s);
    *b->residual_m = finite_or_zero(b->d.residual_m);
    *b->bars_broken = b->d.broken_bars;
}

/* 1 if every published state number is finite. */
static int state_finite(const hg_data *d)
{
    int k, ok = isfinite(d->t_s) && isfinite(d->residual_m);
    for (k = 0; k < 6; k++)
        ok = ok && isfinite(d->z_m[k]) && isfinite(d->zd_mps[k]) && isfinite(d->pose[k]) &&
             isfinite(d->posed[k]) && isfinite(d->current_a[k]) && isfinite(d->force_n[k]);
    return ok;
}

/* First joint whose bar-broken pin is TRUE, or -1. */
static int bar_pin_set(const board_t *b)
{
    int k;
    for (k = 0; k < HG_BOARD_JOINTS; k++)
        if (*b->joint[k].bar_broken)
            return k;
    return -1;
}

/* Break the bars whose pins went TRUE (one RTAPI message each); a broken
 * bar stays broken until a reset. */
static void break_bars(board_t *b)
{
    int k;
    for (k = 0; k < HG_BOARD_JOINTS; k++) {
        unsigned bit = 1u << k;
        if (!*b->joint[k].bar_broken || (b->d.broken_bars & bit))
            continue;
        b->d.broken_bars |= bit;
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: bar %d (joint %d) broke (" XP
                        ".%d.joint-%d.bar-broken): the head hangs on the other bars; the fault "
                        "latches when it leaves the volume the model represents\n",
                        b->id, k, k, b->id, k);
    }
}

static void dynamics(void *arg, long period)
{
    board_t *b = arg;
    long long t0 = rtapi_get_time(), dt_ns;
    double volts[6] = {0, 0, 0, 0, 0, 0}, dt = period * 1e-9;
    int k, amps_on, expired;

    if (*b->reset && !b->prev_reset) {
        int k = bar_pin_set(b);
        if (k >= 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: reset refused: " XP
                            ".%d.joint-%d.bar-broken is TRUE; set it FALSE, then reset again\n",
                            b->id, b->id, k);
        } else {
            b->have_refused = 0;
            apply_params(b);
            reinit_at_home(b);
        }
    }
    b->prev_reset = *b->reset;
    if (memcmp(&b->hal_p, &b->m.p, sizeof b->hal_p) != 0) // NOLINT(bugprone-suspicious-memory-comparison): bitwise change test, NaN-safe
        apply_params(b);
    else if (b->have_refused) {       /* put back to the values in force */
        b->have_refused = 0;
        *b->param_error = 0;
    }
    if (period <= 0 || period > MAX_PERIOD_NS) {
        if (!*b->fault)
            rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board %d: thread period %ld ns outside "
                            "(0, %ld]: not integrating; put motenc.%d.dynamics in a servo thread of about 1 ms\n",
                            b->id, period, MAX_PERIOD_NS, b->id);
        latch_fault(b, HG_ERR_BAD_DT, "bad thread period");
        dt = 0;
    }
    expired = hg_watchdog_advance(&b->wd, dt);
    amps_on = !estop_active(b) && !expired && !*b->fault;
    for (k = 0; k < HG_BOARD_JOINTS; k++)
        volts[k] = (amps_on && !*b->joint[k].amp_fail) ? b->dac_out_v[k] : 0.0;
    *b->amps_on = amps_on;
    *b->watchdog_expired = expired;

    if (!*b->fault) {
        int rc;
        break_bars(b);
        b->d_saved = b->d;
        rc = hg_step(&b->m, &b->d, volts, dt);
        if (rc == 0 && !state_finite(&b->d))
            rc = HG_ERR_STATE_NONFINITE;
        if (rc) {
            b->d = b->d_saved;        /* frozen at the last good state */
            latch_fault(b, rc, "dynamics step failed");
        } else {
            ++*b->steps;
        }
    }
    if (*b->fault)
        for (k = 0; k < HG_BOARD_JOINTS; k++)
            volts[k] = 0.0;

    for (k = 0; k < HG_BOARD_JOINTS; k++) {
        joint_hal *j = &b->joint[k];
        unsigned stuck = (*j->stuck_min ? HG_SW_MIN : 0u) | (*j->stuck_max ? HG_SW_MAX : 0u) |
                         (*j->stuck_home ? HG_SW_HOME : 0u);
        unsigned tripped = (*j->tripped_min ? HG_SW_MIN : 0u) | (*j->tripped_max ? HG_SW_MAX : 0u) |
                           (*j->tripped_home ? HG_SW_HOME : 0u);
        hg_encoder_update(&b->encoder[k], b->d.z_m[k], b->m.p.lead_m, b->m.p.counts_per_rev,
                          *j->index_lost);
        if (*j->enc_glitch) {
            hg_encoder_glitch(&b->encoder[k], *j->enc_glitch);
            *j->enc_glitch = 0;
        }
        b->switches[k] = hg_switches_stuck(hg_switches(&b->m.p, b->d.z_m[k]), b->switches[k], stuck)
                         | tripped;
    }
    publish(b, volts);

    dt_ns = rtapi_get_time() - t0;
    if (dt_ns < 0)
        dt_ns = 0;
    if (dt_ns > 0xffffffffLL)
        dt_ns = 0xffffffffLL;
    *b->step_ns = (hal_u32_t)dt_ns;
    if (*b->step_ns > *b->step_max_ns)
        *b->step_max_ns = *b->step_ns;
}

/* --- export --- */

#define TRY(call) do { if ((rc = (call)) != 0) return rc; } while (0)

/* n analog channels <kind>-CC-value (pin, dir) with -offset and -gain. */
static int export_analog(int id, analog_hal *a, int n, hal_pin_dir_t dir, const char *kind)
{
    int rc, ch;
    for (ch = 0; ch < n; ch++) {
        TRY(hal_pin_float_newf(dir, &a[ch].value, comp_id, "motenc.%d.%s-%02d-value", id, kind, ch));
        TRY(hal_param_float_newf(HAL_RW, &a[ch].offset, comp_id, "motenc.%d.%s-%02d-offset", id, kind, ch));
        TRY(hal_param_float_newf(HAL_RW, &a[ch].gain, comp_id, "motenc.%d.%s-%02d-gain", id, kind, ch));
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
        TRY(hal_pin_s32_newf(HAL_OUT, &p->count, comp_id, "motenc.%d.enc-%02d-count", id, ch));
        TRY(hal_pin_float_newf(HAL_OUT, &p->position, comp_id, "motenc.%d.enc-%02d-position", id, ch));
        TRY(hal_pin_bit_newf(HAL_OUT, &p->index, comp_id, "motenc.%d.enc-%02d-index", id, ch));
        TRY(hal_pin_bit_newf(HAL_IO, &p->index_enable, comp_id, "motenc.%d.enc-%02d-index-enable", id, ch));
        TRY(hal_pin_bit_newf(HAL_IN, &p->reset, comp_id, "motenc.%d.enc-%02d-reset", id, ch));
        TRY(hal_param_float_newf(HAL_RW, &p->scale, comp_id, "motenc.%d.enc-%02d-scale", id, ch));
        p->scale = p->old_scale = p->scale_recip = 1.0;
    }
    TRY(export_funct(b, "encoder-read", encoder_read, 1));
    TRY(export_analog(id, b->dac, HG_BOARD_DACS, HAL_IN, "dac"));
    TRY(export_funct(b, "dac-write", dac_write, 1));
    TRY(export_analog(id, b->adc, HG_BOARD_ADCS, HAL_OUT, "adc"));
    TRY(export_funct(b, "adc-read", adc_read, 1));
    for (ch = 0; ch < HG_BOARD_INPUTS; ch++) {
        TRY(hal_pin_bit_newf(HAL_OUT, &b->in[ch].value, comp_id, "motenc.%d.in-%02d", id, ch));
        TRY(hal_pin_bit_newf(HAL_OUT, &b->in[ch].value_not, comp_id, "motenc.%d.in-%02d-not", id, ch));
        *b->in[ch].value_not = 1;
    }
    TRY(export_funct(b, "digital-in-read", digital_in_read, 0));
    for (ch = 0; ch < HG_BOARD_OUTPUTS; ch++) {
        TRY(hal_pin_bit_newf(HAL_IN, &b->out[ch].value, comp_id, "motenc.%d.out-%02d", id, ch));
        TRY(hal_param_bit_newf(HAL_RW, &b->out[ch].invert, comp_id, "motenc.%d.out-%02d-invert", id, ch));
        b->out[ch].invert = 0;
    }
    TRY(export_funct(b, "digital-out-write", digital_out_write, 0));
    TRY(hal_pin_bit_newf(HAL_OUT, &b->estop_in, comp_id, "motenc.%d.estop-in", id));
    TRY(hal_pin_bit_newf(HAL_OUT, &b->estop_in_not, comp_id, "motenc.%d.estop-in-not", id));
    TRY(hal_pin_bit_newf(HAL_IO, &b->watchdog_reset, comp_id, "motenc.%d.watchdog-reset", id));
    TRY(hal_param_u32_newf(HAL_RW, &b->watchdog_control, comp_id, "motenc.%d.watchdog-control", id));
    *b->estop_in_not = 1;
    b->watchdog_control = 0;
    TRY(export_funct(b, "misc-update", misc_update, 0));
    return 0;
}

/* The extra pins, the model parameters (one per hg_params_table entry,
 * SI units) and the dynamics function. */
static int export_extra(board_t *b)
{
    static const char axis[6] = {'x', 'y', 'z', 'a', 'b', 'c'};
    int rc, k, n, id = b->id;
    const hg_param_info *t = hg_params_table(&n);
    for (k = 0; k < HG_BOARD_JOINTS; k++) {
        joint_hal *j = &b->joint[k];
        TRY(hal_pin_float_newf(HAL_OUT, &j->pos_mm, comp_id, XP ".%d.joint-%d.pos", id, k));
        TRY(hal_pin_float_newf(HAL_OUT, &j->vel_mmps, comp_id, XP ".%d.joint-%d.vel", id, k));
        TRY(hal_pin_float_newf(HAL_OUT, &j->volts, comp_id, XP ".%d.joint-%d.volts", id, k));
        TRY(hal_pin_float_newf(HAL_OUT, &j->current_a, comp_id, XP ".%d.joint-%d.current", id, k));
        TRY(hal_pin_float_newf(HAL_OUT, &j->force_n, comp_id, XP ".%d.joint-%d.force", id, k));
        TRY(hal_pin_bit_newf(HAL_IN, &j->amp_fail, comp_id, XP ".%d.joint-%d.amp-fail", id, k));
        TRY(hal_pin_bit_newf(HAL_IN, &j->stuck_min, comp_id, XP ".%d.joint-%d.stuck-min", id, k));
        TRY(hal_pin_bit_newf(HAL_IN, &j->stuck_max, comp_id, XP ".%d.joint-%d.stuck-max", id, k));
        TRY(hal_pin_bit_newf(HAL_IN, &j->stuck_home, comp_id, XP ".%d.joint-%d.stuck-home", id, k));
        TRY(hal_pin_bit_newf(HAL_IN, &j->tripped_min, comp_id, XP ".%d.joint-%d.tripped-min", id, k));
        TRY(hal_pin_bit_newf(HAL_IN, &j->tripped_max, comp_id, XP ".%d.joint-%d.tripped-max", id, k));
        TRY(hal_pin_bit_newf(HAL_IN, &j->tripped_home, comp_id, XP ".%d.joint-%d.tripped-home", id, k));
        TRY(hal_pin_bit_newf(HAL_IN, &j->index_lost, comp_id, XP ".%d.joint-%d.index-lost", id, k));
        TRY(hal_pin_s32_newf(HAL_IO, &j->enc_glitch, comp_id, XP ".%d.joint-%d.enc-glitch", id, k));
        TRY(hal_pin_bit_newf(HAL_IN, &j->bar_broken, comp_id, XP ".%d.joint-%d.bar-broken", id, k));
    }
    for (k = 0; k < 6; k++)
        TRY(hal_pin_float_newf(HAL_OUT, &b->head[k], comp_id, XP ".%d.head-%c", id, axis[k]));
    TRY(hal_pin_float_newf(HAL_OUT, &b->sim_time_s, comp_id, XP ".%d.sim-time", id));
    TRY(hal_pin_float_newf(HAL_OUT, &b->residual_m, comp_id, XP ".%d.residual", id));
    TRY(hal_pin_u32_newf(HAL_OUT, &b->steps, comp_id, XP ".%d.steps", id));
    TRY(hal_pin_u32_newf(HAL_OUT, &b->bars_broken, comp_id, XP ".%d.bars-broken", id));
    TRY(hal_pin_u32_newf(HAL_OUT, &b->step_ns, comp_id, XP ".%d.step-time-ns", id));
    TRY(hal_pin_u32_newf(HAL_IO, &b->step_max_ns, comp_id, XP ".%d.step-time-max-ns", id));
    TRY(hal_pin_bit_newf(HAL_OUT, &b->fault, comp_id, XP ".%d.fault", id));
    TRY(hal_pin_s32_newf(HAL_OUT, &b->fault_code, comp_id, XP ".%d.fault-code", id));
    TRY(hal_pin_bit_newf(HAL_IN, &b->reset, comp_id, XP ".%d.reset", id));
    TRY(hal_pin_bit_newf(HAL_OUT, &b->amps_on, comp_id, XP ".%d.amps-on", id));
    TRY(hal_pin_bit_newf(HAL_IN, &b->estop_button, comp_id, XP ".%d.estop-button", id));
    TRY(hal_pin_bit_newf(HAL_OUT, &b->watchdog_expired, comp_id, XP ".%d.watchdog-expired", id));
    TRY(hal_pin_bit_newf(HAL_OUT, &b->param_error, comp_id, XP ".%d.param-error", id));
    TRY(hal_pin_bit_newf(HAL_OUT, &b->dac_garbage, comp_id, XP ".%d.dac-nan", id));
    TRY(hal_pin_u32_newf(HAL_OUT, &b->dout_word, comp_id, XP ".%d.digital-out-word", id));
    TRY(hal_param_float_newf(HAL_RW, &b->adc_volts_per_amp, comp_id, XP ".%d.adc-volts-per-amp", id));
    TRY(hal_param_s32_newf(HAL_RW, &b->estop_loop_out, comp_id, XP ".%d.estop-loop-out", id));
    b->estop_loop_out = 7;            /* out-07 as in LinuxCNC's motenc_io.hal */
    b->adc_volts_per_amp = 0.5;
    for (k = 0; k < n; k++)
        TRY(hal_param_float_newf(HAL_RW, (hal_float_t *)((char *)&b->hal_p + t[k].offset),
                                 comp_id, XP ".%d.%s", id, t[k].name));
    TRY(export_funct(b, "dynamics", dynamics, 1));
    return 0;
}

int rtapi_app_main(void)
{
    board_t *b;
    const char *field = "?", *why = "?";
    hg_params p;
    int rc, kind = hg_model_from_name(model);

    if (kind < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": model=%s unknown; use standard, reduced-joints, "
                        "reduced-cartesian or fused-cartesian\n", model);
        return -EINVAL;
    }
    if (board < 0 || board > 3) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": board=%d: a MOTENC board id is 0..3\n", board);
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
    b->id = board;
    hg_params_default(&p);
    rc = hg_model_init(&b->m, &p, (hg_model_kind)kind, &field, &why);
    if (rc) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": default model refused: %s %s (%s)\n",
                        field, why, hg_strerror(rc));
        hal_exit(comp_id);
        return -EINVAL;
    }
    hg_watchdog_init(&b->wd);
    rc = export_motenc(b);
    if (!rc)
        rc = export_extra(b);
    if (rc) {
        rtapi_print_msg(RTAPI_MSG_ERR, MODNAME ": exporting pins failed (%d)\n", rc);
        hal_exit(comp_id);
        return rc;
    }
    b->hal_p = b->m.p;
    reinit_at_home(b);
    publish(b, b->dac_out_v);
    rtapi_print_msg(RTAPI_MSG_INFO, MODNAME ": board %d, model %s, ready\n", board, model);
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    hal_exit(comp_id);
}
