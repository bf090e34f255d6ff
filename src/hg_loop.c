/* hg_loop.c - six LinuxCNC pid loops (and biquads) around the virtual board, one servo period at a time. */
#include "hg_loop.h"
#include "hg_errors.h"
#include "hg_math.h"
#include "hg_units.h"

void hg_loop_config_default(hg_loop_config *c)
{
    int k;
    *c = (hg_loop_config){0};
    for (k = 0; k < HG_LOOP_JOINTS; k++) {
        hg_pid_defaults(&c->pid[k]);
        hg_biquad_defaults(&c->biquad[k]);
        c->input_scale[k] = 1000.0;
        c->output_scale[k] = 1.0;
    }
    c->period_ns = 1000000;
    c->plant = 0;
    c->variant = hg_plant_at(0)->default_variant;
}

/* Record the failed field in *r (may be 0); returns code. */
static int refuse(hg_loop_check_report *r, int code, int joint, const char *component, const char *field,
                  const char *ini_key, const char *why, double value)
{
    if (r) {
        r->joint = joint;
        r->component = component;
        r->field = field;
        r->ini_key = ini_key;
        r->why = why;
        r->value = value;
    }
    return code;
}

/* The rules of an enabled biquad.N (hg_loop_config_check). */
static int biquad_check(const hg_biquad *b, int k, long period_ns, hg_loop_check_report *r)
{
    static const char *const coeff[5] = {"n0", "n1", "n2", "d1", "d2"};
    const double v[5] = {b->n0, b->n1, b->n2, b->d1, b->d2};
    double re, im;
    int i;
    if (!b->enable)
        return HG_OK;                  /* out = in, whatever its settings */
    if (b->type == HG_BIQUAD_DIRECT) {
        for (i = 0; i < 5; i++)
            if (!isfinite(v[i]))
                return refuse(r, HG_ERR_BAD_PARAM, k, "biquad", coeff[i], 0, "must be finite", v[i]);
        return HG_OK;
    }
    if (b->type != HG_BIQUAD_LOW_PASS && b->type != HG_BIQUAD_NOTCH)
        return refuse(r, HG_ERR_BAD_PARAM, k, "biquad", "type", 0, "must be 0 (direct), 1 (low pass) or 2 (notch)",
                      (double)b->type);
    if (!(isfinite(b->f0) && b->f0 > 0.0))
        return refuse(r, HG_ERR_BAD_PARAM, k, "biquad", "f0", 0, "must be finite and > 0 (Hz)", b->f0);
    if (!(b->Q >= 0.5 && b->Q <= 2.0))
        return refuse(r, HG_ERR_BAD_PARAM, k, "biquad", "Q", 0, "must lie in [0.5, 2]: biquad.comp refuses "
                      "another (valid 0), and LinuxCNC would pass pid.N.output unfiltered", b->Q);
    if (!hg_biquad_response(b, period_ns, 0.0, &re, &im))
        return refuse(r, HG_ERR_BAD_PARAM, k, "biquad", "f0", 0, "must be at most half the servo rate: "
                      "biquad.comp refuses more (valid 0), and LinuxCNC would pass pid.N.output unfiltered", b->f0);
    return HG_OK;
}

int hg_loop_config_check(const hg_loop_config *c, hg_loop_check_report *r)
{
    const hg_pid_setting *bad;
    const char *why;
    int k, joints;
    if (c->period_ns <= 0 || c->period_ns > HG_PERIOD_MAX_NS)
        return refuse(r, HG_ERR_BAD_DT, -1, "loop", "period_ns", 0, "must lie in (0, 10000000] ns (at most 10 ms)",
                      (double)c->period_ns);
    joints = hg_plant_channels_at(c->plant, c->variant);
    if (joints <= 0 || joints > HG_LOOP_JOINTS)
        return refuse(r, HG_ERR_BAD_PARAM, -1, "loop", "plant", 0, "must name a plant and model variant of the "
                      "registry (hg_plant.h)", (double)c->plant);
    if (!(isfinite(c->ferror_limit_mm) && c->ferror_limit_mm >= 0.0))
        return refuse(r, HG_ERR_BAD_PARAM, -1, "loop", "ferror_limit_mm", 0, "must be finite and >= 0 (0: no trip)",
                      c->ferror_limit_mm);
    for (k = 0; k < joints; k++) {
        if (hg_pid_gains_check(&c->pid[k], &bad, &why))
            return refuse(r, HG_ERR_BAD_PARAM, k, "pid", bad->pin, bad->ini_key, why,
                          hg_pid_setting_value(&c->pid[k], bad));
        if (!(isfinite(c->input_scale[k]) && fabs(c->input_scale[k]) >= HG_ENC_SCALE_MIN))
            return refuse(r, HG_ERR_BAD_PARAM, k, "loop", "input_scale", "INPUT_SCALE",
                          "must be finite and at least " HG_ENC_SCALE_MIN_TEXT " in magnitude (counts per unit; "
                          "the board's encoder would read a smaller scale as 1)", c->input_scale[k]);
        if (!isfinite(c->output_scale[k]))
            return refuse(r, HG_ERR_BAD_PARAM, k, "loop", "output_scale", "OUTPUT_SCALE", "must be finite",
                          c->output_scale[k]);
        if (!isfinite(c->output_offset[k]))
            return refuse(r, HG_ERR_BAD_PARAM, k, "loop", "output_offset", "OUTPUT_OFFSET", "must be finite",
                          c->output_offset[k]);
        if (biquad_check(&c->biquad[k], k, c->period_ns, r))
            return HG_ERR_BAD_PARAM;
    }
    return HG_OK;
}

int hg_loop_init(hg_loop *L, const hg_loop_config *c, const hg_board_params *p)
{
    int k, rc = hg_loop_config_check(c, 0);
    if (rc)
        return rc;
    L->cfg = *c;
    rc = hg_board_init(&L->board, c->plant, c->variant, p);
    if (rc)
        return rc;
    L->joints = L->board.sense.channels;
    hg_board_inputs_default(&L->board, &L->in);
    L->in.dout_values |= 1u << 7;      /* iocontrol's user-enable-out closes the E-STOP loop (out-07) */
    L->in.dac_written = 1;
    for (k = 0; k < L->joints; k++)
        L->in.enc_scale[k] = c->input_scale[k];
    hg_board_peek(&L->board, &L->out);
    for (k = 0; k < HG_LOOP_JOINTS; k++) {
        hg_pid_reset(&L->pid[k]);
        L->biquad[k] = c->biquad[k];   /* a fresh instance with the config's setp values */
        L->biquad[k].last_enable = L->biquad[k].valid = 0;
        L->biquad[k].in = L->biquad[k].out = L->biquad[k].s1 = L->biquad[k].s2 = 0.0;
        L->prev_cmd_mm[k] = 0.0;
    }
    L->periods = 0;
    return 0;
}

/* The plant: the board's dac-write + dynamics (+ encoders) for one period
 * with the pid outputs as DAC values, through hg_board_step as LinuxCNC's
 * motenc.0.dac-write and motenc.0.dynamics run it. 0 or the fault code. */
static int plant_step(hg_loop *L, const double dac_value[HG_LOOP_JOINTS], long period_ns)
{
    int k;
    for (k = 0; k < L->joints; k++)
        L->in.dac_v[k] = (dac_value[k] - L->cfg.output_offset[k]) * L->cfg.output_scale[k];
    hg_board_step(&L->board, &L->in, &L->out, period_ns);
    if (!L->out.fault)
        return 0;
    return L->out.fault_code ? L->out.fault_code : HG_ERR_STATE_NONFINITE;
}

/* The board's encoder-read: the position the last period left on the counter (mm). */
static double plant_position_mm(const hg_loop *L, int k)
{
    return L->out.position[k];
}

/* The board's unit of channel k in the config's: mm or degrees per m or rad. */
static double user_per_si(const hg_loop *L, int k)
{
    return (L->out.rotary >> k) & 1u ? HG_DEG_PER_RAD : HG_MM_PER_M;
}

int hg_loop_step_io(hg_loop *L, const double *cmd_mm, const int *enable,
                    long period_ns, hg_loop_sample *out)
{
    double fb[HG_LOOP_JOINTS], dac[HG_LOOP_JOINTS] = {0};
    int k, rc;
    for (k = 0; k < L->joints; k++) {
        rc = hg_pid_input_check(cmd_mm[k]);
        if (rc)
            return rc;
    }
    for (k = 0; k < L->joints; k++) {
        fb[k] = plant_position_mm(L, k);
        if (out) {
            out->fb_mm[k] = fb[k];
            out->ferror_mm[k] = L->prev_cmd_mm[k] - fb[k];
        }
        L->biquad[k].in = hg_pid_calc(&L->cfg.pid[k], &L->pid[k], cmd_mm[k], fb[k], enable[k],
                                      L->in.index_enable[k], period_ns);
        hg_biquad_run(&L->biquad[k], period_ns);   /* after the pids, before dac-write */
        dac[k] = L->biquad[k].out;
        if (out) {
            out->output_v[k] = L->biquad[k].in;
            out->dac_value_v[k] = dac[k];
        }
    }
    rc = plant_step(L, dac, period_ns);
    if (out) {
        out->tool_error_mm = L->out.tool_error == HG_TOOL_ERROR_SKIPPED ? HG_TOOL_ERROR_SKIPPED
                             : L->out.tool_error < 0.0                ? -1.0
                                                                      : L->out.tool_error * HG_MM_PER_M;
        for (k = 0; k < L->joints; k++)
            out->load_mm[k] = L->out.pos[k] * user_per_si(L, k);
    }
    for (k = 0; k < L->joints; k++)
        L->prev_cmd_mm[k] = cmd_mm[k];
    L->periods++;
    return rc;
}

int hg_loop_step(hg_loop *L, const double *cmd_mm, hg_loop_sample *out)
{
    static const int on[HG_LOOP_JOINTS] = {1, 1, 1, 1, 1, 1, 1, 1};
    int k;
    for (k = 0; k < L->joints; k++)      /* the board's tool-path error pairs them with this step */
        L->in.pos_cmd[k] = cmd_mm[k] / user_per_si(L, k);
    return hg_loop_step_io(L, cmd_mm, on, L->cfg.period_ns, out);
}

int hg_loop_run(hg_loop *L, const double *cmd_mm, long n, long from, double *ferror_mm,
                double *output_v, hg_loop_summary *sum)
{
    hg_loop_trace tr = {ferror_mm, output_v, 0};
    return hg_loop_run_traced(L, cmd_mm, n, from, &tr, sum);
}

/* Store period i's values of s into the traces tr asks for. */
static void trace_store(const hg_loop_trace *tr, const hg_loop_sample *s, long i, int J)
{
    int k;
    for (k = 0; k < J; k++) {
        if (tr->ferror_mm)
            tr->ferror_mm[J * i + k] = s->ferror_mm[k];
        if (tr->output_v)
            tr->output_v[J * i + k] = s->output_v[k];
        if (tr->load_mm)
            tr->load_mm[J * i + k] = s->load_mm[k];
    }
}

/* The periods of a run that stop scores: its mask's nonzero entries, or those from `from` on. */
static long scored_periods(const hg_loop_stop *stop, long n, long from)
{
    long i, c = 0;
    if (!stop->scored)
        return n > from ? n - (from > 0 ? from : 0) : 0;
    for (i = 0; i < n; i++)
        c += stop->scored[i] != 0;
    return c;
}

/* stop's bound after a scored period (hg_loop_stop): peak, sq and volts over the scored periods so far. */
static double stop_bound_now(const hg_loop_stop *stop, double peak, double sq_max, double volts, long n_scored)
{
    double rms = sqrt(sq_max / (double)n_scored), over;
    peak = peak > stop->peak0 ? peak : stop->peak0;
    rms = rms > stop->rms0 ? rms : stop->rms0;
    volts = volts > stop->volts0 ? volts : stop->volts0;
    over = volts - stop->volts_free;
    return peak + stop->w_rms * rms + stop->w_volts * (over > 0.0 ? over : 0.0);
}

int hg_loop_run_stop(hg_loop *L, const double *cmd_mm, long n, long from, const hg_loop_trace *tr,
                     const hg_loop_stop *stop, hg_loop_summary *sum, double *stop_bound)
{
    hg_loop_sample s = {0};   /* zeroed: fields past the joints stay defined */
    double sq[HG_LOOP_JOINTS] = {0}, ssq[HG_LOOP_JOINTS] = {0}, speak = 0.0, svolts = 0.0;
    long i, counted = 0, n_scored = stop ? scored_periods(stop, n, from) : 0;
    int k, rc = 0, J = L->joints;
    *sum = (hg_loop_summary){0};
    sum->tripped_at = -1;
    if (stop_bound)
        *stop_bound = -1.0;
    for (i = 0; i < n; i++) {
        rc = hg_loop_step(L, cmd_mm + J * i, &s);
        if (rc)
            break;
        if (tr)
            trace_store(tr, &s, i, J);
        for (k = 0; k < J; k++) {
            double fe = fabs(s.ferror_mm[k]), v = fabs(s.dac_value_v[k]);
            if (i < from)
                continue;
            if (fe > sum->peak_ferror_mm[k] || !isfinite(fe))
                sum->peak_ferror_mm[k] = fe;
            if (v > sum->peak_output_v[k] || !isfinite(v))
                sum->peak_output_v[k] = v;
            sq[k] += fe * fe;
            if (L->cfg.ferror_limit_mm > 0 && !(fe <= L->cfg.ferror_limit_mm) && sum->tripped_at < 0)
                sum->tripped_at = i;
        }
        if (i >= from) {
            counted++;
            if (sum->peak_tool_error_mm >= 0.0 && (s.tool_error_mm < 0.0 || s.tool_error_mm > sum->peak_tool_error_mm))
                sum->peak_tool_error_mm = s.tool_error_mm;
        }
        if (sum->tripped_at >= 0) {
            i++;
            break;
        }
        if (stop && (stop->scored ? stop->scored[i] != 0 : i >= from)) {
            double sq_max = 0.0, b;
            for (k = 0; k < J; k++) {
                double fe = fabs(s.ferror_mm[k]), v = fabs(stop->volts_dac ? s.dac_value_v[k] : s.output_v[k]);
                speak = fe > speak ? fe : speak;
                svolts = v > svolts ? v : svolts;
                ssq[k] += fe * fe;
                sq_max = ssq[k] > sq_max ? ssq[k] : sq_max;
            }
            b = stop_bound_now(stop, speak, sq_max, svolts, n_scored);
            if (b > stop->above) {        /* (a NaN bound never stops: the run's own checks see it) */
                if (stop_bound)
                    *stop_bound = b;
                i++;
                break;
            }
        }
    }
    sum->periods = i;
    for (k = 0; k < J; k++)
        sum->rms_ferror_mm[k] = counted ? sqrt(sq[k] / counted) : 0.0;
    return rc;
}

int hg_loop_run_traced(hg_loop *L, const double *cmd_mm, long n, long from, const hg_loop_trace *tr,
                       hg_loop_summary *sum)
{
    return hg_loop_run_stop(L, cmd_mm, n, from, tr, 0, sum, 0);
}

unsigned long hg_loop_sizeof(int which)
{
    switch (which) {
    case 0: return sizeof(hg_loop);
    case 1: return sizeof(hg_loop_config);
    case 2: return sizeof(hg_loop_summary);
    case 3: return sizeof(hg_pid_gains);
    case 7: return sizeof(hg_board_params);
    case 8: return sizeof(hg_board);
    case 9: return sizeof(hg_board_inputs);
    case 10: return sizeof(hg_board_outputs);
    case 11: return sizeof(hg_pid_state);
    case 13: return sizeof(hg_biquad);
    case 14: return sizeof(hg_loop_check_report);
    case 15: return sizeof(hg_pid_setting);
    default: return 0;
    }
}
