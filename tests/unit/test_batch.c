/* test_batch.c - hg_batch_run against serial runs: every job's summary
 * and traces equal what hg_loop_init + hg_loop_run give on their own, bit
 * for bit, with 1, 2 and 5 threads (rigid and flexible trains, three gain
 * sets, a notch on two joints, a trip, a job whose config is refused);
 * skipping the tool-path error changes nothing else; the refused
 * arguments; the notch in the loop is biquad.N between pid.N.output
 * and the DAC (its DAC values are a biquad fed the pid outputs); and a
 * job's early stop ends the run where its bound, recomputed from the whole
 * run's traces, first passes the limit, with the same bits before. */
#include <string.h>
#include "hg_batch.h"
#include "hg_errors.h"
#include "hg_scheme.h"
#include "hg_test.h"

#define N 1200
#define JOBS 8

static double cmd[N * 6];

/* hg_loop_stop's bound after period i of a whole run's traces fe, out
 * (J = 6), from the definition: running peak, sums of squares over the
 * scored periods (mask, or from `from` on), over all nsc of them. */
static double bound_at(const hg_loop_stop *st, const double *fe, const double *out, long i, long from)
{
    double peak = st->peak0, sq[6] = {0}, volts = st->volts0, rms = 0.0;
    long r, nsc = 0;
    int k;
    for (r = 0; r < N; r++)
        nsc += st->scored ? st->scored[r] != 0 : r >= from;
    for (r = 0; r <= i; r++) {
        if (st->scored ? !st->scored[r] : r < from)
            continue;
        for (k = 0; k < 6; k++) {
            peak = fmax(peak, fabs(fe[6 * r + k]));
            volts = fmax(volts, fabs(out[6 * r + k]));
            sq[k] += fe[6 * r + k] * fe[6 * r + k];
        }
    }
    for (k = 0; k < 6; k++)
        rms = fmax(rms, sqrt(sq[k] / nsc));
    return peak + st->w_rms * fmax(rms, st->rms0) + st->w_volts * fmax(0.0, volts - st->volts_free);
}

/* The early stop of job j (whole run: its traces fe, out): stopped where
 * bound_at first passes st->above, that bound reported, the traces the
 * same up to there; 1 when all holds (what failed printed). */
static int stop_check(const char *what, hg_batch_job j, hg_loop_stop st, const double *fe, const double *out)
{
    static double fe2[N * 6], out2[N * 6];
    hg_batch_result r;
    long i, want = -1;
    double b = -1.0;
    for (i = 0; i < N && want < 0; i++)
        if ((st.scored ? st.scored[i] != 0 : i >= j.from) && (b = bound_at(&st, fe, out, i, j.from)) > st.above)
            want = i;
    j.stop = &st;
    j.trace = (hg_loop_trace){fe2, out2, 0};
    hg_batch_run(&j, 1, 1, &r);
    CHECK(want > 0 && r.sum.periods == want + 1 && fabs(r.stop_bound - b) <= 1e-12 * b &&
              memcmp(fe2, fe, sizeof(double) * 6 * r.sum.periods) == 0 &&
              memcmp(out2, out, sizeof(double) * 6 * r.sum.periods) == 0 && r.rc == 0 && r.sum.tripped_at < 0,
          "stop, %s: after period %ld of %d (from the traces: %ld), bound %.9g (from the traces: %.9g), "
          "the traces the same bits up to there", what, r.sum.periods - 1, N, want, r.stop_bound, b);
    return want > 0;
}

/* Serial reference of one job: hg_loop_run on a loop of its own. */
static int serial(const hg_batch_job *j, hg_loop_summary *sum, double *fe, double *out)
{
    static hg_loop L;
    int rc = hg_loop_init(&L, j->cfg, j->params);
    if (rc)
        return rc;
    return hg_loop_run(&L, j->cmd_mm, j->n, j->from, fe, out, sum);
}

int main(void)
{
    static hg_loop_config cfg[JOBS];
    static double fe[JOBS][N * 6], out[JOBS][N * 6], fe_s[N * 6], out_s[N * 6], load[N * 6];
    hg_board_params flex, rigid;
    hg_batch_job jobs[JOBS];
    hg_batch_result res[JOBS];
    hg_params p;
    int i, k, t, same_sum = 1, same_trace = 1, same_rc = 1;
    static const int threads[] = {1, 2, 5};

    for (i = 0; i < N; i++)
        for (k = 0; k < 6; k++)
            cmd[6 * i + k] = (5.0 + k) * (1 - cos(2 * 3.14159265358979323846 * i / N));
    hg_params_default(&p);
    hg_test_block(&flex, &p, 1, HG_INTEGRATOR_HEUN);
    p.k_axial_n_per_m = 0.0;
    hg_test_block(&rigid, &p, 1, HG_INTEGRATOR_HEUN);
    for (i = 0; i < JOBS; i++) {
        hg_loop_config_default(&cfg[i]);
        for (k = 0; k < 6; k++) {
            cfg[i].pid[k].pgain = 10.0 + 5.0 * (i % 3);
            cfg[i].pid[k].igain = 40.0 * (1 + i % 2);
            cfg[i].pid[k].dgain = 0.02 + 0.01 * (i % 3);
            cfg[i].pid[k].ff1 = 0.026;
            cfg[i].pid[k].ff2 = 0.00036;
            cfg[i].pid[k].bias = 0.26;
            cfg[i].pid[k].maxoutput = 10.0;
        }
        cfg[i].ferror_limit_mm = 2.0;
        jobs[i] = (hg_batch_job){&cfg[i], i % 2 ? &rigid : &flex, cmd, N, 100, {fe[i], out[i], 0}, 0, 0};
    }
    hg_biquad_notch(&cfg[3].biquad[0], 352.75, 0.7);
    hg_biquad_notch(&cfg[3].biquad[2], 300, 2.0);
    for (k = 0; k < 6; k++)
        cfg[5].pid[k].dgain = -0.5;            /* unstable: trips */
    cfg[6].period_ns = 0;                      /* refused by hg_loop_init */
    jobs[7].params = 0;                        /* the plant's defaults */

    for (t = 0; t < 3; t++) {
        memset(res, 0x55, sizeof res);
        CHECK(hg_batch_run(jobs, JOBS, threads[t], res) == 0, "hg_batch_run on %d thread(s) returns 0", threads[t]);
        for (i = 0; i < JOBS; i++) {
            hg_loop_summary sum;
            int rc = serial(&jobs[i], &sum, fe_s, out_s);
            same_rc &= rc == res[i].rc;
            if (rc == HG_ERR_BAD_DT)
                continue;
            same_sum &= memcmp(&sum, &res[i].sum, sizeof sum) == 0;
            same_trace &= memcmp(fe_s, fe[i], sizeof(double) * 6 * sum.periods) == 0 &&
                          memcmp(out_s, out[i], sizeof(double) * 6 * sum.periods) == 0;
        }
    }
    CHECK(same_rc && res[6].rc == HG_ERR_BAD_DT, "every job's code as the serial run's (the refused period: %d)", res[6].rc);
    CHECK(same_sum, "every summary (peaks, RMS, tool error, periods, trip) = hg_loop_run's, bit for bit, on 1, 2, 5 threads");
    CHECK(same_trace, "every f-error and pid-output trace = hg_loop_run's, bit for bit");
    CHECK(res[5].sum.tripped_at >= 0 && res[5].sum.periods == res[5].sum.tripped_at + 1,
          "the unstable job tripped (period %ld) and stopped there", res[5].sum.tripped_at);
    CHECK(res[0].sum.periods == N && res[0].sum.tripped_at < 0, "a stable job ran its %d periods", N);

    /* the notch sits between pid.N.output and the DAC: the peak DAC value of
     * the notched joint is that of a biquad fed the pid outputs */
    {
        hg_biquad b;
        double peak = 0;
        hg_biquad_notch(&b, 352.75, 0.7);
        for (i = 0; i < res[3].sum.periods; i++) {
            b.in = out[3][6 * i];
            hg_biquad_run(&b, 1000000);
            if (i >= 100 && fabs(b.out) > peak)
                peak = fabs(b.out);
        }
        CHECK(peak == res[3].sum.peak_output_v[0] && peak != res[3].sum.peak_output_v[1],
              "notched joint 0: peak DAC value %.6f V = a biquad on its pid outputs (joint 1 unfiltered: %.6f V)",
              peak, res[3].sum.peak_output_v[1]);
    }
    /* the load trace is the carriage: it lags the encoder by the train's windup */
    {
        hg_batch_job j = jobs[0];
        j.trace = (hg_loop_trace){0, 0, load};
        hg_batch_run(&j, 1, 1, res);
        CHECK(fabs(load[6 * (N / 2)] - cmd[6 * (N / 2)]) < 0.05, "load trace near the command mid-move (%.4f vs %.4f mm)",
              load[6 * (N / 2)], cmd[6 * (N / 2)]);
    }
    /* skipping the tool-path error changes nothing else: the same summary
     * but its peak, the same traces (rigid and flexible trains) */
    for (i = 0; i < 2; i++) {
        hg_batch_job j = jobs[i];
        hg_batch_result with, without;
        static double fe2[N * 6], out2[N * 6];
        hg_batch_run(&j, 1, 1, &with);
        j.skip_tool_error = 1;
        j.trace = (hg_loop_trace){fe2, out2, 0};
        hg_batch_run(&j, 1, 1, &without);
        CHECK(without.sum.peak_tool_error_mm == HG_TOOL_ERROR_SKIPPED && with.sum.peak_tool_error_mm > 0.0,
              "%s train: skip_tool_error gives peak tool error %g (computed: %.6f mm)", i ? "rigid" : "flexible",
              without.sum.peak_tool_error_mm, with.sum.peak_tool_error_mm);
        without.sum.peak_tool_error_mm = with.sum.peak_tool_error_mm;
        CHECK(memcmp(&with, &without, sizeof with) == 0 &&
                  memcmp(fe2, fe[i], sizeof(double) * 6 * with.sum.periods) == 0 &&
                  memcmp(out2, out[i], sizeof(double) * 6 * with.sum.periods) == 0,
              "%s train: without the tool error every other summary field and trace is the same bits",
              i ? "rigid" : "flexible");
    }
    /* the early stop, on the stable flexible job's whole run (fe[0], out[0]) */
    {
        static unsigned char every3[N];
        hg_batch_job j = jobs[0];
        hg_batch_result whole, none;
        hg_loop_stop st = {0, 0.0, 0.2, 1.0, 0.0, 0.0, 0.0, 0.0, 0};
        hg_batch_run(&j, 1, 1, &whole);
        st.above = bound_at(&st, fe[0], out[0], N / 2, j.from);   /* passed in the second half */
        stop_check("peak + RMS + volts from `from` on", j, st, fe[0], out[0]);
        for (i = 0; i < N; i++)
            every3[i] = i % 3 == 1 && i > 300;
        st.scored = every3;
        st.above = bound_at(&st, fe[0], out[0], 2 * N / 3, j.from);
        stop_check("every third period after 300 scored", j, st, fe[0], out[0]);
        st.scored = 0;
        st.peak0 = 0.1;
        st.rms0 = 0.01;
        st.volts0 = 0.5;
        st.volts_free = 0.3;
        st.above = 0.5 * (bound_at(&st, fe[0], out[0], j.from, j.from) + bound_at(&st, fe[0], out[0], N / 2, j.from));
        stop_check("floors from earlier runs, passed by the run's own terms", j, st, fe[0], out[0]);
        st.peak0 = 5.0;
        st.above = 5.0;
        CHECK(stop_check("floors alone above the limit", j, st, fe[0], out[0]) && bound_at(&st, fe[0], out[0], j.from, j.from) > 5.0,
              "... which stops the run at its first scored period (%ld)", j.from);
        st = (hg_loop_stop){0, 1e9, 0.2, 1.0, 0.0, 0.0, 0.0, 0.0, 1};
        j.stop = &st;
        hg_batch_run(&j, 1, 1, &none);
        CHECK(none.stop_bound == -1.0 && memcmp(&none.sum, &whole.sum, sizeof whole.sum) == 0 && whole.stop_bound == -1.0,
              "stop: a bound that never passes its limit leaves the run whole, the summary the same bits");
    }
    CHECK(hg_batch_run(jobs, -1, 2, res) == HG_ERR_BAD_PARAM && hg_batch_run(0, 3, 2, res) == HG_ERR_BAD_PARAM &&
          hg_batch_run(jobs, 0, 2, 0) == 0, "njobs < 0 or no jobs array refused; an empty batch is 0");
    CHECK(hg_batch_cores() >= 1, "hg_batch_cores: %d", hg_batch_cores());
    return hg_test_exit();
}
