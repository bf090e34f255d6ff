/* hg_board.c - one servo period of the virtual MOTENC-100 board with the
 * Hexaglide behind it (contracts in hg_board.h). */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_board.h"
#include "hg_errors.h"
#include "hg_stability.h"
#include "hg_text.h"

/* Finite x, or 0 (nothing non-finite reaches an output). */
static double finite_or_zero(double x) { return isfinite(x) ? x : 0.0; }

/* The spec's parameter block: defaults, 1 substep, Heun. */
static void params_default(hg_board_params *p)
{
    memset(p, 0, sizeof *p);
    hg_params_default(&p->model);
    p->substeps = 1;
    p->integrator = HG_INTEGRATOR_DEFAULT;
}

int hg_board_params_check(const hg_board_params *p, unsigned long long *mask,
                          const char *why[HG_BOARD_WHY_LEN])
{
    unsigned long long bad = 0;
    int i;
    if (why)
        for (i = 0; i < HG_BOARD_WHY_LEN; i++)
            why[i] = 0;
    hg_params_check_all(&p->model, &bad, why);
    if (!(p->substeps >= 1 && p->substeps <= HG_SUBSTEPS_MAX)) {
        bad |= 1ull << HG_BOARD_BIT_SUBSTEPS;
        if (why)
            why[HG_BOARD_BIT_SUBSTEPS] = "must be an integer in 1..64 (integration steps per servo period)";
    }
    if (!(p->integrator < (unsigned)HG_INTEGRATOR_COUNT)) {
        bad |= 1ull << HG_BOARD_BIT_INTEGRATOR;
        if (why)
            why[HG_BOARD_BIT_INTEGRATOR] = "must be 0 (improved-euler), 1 (heun) or 2 (rk4)";
    }
    if (mask)
        *mask = bad;
    return bad ? HG_ERR_BAD_PARAM : HG_OK;
}

const char *hg_board_param_hal_name(int bit)
{
    int n;
    const hg_param_info *t = hg_params_table(&n);
    if (bit == HG_BOARD_BIT_SUBSTEPS)
        return "substeps";
    if (bit == HG_BOARD_BIT_INTEGRATOR)
        return "integrator";
    return bit >= 0 && bit < n ? t[bit].hal_name : 0;
}

/* Latch the fault with code rc (first cause wins; event once). */
static void latch_fault(hg_board *b, hg_board_outputs *out, int rc, int cause)
{
    if (!b->fault) {
        out->events |= HG_EV_FAULT_LATCHED;
        out->fault_cause = cause;
    }
    b->fault = 1;
    b->fault_code = rc;
}

/* Machine at HOME at rest, counters at 0 and disarmed, fault cleared. */
static void reinit_at_home(hg_board *b, hg_board_outputs *out)
{
    int k, rc = hg_data_reset(&b->m, &b->d);
    b->fault = 0;
    b->fault_code = 0;
    memset(&b->fault_guard, 0, sizeof b->fault_guard);
    if (rc)
        latch_fault(b, out, rc, HG_FAULT_HOME);
    for (k = 0; k < HG_BOARD_ENCODERS; k++) {
        double z = k < HG_BOARD_JOINTS ? b->d.z_m[k] : 0.0;
        hg_encoder_init(&b->enc[k], z, b->m.p.lead_m, b->m.p.counts_per_rev);
    }
    for (k = 0; k < HG_BOARD_JOINTS; k++)
        b->switches[k] = hg_switches(&b->m.p, b->d.z_m[k]);
}

int hg_board_init(hg_board *b, hg_model_kind kind, const hg_board_params *p)
{
    hg_board_params def;
    hg_board_outputs scratch;
    const char *field, *why;
    int k, rc;
    memset(b, 0, sizeof *b);
    if (!p) {
        params_default(&def);
        p = &def;
    }
    if (hg_board_params_check(p, 0, 0))
        return HG_ERR_BAD_PARAM;
    rc = hg_model_init(&b->m, &p->model, kind, &field, &why);
    if (rc == 0)
        rc = hg_model_set_integrator(&b->m, (int)p->integrator);
    if (rc)
        return rc;
    b->substeps = b->substeps_run = p->substeps;
    b->stiff_param = -1;
    b->last_in = *p;
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        b->enc_scale[k] = b->enc_scale_in[k] = 1.0;
    hg_watchdog_init(&b->wd);
    memset(&scratch, 0, sizeof scratch);
    reinit_at_home(b, &scratch);
    return b->fault ? b->fault_code : HG_OK;
}

void hg_board_inputs_default(const hg_board *b, hg_board_inputs *in)
{
    int k;
    memset(in, 0, sizeof *in);
    in->estop_loop_out = 7;
    in->adc_volts_per_amp = 0.5;
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        in->enc_scale[k] = 1.0;
    for (k = 0; k < HG_BOARD_ADCS; k++)
        in->adc_gain[k] = 1.0;
    in->params.model = b->m.p;
    in->params.substeps = b->substeps;
    in->params.integrator = (unsigned)b->m.integrator;
}

/* 1 when the parameter blocks differ bitwise (a NaN equals itself). */
static int params_differ(const hg_board_params *a, const hg_board_params *c)
{
    return memcmp(&a->model, &c->model, sizeof a->model) != 0 || // NOLINT(bugprone-suspicious-memory-comparison): all doubles, bitwise on purpose
           a->substeps != c->substeps || a->integrator != c->integrator;
}

/* 1 when the machine's shape (l, lb, e, lp: where HOME is) differs; the
 * joints' ranges and the bar diameter are limits, not shape. */
static int shape_differs(const hg_geometry *a, const hg_geometry *c)
{
    return a->l_m != c->l_m || a->lb_m != c->lb_m || a->e_m != c->e_m || a->lp_m != c->lp_m;
}

/* Table index of the parameter with spec name `name`, or -1. */
static int param_index(const char *name)
{
    int i, n;
    const hg_param_info *t = hg_params_table(&n);
    for (i = 0; name && i < n; i++)
        if (strcmp(t[i].name, name) == 0)
            return i;
    return -1;
}

/* The substeps the period needs with the parameters in force (once per
 * change of either): substeps_run, an event when it rises above substeps,
 * a latched fault when not even HG_SUBSTEPS_MAX integrate it. */
static void find_substeps(hg_board *b, long period_ns, hg_board_outputs *out)
{
    hg_stability st;
    unsigned before = b->substeps_run;
    int rc;
    if (b->stab_period_ns == period_ns)
        return;
    rc = hg_stability_check(&b->m.p, b->m.integrator, (double)period_ns * 1e-9, b->substeps,
                            HG_SUBSTEPS_MAX, &st);
    b->stab_period_ns = period_ns;
    b->stiff_param = param_index(st.param);
    b->stiff_dt_max_s = st.dt_max_s;
    b->substeps_run = rc ? b->substeps : st.substeps;
    if (rc)
        latch_fault(b, out, HG_ERR_STIFF, HG_FAULT_STIFF);
    else if (b->substeps_run > b->substeps && b->substeps_run != before)
        out->events |= HG_EV_SUBSTEPS_AUTO;
}

/* Try the input parameter block: apply it, or refuse it naming every
 * invalid field (the set in force stays). A new shape restarts at HOME; a
 * new lead or counts-per-rev rescales the counters without a jump. */
static void apply_params(hg_board *b, const hg_board_params *want, hg_board_outputs *out)
{
    const char *field, *why;
    double old_lead = b->m.p.lead_m, old_cpr = b->m.p.counts_per_rev;
    int k, rc, geometry_changed;
    if (hg_board_params_check(want, &out->refused_mask, 0)) {
        out->events |= HG_EV_PARAM_REFUSED;
        out->param_rc = HG_ERR_BAD_PARAM;
        b->param_error = 1;
        return;
    }
    if (memcmp(&want->model, &b->m.p, sizeof want->model) == 0 && // NOLINT(bugprone-suspicious-memory-comparison): bitwise
        want->substeps == b->substeps && want->integrator == (unsigned)b->m.integrator)
        return;                       /* back to the block in force: nothing to do */
    rc = hg_model_init(&b->m_new, &want->model, b->m.kind, &field, &why);
    if (rc == 0)
        rc = hg_model_set_integrator(&b->m_new, (int)want->integrator);
    if (rc) {                         /* passed the checks, could not be built */
        out->events |= HG_EV_PARAM_REFUSED;
        out->refused_mask = 0;
        out->param_rc = rc;
        b->param_error = 1;
        return;
    }
    if (b->stab_period_ns > 0) {      /* can the scheme integrate it at the running period? */
        hg_stability st;
        if (hg_stability_check(&b->m_new.p, b->m_new.integrator, (double)b->stab_period_ns * 1e-9,
                               want->substeps, HG_SUBSTEPS_MAX, &st)) {
            out->events |= HG_EV_PARAM_REFUSED;
            int pi = param_index(st.param);
            out->refused_mask = pi >= 0 ? 1ull << pi : 0;
            out->param_rc = HG_ERR_STIFF;
            out->stiff_param = pi;
            out->stiff_dt_max_s = st.dt_max_s;
            b->param_error = 1;
            return;
        }
    }
    geometry_changed = shape_differs(&b->m_new.p.geo, &b->m.p.geo);
    b->m = b->m_new;
    b->stab_period_ns = 0;            /* substeps_run found again at the next period */
    b->substeps = want->substeps;
    b->param_error = 0;
    out->events |= HG_EV_PARAM_APPLIED;
    if (geometry_changed) {
        out->events |= HG_EV_GEOMETRY_RESTART;
        reinit_at_home(b, out);
    } else if (old_lead != b->m.p.lead_m || old_cpr != b->m.p.counts_per_rev) {
        for (k = 0; k < HG_BOARD_JOINTS; k++)
            hg_encoder_rescale(&b->enc[k], b->d.z_m[k], b->m.p.lead_m, b->m.p.counts_per_rev);
    }
}

/* 1 when the E-STOP loop is open: button pressed, or the loop output's
 * commanded state (value xor invert) is off. */
static int estop_open(const hg_board_inputs *in)
{
    int o = in->estop_loop_out;
    unsigned cmd = in->dout_values ^ in->dout_inverts;
    if (in->estop_button)
        return 1;
    return o >= 0 && o < HG_BOARD_OUTPUTS && !((cmd >> o) & 1u);
}

/* 1 if every state number that reaches an output is finite. */
static int state_finite(const hg_data *d)
{
    int k, ok = isfinite(d->t_s) && isfinite(d->residual_m);
    for (k = 0; k < 6; k++)
        ok = ok && isfinite(d->z_m[k]) && isfinite(d->zd_mps[k]) && isfinite(d->pose[k]) &&
             isfinite(d->posed[k]) && isfinite(d->current_a[k]) && isfinite(d->force_n[k]);
    return ok;
}

/* `substeps` steps of dt/substeps, all or nothing: 0 or the failing code
 * with the state restored to the period's start. */
static int integrate(hg_board *b, const double volts[6], double dt)
{
    unsigned i, n = b->substeps_run;
    double h = dt / (double)n;
    int rc = 0;
    memcpy(&b->d_saved, &b->d, HG_DATA_STATE_BYTES); /* the state, not the step's scratch */
    for (i = 0; i < n && rc == 0; i++) {
        rc = hg_step(&b->m, &b->d, volts, h);
        if (rc == 0 && !state_finite(&b->d))
            rc = HG_ERR_STATE_NONFINITE;
    }
    if (rc) {
        b->fault_guard = b->d.guard;  /* what was struck, kept through the rollback */
        memcpy(&b->d, &b->d_saved, HG_DATA_STATE_BYTES);
    }
    return rc;
}

/* Break the bars whose inputs are set (a broken bar stays broken until a reset). */
static void break_bars(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out)
{
    int k;
    for (k = 0; k < HG_BOARD_JOINTS; k++) {
        unsigned bit = 1u << k;
        if (!in->bar_broken[k] || (b->d.broken_bars & bit))
            continue;
        b->d.broken_bars |= bit;
        out->bars_newly_broken |= bit;
        out->events |= HG_EV_BAR_BROKEN;
    }
}

/* Encoders: index-enable arms the latch, the carriage moves the counter,
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
        if (ch < HG_BOARD_JOINTS) {
            hg_encoder_update(e, b->d.z_m[ch], b->m.p.lead_m, b->m.p.counts_per_rev,
                              in->index_lost[ch]);
            if (in->enc_glitch[ch])
                hg_encoder_glitch(e, in->enc_glitch[ch]);
        } else {
            e->index_pulse = 0;
        }
        if (in->enc_reset[ch])
            hg_encoder_zero(e);
        if (memcmp(&s, &b->enc_scale_in[ch], sizeof s) != 0) { // NOLINT(bugprone-suspicious-memory-comparison): bitwise, a NaN scale equals itself
            b->enc_scale_in[ch] = s;
            if (!isfinite(s) || (s < 1e-20 && s > -1e-20)) {
                out->enc_scale_bad |= 1u << ch;
                b->param_error = 1;
                s = 1.0;              /* as hal_motenc */
            }
            b->enc_scale[ch] = s;
        }
        s = b->enc_scale[ch];
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
static void adc(hg_board *b, const hg_board_inputs *in)
{
    int i, done = b->adc_state == 1 ? 0 : 4, next = b->adc_state == 1 ? 4 : 0;
    if (!in->adc_read)
        return;
    if (b->adc_state != 0)
        for (i = done; i < done + 4; i++)
            b->adc_value[i] = hg_adc_value(b->adc_sample_v[i], in->adc_gain[i], in->adc_offset[i]);
    for (i = next; i < next + 4; i++) {
        double amps = i < HG_BOARD_JOINTS && !b->fault ? b->d.current_a[i] : 0.0;
        b->adc_sample_v[i] = hg_adc_sample(amps * in->adc_volts_per_amp);
    }
    b->adc_state = b->adc_state == 1 ? 2 : 1;
}

/* Everything the outputs show that is not an event: state, sensors, latches. */
static void publish(const hg_board *b, const hg_board_inputs *in, hg_board_outputs *out,
                    const double volts[6])
{
    int k, i, open = in ? estop_open(in) : 0; /* before any step: pins as hal_motenc powers up */
    for (k = 0; k < HG_BOARD_JOINTS; k++) {
        out->z_m[k] = finite_or_zero(b->d.z_m[k]);
        out->zd_mps[k] = finite_or_zero(b->d.zd_mps[k]);
        out->volts[k] = finite_or_zero(volts[k]);
        out->current_a[k] = b->fault ? 0.0 : finite_or_zero(b->d.current_a[k]);
        out->force_n[k] = finite_or_zero(b->d.force_n[k]);
    }
    for (k = 0; k < 6; k++)
        out->pose[k] = finite_or_zero(b->d.pose[k]);
    for (i = 0; i < HG_BOARD_INPUTS; i++) {
        int j = i / HG_INPUTS_PER_JOINT, bit = i % HG_INPUTS_PER_JOINT, v = 0;
        if (j < HG_BOARD_JOINTS)
            v = bit == HG_IN_AMP_FAULT ? (in && in->amp_fail[j] != 0) : (int)((b->switches[j] >> bit) & 1u);
        out->in[i] = (unsigned char)v;
    }
    for (k = 0; k < HG_BOARD_ADCS; k++)
        out->adc[k] = finite_or_zero(b->adc_value[k]);
    /* E-STOP and an expired watchdog switch the outputs off in hardware */
    out->dout_word = (!in || open || b->wd.expired) ? 0u : (in->dout_values ^ in->dout_inverts);
    out->estop_in = open;
    out->sim_time_s = finite_or_zero(b->d.t_s);
    out->residual_m = finite_or_zero(b->d.residual_m);
    out->steps = b->steps;
    out->bars_broken = b->d.broken_bars;
    out->fault = b->fault;
    out->fault_code = b->fault_code;
    out->fault_guard = b->fault_guard;
    out->watchdog_expired = b->wd.expired;
    out->param_error = b->param_error;
    out->dac_nan = b->dac_nan != 0;
    out->params.model = b->m.p;
    out->params.substeps = b->substeps;
    out->substeps_run = b->substeps_run;
    if (out->stiff_param < 0 || !(out->events & HG_EV_PARAM_REFUSED)) {
        out->stiff_param = b->substeps_run > b->substeps || b->fault_code == HG_ERR_STIFF ? b->stiff_param : -1;
        out->stiff_dt_max_s = out->stiff_param >= 0 ? b->stiff_dt_max_s : 0.0;
    }
    out->params.integrator = (unsigned)b->m.integrator;
}

void hg_board_peek(const hg_board *b, hg_board_outputs *out)
{
    static const double zero[6] = {0, 0, 0, 0, 0, 0};
    int ch;
    memset(out, 0, sizeof *out);
    publish(b, 0, out, zero);
    for (ch = 0; ch < HG_BOARD_ENCODERS; ch++) {
        out->count[ch] = hg_encoder_count(&b->enc[ch]);
        out->position[ch] = finite_or_zero(out->count[ch] / b->enc_scale[ch]);
        out->enc_scale[ch] = b->enc_scale[ch];
    }
}

/* First joint whose bar-broken input is set, or -1. */
static int bar_input_set(const hg_board_inputs *in)
{
    int k;
    for (k = 0; k < HG_BOARD_JOINTS; k++)
        if (in->bar_broken[k])
            return k;
    return -1;
}

/* A step whose volts are not this period's (no dac-write since the last
 * step, or one before the encoders were read) twice in a row: the servo
 * thread's addf order is wrong; said once per load or reset. The first
 * period of a thread that runs dynamics first is not a fault: two in a row. */
static void addf_order(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out)
{
    if (in->dac_written && !in->dac_stale) {
        b->order_bad_run = 0;
        return;
    }
    if (b->order_bad_run < 2)
        b->order_bad_run++;
    if (b->order_bad_run == 2 && !b->order_reported) {
        out->events |= HG_EV_ADDF_ORDER;
        b->order_reported = 1;
    }
}

void hg_board_step(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out, long period_ns)
{
    double volts[6] = {0, 0, 0, 0, 0, 0}, dac_out_v[HG_BOARD_DACS];
    double dt = (double)period_ns * 1e-9;
    unsigned nan_now = 0;
    int k, amps_on, expired;

    memset(out, 0, sizeof *out);
    out->reset_refused_joint = -1;
    out->stiff_param = -1;
    /* reset edge: HOME at rest, unless a bar-broken input still holds */
    if (in->reset && !b->prev_reset) {
        int j = bar_input_set(in);
        if (j >= 0) {
            out->events |= HG_EV_RESET_REFUSED;
            out->reset_refused_joint = j;
        } else {
            b->param_error = 0;       /* the input block is tried again */
            apply_params(b, &in->params, out);
            reinit_at_home(b, out);
            b->order_bad_run = b->order_reported = 0;
            out->events |= HG_EV_RESET_DONE;
        }
    } else if (params_differ(&in->params, &b->last_in)) {
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
    addf_order(b, in, out);
    expired = hg_watchdog_advance(&b->wd, dt);
    amps_on = !estop_open(in) && !expired && !b->fault;
    b->d.amp_enabled = 0;
    for (k = 0; k < HG_BOARD_JOINTS; k++) {
        int on = amps_on && !in->amp_fail[k];
        volts[k] = on ? dac_out_v[k] : 0.0;
        b->d.amp_enabled |= on ? 1u << k : 0u;   /* a disabled amplifier passes no current */
    }

    if (!b->fault && dt > 0.0)
        find_substeps(b, period_ns, out);
    if (!b->fault) {
        int rc;
        break_bars(b, in, out);
        rc = integrate(b, volts, dt);
        if (rc)
            latch_fault(b, out, rc, HG_FAULT_STEP);
        else
            b->steps++;
    }
    if (b->fault)
        for (k = 0; k < HG_BOARD_JOINTS; k++)
            volts[k] = 0.0;
    out->amps_on = amps_on && !b->fault;

    encoders(b, in, out);
    for (k = 0; k < HG_BOARD_JOINTS; k++)
        b->switches[k] = hg_switches_stuck(hg_switches(&b->m.p, b->d.z_m[k]), b->switches[k],
                                           in->stuck[k]) | in->tripped[k];
    adc(b, in);
    publish(b, in, out, volts);
}

void hg_board_describe_stiffness(const hg_board *b, const hg_board_outputs *out, long period_ns, int hal,
                                 char buf[HG_BOARD_TEXT_LEN])
{
    const unsigned long n = HG_BOARD_TEXT_LEN;
    int np;
    const hg_param_info *t = hg_params_table(&np);
    const hg_param_info *e = out->stiff_param >= 0 && out->stiff_param < np ? &t[out->stiff_param] : 0;
    buf[0] = '\0';
    if (!e)
        return;
    hg_text_add(buf, n, hal ? e->hal_name : e->name);
    hg_text_add(buf, n, " = ");
    hg_text_add_value(buf, n, hg_params_get(&b->m.p, out->stiff_param) * (hal ? e->hal_scale : 1.0));
    hg_text_add(buf, n, " ");
    hg_text_add(buf, n, hal ? e->hal_unit : e->unit);
    hg_text_add(buf, n, ": ");
    hg_text_add(buf, n, hg_integrator_name(b->m.integrator));
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
