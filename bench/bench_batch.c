/* bench_batch.c - offline closed-loop throughput: servo periods per second
 * of hg_batch_run with 1 thread and with every core (and 2), the default
 * (flexible) drive train and the rigid one (k_axial 0), on a batch of
 * independent runs as tune's search makes (16 candidates x 2 s of joint
 * commands, the tool-path error skipped: skip_tool_error), and the flexible
 * train with the tool-path error (flexible_tool: replay's what-ifs, soak).
 * Thread counts interleave within one run, repeated 5 times; medians and
 * the ratio of the medians (a shared machine moves both alike).
 *   build/bench/bench_batch [REPEATS]
 * BENCH lines: batch_<train>_<N>t median_us=<us per period> and
 * batch_<train>_speedup_<N>t ratio=<periods/s with N threads over 1>. */
#include <math.h>
#include <stdio.h>
#include "hg_batch.h"
#include "bench_timing.h"

#define N 2000
#define JOBS 16
#define REPS_MAX 21
#define TRAINS 3   /* flexible (as tune's search: no tool error), flexible with it, rigid */

static double cmd[N * 6];

/* Wall time (us) of one batch of JOBS runs on `threads` threads. */
static double time_batch(const hg_batch_job *jobs, int threads)
{
    hg_batch_result res[JOBS];
    double t0 = bench_now_us();
    hg_batch_run(jobs, JOBS, threads, res);
    return bench_now_us() - t0;
}

int main(int argc, char **argv)
{
    static hg_loop_config cfg[JOBS];
    hg_board_params bp[2];
    static const int params_of[TRAINS] = {0, 0, 1}, skip_of[TRAINS] = {1, 0, 1};
    hg_batch_job jobs[JOBS];
    int reps = argc > 1 ? atoi(argv[1]) : 5, cores = hg_batch_cores(), nt, t, r, i, k, train;
    int counts[3] = {1, 2, cores};
    const char *name[TRAINS] = {"flexible", "flexible_tool", "rigid"};
    if (reps < 1 || reps > REPS_MAX)
        reps = 5;
    nt = cores > 2 ? 3 : 2;
    for (i = 0; i < N; i++)
        for (k = 0; k < 6; k++)
            cmd[6 * i + k] = (10.0 + 2 * k) * (1 - cos(2 * 3.14159265358979323846 * i / N));
    for (train = 0; train < 2; train++)           /* the Hexaglide's defaults, 1 substep asked, Heun */
        hg_board_params_default(0, hg_plant_at(0)->default_variant, &bp[train]);
    bp[1].plant.v[hg_plant_param_find(hg_plant_at(0), hg_plant_at(0)->default_variant, "k_axial")] = 0.0;
    for (i = 0; i < JOBS; i++) {
        hg_loop_config_default(&cfg[i]);
        for (k = 0; k < 6; k++) {
            cfg[i].pid[k].pgain = 15.0 + i;
            cfg[i].pid[k].igain = 40.0 + 5 * i;
            cfg[i].pid[k].dgain = 0.026;
            cfg[i].pid[k].ff1 = 0.026;
            cfg[i].pid[k].ff2 = 0.00036;
            cfg[i].pid[k].bias = 0.26;
            cfg[i].pid[k].maxoutput = 10.0;
        }
    }
    printf("hg_batch_run: %d runs of %d periods, %d core(s) online, %d repeats interleaved\n", JOBS, N, cores, reps);
    for (train = 0; train < TRAINS; train++) {
        double us[3][REPS_MAX], med[3], p99;
        for (i = 0; i < JOBS; i++)
            jobs[i] = (hg_batch_job){&cfg[i], &bp[params_of[train]], cmd, N, 0, {0, 0, 0}, skip_of[train]};
        time_batch(jobs, 1);           /* warm up */
        for (r = 0; r < reps; r++)
            for (t = 0; t < nt; t++)
                us[t][r] = time_batch(jobs, counts[t]) / ((double)JOBS * N);
        for (t = 0; t < nt; t++) {
            bench_percentiles(us[t], reps, &med[t], &p99);
            printf("  %-8s %d thread(s): %.3f us per period, %.0f periods/s\n", name[train], counts[t], med[t],
                   1e6 / med[t]);
            printf("BENCH batch_%s_%dt median_us=%.3f p99_us=%.3f\n", name[train], counts[t], med[t], p99);
        }
        for (t = 1; t < nt; t++)
            printf("BENCH batch_%s_speedup_%dt ratio=%.2f\n", name[train], counts[t], med[0] / med[t]);
    }
    return 0;
}
