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
#include "bench_loop.h"

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
    int reps = argc > 1 ? atoi(argv[1]) : 5, cores = hg_batch_cores(), nt, t, r, i, train;
    int counts[3] = {1, 2, cores};
    const char *name[TRAINS] = {"flexible", "flexible_tool", "rigid"};
    if (reps < 1 || reps > REPS_MAX)
        reps = 5;
    nt = cores > 2 ? 3 : 2;
    bench_loop_move(cmd, N, 0);
    for (train = 0; train < 2; train++)           /* the Hexaglide's defaults, 1 substep asked, Heun */
        hg_board_params_default(0, hg_plant_at(0)->default_variant, &bp[train]);
    bp[1].plant.v[hg_plant_param_find(hg_plant_at(0), hg_plant_at(0)->default_variant, "k_axial")] = 0.0;
    for (i = 0; i < JOBS; i++)
        bench_loop_gains(&cfg[i], i);
    printf("hg_batch_run: %d runs of %d periods, %d core(s) online, %d repeats interleaved\n", JOBS, N, cores, reps);
    for (train = 0; train < TRAINS; train++) {
        double us[3][REPS_MAX], med[3], p99;
        for (i = 0; i < JOBS; i++)
            jobs[i] = (hg_batch_job){&cfg[i], &bp[params_of[train]], cmd, N, 0, {0, 0, 0}, skip_of[train], 0};
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
