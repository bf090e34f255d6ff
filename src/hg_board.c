/* hg_board.c - one servo period of the virtual MOTENC-100 board with a
 * plant behind it (contracts in hg_board.h; the plant interface in
 * hg_plant.h). */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_board.h"
#include "hg_errors.h"
#include "hg_scheme.h"
#include "hg_text.h"
#include "hg_units.h"

/* Finite x, or 0 (nothing non-finite reaches an output). */
static double finite_or_zero(double x) { return isfinite(x) ? x : 0.0; }

const hg_plant *hg_board_plant(const hg_board *b)
{
    return hg_plant_at(b->plant);
}

/* Entries of b's parameter table. */
static int nparams(const hg_board *b)
{
    return hg_board_plant(b)->nparams(b->variant);
}

int hg_board_params_default(int plant, int variant, hg_board_params *p)
{
    memset(p, 0, sizeof *p);
    if (hg_plant_defaults_at(plant, variant, &p->plant))
        return HG_ERR_BAD_PARAM;
    p->substeps = 1;
    p->integrator = HG_INTEGRATOR_DEFAULT;
    return HG_OK;
}

int hg_board_params_check(const hg_board *b, const hg_board_params *p, hg_bitset *bad,
                          const char *why[HG_BOARD_WHY_LEN])
{
    const hg_plant *pl = hg_board_plant(b);
    hg_bitset s;
    int i;
    if (why)
        for (i = 0; i < HG_BOARD_WHY_LEN; i++)
            why[i] = 0;
    hg_bitset_clear(&s);
    pl->check(b->variant, &p->plant, &s, why);
    if (!(p->substeps >= 1 && p->substeps <= HG_SUBSTEPS_MAX)) {
        hg_bitset_set(&s, HG_BOARD_BIT_SUBSTEPS);
        if (why)
            why[HG_BOARD_BIT_SUBSTEPS] = "must be an integer in 1..64 (integration steps per servo period)";
    }
    if (!(p->integrator < (unsigned)HG_INTEGRATOR_COUNT)) {
        hg_bitset_set(&s, HG_BOARD_BIT_INTEGRATOR);
        if (why)
            why[HG_BOARD_BIT_INTEGRATOR] = "must be 0 (improved-euler), 1 (heun) or 2 (rk4)";
    }
    if (bad)
        *bad = s;
    return hg_bitset_empty(&s) ? HG_OK : HG_ERR_BAD_PARAM;
}

double hg_board_param_value(const hg_board_params *p, int bit)
{
    if (bit == HG_BOARD_BIT_SUBSTEPS)
        return p->substeps;
    if (bit == HG_BOARD_BIT_INTEGRATOR)
        return p->integrator;
    return p->plant.v[bit];
}

const char *hg_board_param_hal_name(const hg_board *b, int bit)
{
    hg_param_info e;
    if (bit == HG_BOARD_BIT_SUBSTEPS)
        return "substeps";
    if (bit == HG_BOARD_BIT_INTEGRATOR)
        return "integrator";
    return hg_plant_param(hg_board_plant(b), b->variant, bit, &e) == 0 ? e.hal_name : 0;
}

/* Latch the fault with code rc (first cause wins; event once, into out if given). */
static void latch_fault(hg_board *b, hg_board_outputs *out, int rc, int cause)
{
    if (!b->fault && out) {
        out->events |= HG_EV_FAULT_LATCHED;
        out->fault_cause = cause;
    }
    b->fault = 1;
    b->fault_code = rc;
}

/* The plant's tool-path error at commands pos_cmd (m; -1 none, never NaN). */
static double tool_error(const hg_board *b, const double pos_cmd[HG_CHANNELS_MAX])
{
    double e = hg_board_plant(b)->tool_error(&b->m, &b->d, pos_cmd);
    return isfinite(e) && e >= 0.0 ? e : -1.0;
}

/* Say which of motion's commands became NaN or inf this period (POS_CMD_BAD): the
 * tool-path error reads -1 while one is, and a user should learn why. */
static void pos_cmd_checked(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out)
{
    unsigned bad = 0;
    int k;
    for (k = 0; k < b->sense.channels && !b->skip_tool_error; k++)
        bad |= isfinite(in->pos_cmd[k]) ? 0u : 1u << k;
    out->pos_cmd_bad_new = bad & ~b->pos_cmd_bad;
    if (out->pos_cmd_bad_new)
        out->events |= HG_EV_POS_CMD_BAD;
    b->pos_cmd_bad = bad;
}

/* Machine at HOME at rest, counters at 0 and disarmed, fault cleared. */
static void reinit_at_home(hg_board *b, hg_board_outputs *out)
{
    const hg_plant *pl = hg_board_plant(b);
    int k, rc = pl->reset(&b->m, &b->d);
    b->fault = 0;
    b->fault_code = 0;
    memset(&b->fault_report, 0, sizeof b->fault_report);
    if (rc)
        latch_fault(b, out, rc, HG_FAULT_HOME);
    pl->sense(&b->m, &b->d, &b->sense);
    b->tool_error = 0.0;               /* (at HOME the command is HOME's until a step says otherwise) */
    for (k = 0; k < HG_BOARD_ENCODERS; k++) {
        int used = k < b->sense.channels;
        hg_encoder_init(&b->enc[k], used ? b->sense.turns[k] : 0.0, used ? b->sense.counts_per_rev[k] : 0.0);
    }
    for (k = 0; k < HG_CHANNELS_MAX; k++)
        b->switches[k] = k < b->sense.channels ? b->sense.switches[k] : 0u;
}

int hg_board_init(hg_board *b, int plant, int variant, const hg_board_params *p)
{
    const hg_plant *pl = hg_plant_at(plant);
    const char *field, *why;
    int k, rc;
    memset(b, 0, sizeof *b);
    if (!pl || !hg_plant_nparams_at(plant, variant))
        return HG_ERR_BAD_PARAM;
    b->plant = plant;
    b->variant = variant;
    if (!p) {                         /* the defaults, built where the block in force lives */
        hg_board_params_default(plant, variant, &b->last_in);
        p = &b->last_in;
    }
    if (hg_board_params_check(b, p, 0, 0))
        return HG_ERR_BAD_PARAM;
    rc = pl->build(&b->m, &p->plant, variant, (int)p->integrator, &field, &why);
    if (rc)
        return rc;
    pl->params_of(&b->m, &b->in_force.plant);
    b->in_force.substeps = p->substeps;
    b->in_force.integrator = p->integrator;
    b->integrator = (int)p->integrator;
    b->substeps = b->substeps_run = p->substeps;
    b->stiff_param = -1;
    if (p != &b->last_in)
        b->last_in = *p;
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        b->enc_scale[k] = b->enc_scale_in[k] = 1.0;
    b->estop_loop_out = b->estop_loop_out_in = HG_BOARD_ESTOP_LOOP_OUT;
    b->adc_volts_per_amp = b->adc_volts_per_amp_in = HG_BOARD_ADC_VOLTS_PER_AMP;
    hg_watchdog_init(&b->wd);
    reinit_at_home(b, 0);
    return b->fault ? b->fault_code : HG_OK;
}

int hg_board_integrable(hg_board *b, hg_board_inputs *in, int plant, int variant, const hg_board_params *p,
                        long period_ns, hg_board_outputs *out)
{
    int rc = hg_board_init(b, plant, variant, p);
    memset(out, 0, sizeof *out);
    if (rc)
        return rc;
    hg_board_inputs_default(b, in);
    if (p)
        in->params = *p;                         /* the block as given, not as the model keeps it */
    hg_board_step(b, in, out, period_ns);       /* the first period checks the block's stability */
    return out->fault && out->fault_cause == HG_FAULT_STIFF ? HG_ERR_STIFF : HG_OK;
}

void hg_board_inputs_default(const hg_board *b, hg_board_inputs *in)
{
    int k;
    memset(in, 0, sizeof *in);
    in->estop_loop_out = HG_BOARD_ESTOP_LOOP_OUT;
    in->adc_volts_per_amp = HG_BOARD_ADC_VOLTS_PER_AMP;
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        in->enc_scale[k] = 1.0;
    for (k = 0; k < HG_BOARD_ADCS; k++)
        in->adc_gain[k] = 1.0;
    in->params = b->in_force;
}

/* 1 when the parameter blocks of plant p differ bitwise (a NaN equals itself). */
static int params_differ(const hg_board *b, const hg_board_params *a, const hg_board_params *c)
{
    return memcmp(a->plant.v, c->plant.v, (unsigned long)nparams(b) * sizeof(double)) != 0 || // NOLINT(bugprone-suspicious-memory-comparison): all doubles, bitwise on purpose
           a->substeps != c->substeps || a->integrator != c->integrator;
}

/* The substeps the period needs with the parameters in force (once per
 * change of either): substeps_run, an event when it rises above substeps,
 * a latched fault when not even HG_SUBSTEPS_MAX integrate it. */
static void find_substeps(hg_board *b, long period_ns, hg_board_outputs *out)
{
    unsigned before = b->substeps_run, need;
    int rc;
    if (b->stab_period_ns == period_ns)
        return;
    rc = hg_board_plant(b)->stability(b->variant, &b->in_force.plant, b->integrator, (double)period_ns * 1e-9,
                                      b->substeps, HG_SUBSTEPS_MAX, &need, &b->stiff_param,
                                      &b->stiff_dt_max_s);
    b->stab_period_ns = period_ns;
    b->substeps_run = rc ? b->substeps : need;
    if (rc)
        latch_fault(b, out, HG_ERR_STIFF, HG_FAULT_STIFF);
    else if (b->substeps_run > b->substeps && b->substeps_run != before)
        out->events |= HG_EV_SUBSTEPS_AUTO;
}

/* Refuse a parameter block with code rc (the set in force stays). */
static void refuse(hg_board *b, hg_board_outputs *out, int rc)
{
    out->events |= HG_EV_PARAM_REFUSED;
    out->param_rc = rc;
    b->param_error = 1;
}

/* Try the input parameter block: apply it, or refuse it naming every
 * invalid field (the set in force stays). A new shape restarts at HOME; a
 * change of the encoders' scale rescales the counters without a jump. */
static void apply_params(hg_board *b, const hg_board_params *want, hg_board_outputs *out)
{
    const hg_plant *pl = hg_board_plant(b);
    const char *field, *why;
    unsigned change;
    int k, rc;
    if (hg_board_params_check(b, want, &out->refused, 0)) {
        refuse(b, out, HG_ERR_BAD_PARAM);
        return;
    }
    if (!params_differ(b, want, &b->in_force))
        return;                       /* back to the block in force: nothing to do */
    rc = pl->build(&b->m_new, &want->plant, b->variant, (int)want->integrator, &field, &why);
    if (rc) {                         /* passed the checks, could not be built */
        hg_bitset_clear(&out->refused);
        refuse(b, out, rc);
        return;
    }
    if (b->stab_period_ns > 0) {      /* can the scheme integrate it at the running period? */
        unsigned need;
        int param;
        double dt_max;
        if (pl->stability(b->variant, &want->plant, (int)want->integrator, (double)b->stab_period_ns * 1e-9,
                          want->substeps, HG_SUBSTEPS_MAX, &need, &param, &dt_max)) {
            hg_bitset_clear(&out->refused);
            hg_bitset_set(&out->refused, param);
            refuse(b, out, HG_ERR_STIFF);
            out->stiff_param = param;
            out->stiff_dt_max_s = dt_max;
            out->stiff_value = want->plant.v[param];
            out->stiff_integrator = (int)want->integrator;
            return;
        }
    }
    change = pl->change(b->variant, &b->in_force.plant, &want->plant);
    b->m = b->m_new;
    pl->params_of(&b->m, &b->in_force.plant);
    b->in_force.substeps = want->substeps;
    b->in_force.integrator = want->integrator;
    b->integrator = (int)want->integrator;
    b->stab_period_ns = 0;            /* substeps_run found again at the next period */
    b->substeps = want->substeps;
    b->param_error = 0;
    out->events |= HG_EV_PARAM_APPLIED;
    /* a new shape restarts at HOME; once running, a shape moved by rounding only keeps the machine
     * where it is (before the first period the restart is the power-up's, as records made then have it) */
    if ((change & HG_PLANT_CHANGE_RESTART) && (b->steps == 0 || !(change & HG_PLANT_CHANGE_ROUNDING))) {
        out->events |= HG_EV_GEOMETRY_RESTART;
        reinit_at_home(b, out);
        return;
    }
    pl->sense(&b->m, &b->d, &b->sense);
    if (change & HG_PLANT_CHANGE_RESCALE)
        for (k = 0; k < b->sense.channels && k < HG_BOARD_ENCODERS; k++)
            hg_encoder_rescale(&b->enc[k], b->sense.turns[k], b->sense.counts_per_rev[k]);
}

/* The E-STOP loop's output from the input, once per change: -1 (none) or
 * 0..31 is taken; any other value is refused (ESTOP_OUT_BAD, param_error)
 * and the output in force stays in the loop: a typo must not take the
 * loop out of the circuit, which would leave the amplifiers on whatever
 * LinuxCNC's E-STOP says. */
static void estop_loop_out(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out)
{
    int o = in->estop_loop_out;
    if (o == b->estop_loop_out_in)
        return;
    b->estop_loop_out_in = o;
    if (o >= -1 && o < HG_BOARD_OUTPUTS) {
        b->estop_loop_out = o;
    } else {
        out->events |= HG_EV_ESTOP_OUT_BAD;
        b->param_error = 1;
    }
}

/* The current monitors' volts per amp from the input, once per change:
 * finite and above 0 is taken; any other value is refused (ADC_VPA_BAD,
 * param_error) and the one in force kept. */
static void adc_volts_per_amp(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out)
{
    double v = in->adc_volts_per_amp;
    if (memcmp(&v, &b->adc_volts_per_amp_in, sizeof v) == 0) // NOLINT(bugprone-suspicious-memory-comparison): bitwise, NaN equals itself
        return;
    b->adc_volts_per_amp_in = v;
    if (isfinite(v) && v > 0.0) {
        b->adc_volts_per_amp = v;
    } else {
        out->events |= HG_EV_ADC_VPA_BAD;
        b->param_error = 1;
    }
}

/* 1 when the E-STOP loop is open: button pressed, or the commanded state
 * (value xor invert) of the loop output in force is off. */
static int estop_open(const hg_board *b, const hg_board_inputs *in)
{
    int o = b->estop_loop_out;
    unsigned cmd = in->dout_values ^ in->dout_inverts;
    if (in->estop_button)
        return 1;
    return o >= 0 && o < HG_BOARD_OUTPUTS && !((cmd >> o) & 1u);
}

/* `substeps_run` plant steps of dt/substeps_run, all or nothing: 0 or the
 * failing code with the state restored to the period's start. */
static int integrate(hg_board *b, const double volts[HG_CHANNELS_MAX], unsigned enabled, double dt)
{
    const hg_plant *pl = hg_board_plant(b);
    unsigned i, n = b->substeps_run;
    double h = dt / (double)n;
    hg_plant_report r;
    int rc = 0;
    memset(&r, 0, sizeof r);
    memcpy(b->d_saved.store, b->d.store, pl->state_bytes); /* the state, not the step's scratch */
    for (i = 0; i < n && rc == 0; i++)
        rc = pl->step(&b->m, &b->d, volts, enabled, h, &r);
    if (rc) {
        b->fault_report = r;          /* what was struck, kept through the rollback */
        memcpy(b->d.store, b->d_saved.store, pl->state_bytes);
    }
    return rc;
}

/* The plant's fault injections whose inputs are set (what they do is the plant's). */
static void inject(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out)
{
    const hg_plant *pl = hg_board_plant(b);
    int i;
    if (pl->ninjections == 0)
        return;
    pl->inject(&b->m, &b->d, in->inject, out->injected);
    for (i = 0; i < pl->ninjections && i < HG_PLANT_INJECT_MAX; i++)
        if (out->injected[i])
            out->events |= HG_EV_INJECTED;
}

/* 1 when scale is channel ch's counts per HAL unit (counts_per_unit),
 * per inch of a linear channel, or 1 (the power-up value: counts), within
 * HG_ENC_SCALE_FIT. */
static int enc_scale_fits(const hg_board *b, int ch, double scale, double counts_per_unit)
{
    const double per_inch = counts_per_unit * HG_MM_PER_INCH;
    const int rotary = (int)((b->sense.rotary >> ch) & 1u);
    return scale == 1.0 || fabs(scale - counts_per_unit) <= HG_ENC_SCALE_FIT * fabs(counts_per_unit) ||
           (!rotary && fabs(scale - per_inch) <= HG_ENC_SCALE_FIT * fabs(per_inch));
}

int hg_board_enc_scale_fits(const hg_board *b, int ch, double scale)
{
    return ch < 0 || ch >= b->sense.channels || enc_scale_fits(b, ch, scale, hg_board_counts_per_unit(b, ch));
}

/* enc_scale_odd of channel ch, once per change of its scale or its counts per unit. */
static void judge_enc_scale(hg_board *b, int ch, double scale, hg_board_outputs *out)
{
    const double cpu = hg_board_counts_per_unit(b, ch);
    if (memcmp(&scale, &b->enc_scale_judged[ch], sizeof scale) == 0 && // NOLINT(bugprone-suspicious-memory-comparison): bitwise
        memcmp(&cpu, &b->enc_counts_judged[ch], sizeof cpu) == 0) // NOLINT(bugprone-suspicious-memory-comparison): bitwise
        return;
    b->enc_scale_judged[ch] = scale;
    b->enc_counts_judged[ch] = cpu;
    if (!enc_scale_fits(b, ch, scale, cpu))
        out->enc_scale_odd |= 1u << ch;
}

/* Encoders: index-enable arms the latch, the motor moves the counter,
 * a glitch adds counts, reset zeroes it; scale checked. */
static void encoders(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out)
{
    int ch;
    for (ch = 0; ch < HG_BOARD_ENCODERS; ch++) {
        hg_encoder *e = &b->enc[ch];
        double s = in->enc_scale[ch];
        if (e->latch_hit)             /* the driver was told (index_latched) last step */
            hg_encoder_arm(e, 0);
        hg_encoder_arm(e, in->index_enable[ch]);
        if (ch < b->sense.channels) {
            hg_encoder_update(e, b->sense.turns[ch], b->sense.counts_per_rev[ch], in->index_lost[ch]);
            if (in->enc_glitch[ch])
                hg_encoder_glitch(e, in->enc_glitch[ch]);
        } else {
            e->index_pulse = 0;
        }
        if (in->enc_reset[ch])
            hg_encoder_zero(e);
        if (memcmp(&s, &b->enc_scale_in[ch], sizeof s) != 0) { // NOLINT(bugprone-suspicious-memory-comparison): bitwise, a NaN scale equals itself
            b->enc_scale_in[ch] = s;
            if (!isfinite(s) || (s < HG_ENC_SCALE_MIN && s > -HG_ENC_SCALE_MIN)) {
                out->enc_scale_bad |= 1u << ch;
                b->param_error = 1;
                s = 1.0;              /* as hal_motenc */
            }
            b->enc_scale[ch] = s;
        }
        s = b->enc_scale[ch];
        if (ch < b->sense.channels)
            judge_enc_scale(b, ch, s, out);
        out->count[ch] = hg_encoder_count(e);
        out->position[ch] = finite_or_zero(out->count[ch] / s);
        out->index[ch] = e->index_pulse;
        out->index_latched[ch] = e->latch_hit;
        out->enc_scale[ch] = s;
    }
    if (out->enc_scale_bad)
        out->events |= HG_EV_ENC_SCALE_BAD;
}

/* adc-read: publish the group converted at the last read, convert the other. */
static void adc(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out)
{
    int i, done = b->adc_state == 1 ? 0 : 4, next = b->adc_state == 1 ? 4 : 0;
    if (!in->adc_read)
        return;
    if (b->adc_state != 0)
        for (i = done; i < done + 4; i++) {
            const unsigned bit = 1u << i;
            const double v = b->adc_sample_v[i] * in->adc_gain[i] - in->adc_offset[i];
            b->adc_value[i] = hg_adc_value(b->adc_sample_v[i], in->adc_gain[i], in->adc_offset[i]);
            if (isfinite(v) && !(b->adc_sample_bad & bit)) {
                b->adc_nan &= ~bit;
            } else if (!(b->adc_nan & bit)) {
                b->adc_nan |= bit;
                out->adc_nan_new |= bit;
                out->events |= HG_EV_ADC_NAN;
            }
        }
    for (i = next; i < next + 4; i++) {
        double amps = i < b->sense.channels && !b->fault ? b->sense.current_a[i] : 0.0;
        double x = amps * b->adc_volts_per_amp;
        b->adc_sample_v[i] = isfinite(x) ? hg_adc_sample(x) : 0.0;
        b->adc_sample_bad = isfinite(x) ? b->adc_sample_bad & ~(1u << i) : b->adc_sample_bad | 1u << i;
    }
    b->adc_state = b->adc_state == 1 ? 2 : 1;
}

/* Everything the outputs show that is not an event: state, sensors, latches. */
static void publish(const hg_board *b, const hg_board_inputs *in, hg_board_outputs *out,
                    const double volts[HG_CHANNELS_MAX])
{
    const hg_plant_sense *s = &b->sense;
    int k, i, open = in ? estop_open(b, in) : 0; /* before any step: pins as hal_motenc powers up */
    out->channels = s->channels;
    out->rotary = s->rotary;
    for (k = 0; k < s->channels; k++) {
        out->pos[k] = s->pos[k];
        out->vel[k] = s->vel[k];
        out->motor_pos[k] = s->motor_pos[k];
        out->volts[k] = finite_or_zero(volts[k]);
        out->current_a[k] = b->fault ? 0.0 : s->current_a[k];
        out->force[k] = s->force[k];
    }
    for (k = 0; k < HG_PLANT_EXTRA_MAX; k++)
        out->extra[k] = finite_or_zero(s->extra[k]);
    for (i = 0; i < HG_BOARD_INPUTS; i++) {
        int j = i / HG_INPUTS_PER_CHANNEL, bit = i % HG_INPUTS_PER_CHANNEL, v = 0;
        if (j < s->channels)
            v = bit == HG_IN_AMP_FAULT ? (in && in->amp_fail[j] != 0) : (int)((b->switches[j] >> bit) & 1u);
        out->in[i] = (unsigned char)v;
    }
    for (k = 0; k < HG_BOARD_ADCS; k++)
        out->adc[k] = finite_or_zero(b->adc_value[k]);
    /* E-STOP and an expired watchdog switch the outputs off in hardware */
    out->dout_word = (!in || open || b->wd.expired) ? 0u : (in->dout_values ^ in->dout_inverts);
    out->estop_in = open;
    out->tool_error = b->tool_error;
    out->sim_time_s = s->sim_time_s;
    out->steps = b->steps;
    out->fault = b->fault;
    out->fault_code = b->fault_code;
    out->fault_report = b->fault_report;
    out->watchdog_expired = b->wd.expired;
    out->param_error = b->param_error;
    out->dac_nan = b->dac_nan != 0;
    memcpy(out->params.plant.v, b->in_force.plant.v, (unsigned long)nparams(b) * sizeof(double));
    out->params.substeps = b->in_force.substeps;    /* (the entries past the plant's stay 0) */
    out->params.integrator = b->in_force.integrator;
    out->substeps_run = b->substeps_run;
    out->estop_loop_out = b->estop_loop_out;
    out->adc_volts_per_amp = b->adc_volts_per_amp;
    if (out->stiff_param < 0 || !(out->events & HG_EV_PARAM_REFUSED)) {
        out->stiff_param = b->substeps_run > b->substeps || b->fault_code == HG_ERR_STIFF ? b->stiff_param : -1;
        out->stiff_dt_max_s = out->stiff_param >= 0 ? b->stiff_dt_max_s : 0.0;
        out->stiff_value = out->stiff_param >= 0 ? b->in_force.plant.v[out->stiff_param] : 0.0;
        out->stiff_integrator = b->integrator;
    }
}

void hg_board_peek(const hg_board *b, hg_board_outputs *out)
{
    static const double zero[HG_CHANNELS_MAX] = {0, 0, 0, 0, 0, 0, 0, 0};
    int ch;
    memset(out, 0, sizeof *out);
    out->stiff_param = -1;
    publish(b, 0, out, zero);
    for (ch = 0; ch < HG_BOARD_ENCODERS; ch++) {
        out->count[ch] = hg_encoder_count(&b->enc[ch]);
        out->position[ch] = finite_or_zero(out->count[ch] / b->enc_scale[ch]);
        out->enc_scale[ch] = b->enc_scale[ch];
    }
}

void hg_board_forget(hg_board *b)
{
    const hg_plant *pl = hg_board_plant(b);
    memset((char *)b->d.store + pl->state_bytes, 0, pl->data_bytes - pl->state_bytes);
}

/* First channel whose reset-blocking injection input is set (its injection
 * in *which), or -1. */
static int reset_blocked(const hg_board *b, const hg_board_inputs *in, int *which)
{
    const hg_plant *pl = hg_board_plant(b);
    int k, i;
    for (k = 0; k < b->sense.channels; k++)
        for (i = 0; i < pl->ninjections; i++)
            if (pl->injections[i].blocks_reset && ((in->inject[k] >> i) & 1u)) {
                *which = i;
                return k;
            }
    return -1;
}

/* The servo thread's addf order: a step whose volts were written before
 * the encoders were read (dynamics between encoder-read and dac-write)
 * twice in a row, or steps with no dac-write at all for
 * HG_BOARD_UNWRITTEN_NS (dac-write missing): said once per load or reset.
 * The first period of a thread that runs dynamics first is not a fault
 * (two in a row), nor is dynamics in a
 * faster thread of its own (a finer plant step: each period's volts are
 * held for several steps, as a DAC holds them). */
static void addf_order(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out, long period_ns)
{
    int bad = 0;
    if (in->dac_written && in->dac_stale) {
        if (b->order_bad_run < 2)
            b->order_bad_run++;
        bad = b->order_bad_run == 2;
    } else {
        b->order_bad_run = 0;
    }
    if (in->dac_written) {
        b->unwritten_ns = 0;
    } else if (b->unwritten_ns < HG_BOARD_UNWRITTEN_NS && period_ns > 0) {
        b->unwritten_ns += period_ns < HG_BOARD_UNWRITTEN_NS ? period_ns : HG_BOARD_UNWRITTEN_NS; /* no overflow */
        bad |= b->unwritten_ns >= HG_BOARD_UNWRITTEN_NS;
    }
    if (bad && !b->order_reported) {
        out->events |= HG_EV_ADDF_ORDER;
        b->order_reported = 1;
    }
}

void hg_board_step(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out, long period_ns)
{
    const hg_plant *pl = hg_board_plant(b);
    double volts[HG_CHANNELS_MAX] = {0, 0, 0, 0, 0, 0, 0, 0}, dac_out_v[HG_BOARD_DACS];
    double dt = (double)period_ns * 1e-9;
    unsigned nan_now = 0, enabled = 0;
    int k, amps_on, expired, was_expired;

    memset(out, 0, sizeof *out);
    out->reset_refused_channel = -1;
    out->reset_refused_injection = -1;
    out->stiff_param = -1;
    /* reset edge: HOME at rest, unless an injection that cannot be undone still holds */
    if (in->reset && !b->prev_reset) {
        int which = -1, j = reset_blocked(b, in, &which);
        if (j >= 0) {
            out->events |= HG_EV_RESET_REFUSED;
            out->reset_refused_channel = j;
            out->reset_refused_injection = which;
        } else {
            b->param_error = 0;       /* the input block is tried again */
            apply_params(b, &in->params, out);
            reinit_at_home(b, out);
            b->order_bad_run = b->order_reported = 0;
            b->unwritten_ns = 0;
            out->events |= HG_EV_RESET_DONE;
        }
    } else if (params_differ(b, &in->params, &b->last_in)) {
        apply_params(b, &in->params, out);
    }
    b->prev_reset = in->reset != 0;
    b->last_in = in->params;

    if (period_ns <= 0 || period_ns > HG_PERIOD_MAX_NS) {
        if (!b->fault)
            out->events |= HG_EV_PERIOD_BAD;
        latch_fault(b, out, HG_ERR_BAD_DT, HG_FAULT_PERIOD);
        dt = 0;
    }
    /* misc-update, dac-write: watchdog control, kick, auto reset */
    hg_watchdog_set_control(&b->wd, in->watchdog_control);
    if (in->watchdog_reset) {
        hg_watchdog_kick(&b->wd);
        out->events |= HG_EV_WATCHDOG_KICKED;
    }
    for (k = 0; k < HG_BOARD_DACS; k++) {
        int garbage;
        dac_out_v[k] = hg_dac_output(hg_dac_volts(in->dac_v[k], 0.0, 1.0, &garbage));
        nan_now |= garbage ? 1u << k : 0u;
    }
    out->dac_nan_new = nan_now & ~b->dac_nan;
    if (out->dac_nan_new)
        out->events |= HG_EV_DAC_NAN;
    b->dac_nan = nan_now;
    if (in->dac_written)
        hg_watchdog_dac_write(&b->wd);
    addf_order(b, in, out, period_ns);
    was_expired = b->wd.expired;
    expired = hg_watchdog_advance(&b->wd, dt);
    if (expired && !was_expired)
        out->events |= HG_EV_WATCHDOG_EXPIRED;
    estop_loop_out(b, in, out);
    adc_volts_per_amp(b, in, out);
    amps_on = !estop_open(b, in) && !expired && !b->fault;
    for (k = 0; k < b->sense.channels; k++) {
        int on = amps_on && !in->amp_fail[k];
        volts[k] = on ? dac_out_v[k] : 0.0;
        enabled |= on ? 1u << k : 0u;  /* a disabled amplifier passes no current */
    }

    if (!b->fault && dt > 0.0)
        find_substeps(b, period_ns, out);
    if (!b->fault) {
        int rc;
        inject(b, in, out);
        rc = integrate(b, volts, enabled, dt);
        if (rc)
            latch_fault(b, out, rc, HG_FAULT_STEP);
        else
            b->steps++;
    }
    if (b->fault)
        for (k = 0; k < HG_CHANNELS_MAX; k++)
            volts[k] = 0.0;
    out->amps_on = amps_on && !b->fault;

    pl->sense(&b->m, &b->d, &b->sense);
    b->tool_error = b->skip_tool_error ? HG_TOOL_ERROR_SKIPPED : tool_error(b, in->pos_cmd);
    pos_cmd_checked(b, in, out);
    encoders(b, in, out);
    for (k = 0; k < b->sense.channels; k++)
        b->switches[k] = hg_switches_stuck(b->sense.switches[k], b->switches[k], in->stuck[k]) | in->tripped[k];
    adc(b, in, out);
    publish(b, in, out, volts);
}

/* Add a thread's period to the time *ns one function ran without the other (a period <= 0 adds
 * nothing); 1 exactly when that time first reaches HG_BOARD_UNSTEPPED_NS (the other function
 * sets it back to 0). */
static int time_without(long long *ns, long period_ns)
{
    if (period_ns <= 0 || *ns >= HG_BOARD_UNSTEPPED_NS)
        return 0;
    *ns += period_ns < HG_BOARD_UNSTEPPED_NS ? period_ns : HG_BOARD_UNSTEPPED_NS; /* no overflow */
    return *ns >= HG_BOARD_UNSTEPPED_NS;
}

int hg_board_rate_read(hg_board_rate *r, long period_ns)
{
    r->unread_ns = 0;
    if (r->reads < HG_BOARD_RATE_READS_MAX)
        r->reads++;
    return time_without(&r->unstepped_ns, period_ns);
}

int hg_board_rate_step(hg_board_rate *r)
{
    int slow, gap = !r->stepped || r->unstepped_ns >= HG_BOARD_UNSTEPPED_NS;
    unsigned reads = r->reads;
    r->unstepped_ns = 0;
    r->reads = 0;
    r->stepped = 1;
    if (r->said || gap)               /* a window starts at the step after a gap */
        return 0;
    r->window_reads += reads;
    if (++r->steps < HG_BOARD_RATE_WINDOW)
        return 0;
    slow = 2u * r->window_reads >= 3u * r->steps;  /* at least 1.5 reads per step */
    r->steps = r->window_reads = 0;
    r->said = slow;
    return slow;
}

int hg_board_rate_unread(hg_board_rate *r, long period_ns)
{
    return time_without(&r->unread_ns, period_ns);
}

double hg_board_counts_per_unit(const hg_board *b, int ch)
{
    if (ch < 0 || ch >= b->sense.channels)
        return 0.0;
    return b->sense.counts_per_rev[ch] * b->sense.turns_per_unit[ch] /
           ((b->sense.rotary >> ch) & 1u ? HG_DEG_PER_RAD : HG_MM_PER_M);
}

void hg_board_describe_enc_scale(const hg_board *b, int ch, double scale, char buf[HG_BOARD_TEXT_LEN])
{
    const unsigned long n = HG_BOARD_TEXT_LEN;
    const double cpu = hg_board_counts_per_unit(b, ch);
    const int rotary = (int)((b->sense.rotary >> ch) & 1u);
    buf[0] = '\0';
    hg_text_add(buf, n, "is not the encoder's ");
    hg_text_add_value(buf, n, cpu);
    hg_text_add(buf, n, rotary ? " counts per deg" : " counts per mm (");
    if (!rotary) {
        hg_text_add_value(buf, n, cpu * HG_MM_PER_INCH);
        hg_text_add(buf, n, " per inch)");
    }
    if (scale * cpu < 0.0) {
        hg_text_add(buf, n, ": counts / scale read the travel with the other sign (a position loop on it runs away)");
    } else {
        hg_text_add(buf, n, ": counts / scale read the travel ");
        hg_text_add_value(buf, n, cpu / scale);
        hg_text_add(buf, n, rotary ? " times as long" : " times as long in mm (");
        if (!rotary) {
            hg_text_add_value(buf, n, cpu * HG_MM_PER_INCH / scale);
            hg_text_add(buf, n, " in inches)");
        }
    }
}

void hg_board_describe_stiffness(const hg_board *b, const hg_board_outputs *out, long period_ns, int hal,
                                 char buf[HG_BOARD_TEXT_LEN])
{
    const unsigned long n = HG_BOARD_TEXT_LEN;
    hg_param_info info;
    const hg_param_info *e = hg_plant_param(hg_board_plant(b), b->variant, out->stiff_param, &info) == 0 ? &info : 0;
    buf[0] = '\0';
    if (!e)
        return;
    hg_text_add(buf, n, hal ? e->hal_name : e->name);
    hg_text_add(buf, n, " = ");
    hg_text_add_value(buf, n, out->stiff_value * (hal ? e->hal_scale : 1.0));
    hg_text_add(buf, n, " ");
    hg_text_add(buf, n, hal ? e->hal_unit : e->unit);
    hg_text_add(buf, n, ": ");
    hg_text_add(buf, n, hg_integrator_name((hg_integrator)out->stiff_integrator));
    if (out->stiff_dt_max_s > 0.0) {
        hg_text_add(buf, n, " is stable with it in steps of at most ");
        if (out->stiff_dt_max_s >= 1e-3) {   /* ms to the ns, else us to the ps */
            hg_text_add_value(buf, n, floor(out->stiff_dt_max_s * 1e9 + 0.5) / 1e6);
            hg_text_add(buf, n, " ms");
        } else {
            hg_text_add_value(buf, n, out->stiff_dt_max_s * 1e6);
            hg_text_add(buf, n, " us");
        }
    } else {
        hg_text_add(buf, n, " is unstable with it at any step (the mode needs damping)");
    }
    hg_text_add(buf, n, "; the period is ");
    hg_text_add_value(buf, n, (double)period_ns / 1e6);
    hg_text_add(buf, n, " ms");
}

void hg_board_stiff_remedy(const hg_board_outputs *out, const char *integrator, const char *period,
                           char buf[HG_BOARD_TEXT_LEN])
{
    const unsigned long n = HG_BOARD_TEXT_LEN;
    const int steps_help = out->stiff_dt_max_s > 0.0;   /* a shorter step integrates the mode */
    buf[0] = '\0';
    hg_text_add(buf, n, steps_help ? "a softer value" : "the mode damping");
    hg_text_add(buf, n, steps_help && period ? ", another " : " or another ");
    hg_text_add(buf, n, integrator);
    if (steps_help && period) {
        hg_text_add(buf, n, " or a shorter ");
        hg_text_add(buf, n, period);
    }
    if (!steps_help)
        hg_text_add(buf, n, " (no step is short enough)");
}
