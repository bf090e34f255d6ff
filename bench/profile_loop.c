/* profile_loop.c - the offline closed loop's workload for callgrind
 * (bench/profile_step.sh; docs/benchmarks.md): two runs of hg_loop (six
 * LinuxCNC pids and the board, as tune's search and bench_batch run them)
 * through hg_batch_run on one thread, each PERIODS servo periods (default
 * 2000) of a cosine move of every joint out 20..30 mm and back, from rest
 * at HOME, optionally after SETTLE periods at rest (tune's runs settle at
 * their first command), with gains about tune's (bench_loop.h: bench_batch's). TRAIN: flexible (the
 * default drive trains and Heun, the tool-path error skipped: tune's
 * verification), flexible_rk4 (the same on RK4: tune's search,
 * docs/tuning.md), flexible_tool (Heun with it: replay's what-ifs, soak)
 * or rigid (k_axial 0, skipped). callgrind
 * --toggle-collect=hg_loop_run_stop counts only the runs; prints the
 * runs' codes and a sum of their peaks.
 * Usage: profile_loop flexible|flexible_rk4|flexible_tool|rigid [PERIODS [SETTLE]] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hg_batch.h"
#include "hg_scheme.h"
#include "bench_loop.h"

#define JOBS 2
#define PERIODS_MAX 100000L

int main(int argc, char **argv)
{
    static hg_loop_config cfg[JOBS];
    static double cmd[6 * PERIODS_MAX];
    const hg_plant *pl = hg_plant_at(0);
    hg_board_params bp;
    hg_batch_job jobs[JOBS];
    hg_batch_result res[JOBS];
    long n = argc > 2 ? atol(argv[2]) : 2000, settle = argc > 3 ? atol(argv[3]) : 0;
    int j, tool = argc > 1 && strcmp(argv[1], "flexible_tool") == 0;
    int rigid = argc > 1 && strcmp(argv[1], "rigid") == 0;
    int rk4 = argc > 1 && strcmp(argv[1], "flexible_rk4") == 0;
    double sum = 0.0;
    if (argc < 2 || !(tool || rigid || rk4 || strcmp(argv[1], "flexible") == 0) || n < 1 || settle < 0 ||
        n + settle > PERIODS_MAX) {
        fprintf(stderr, "usage: profile_loop flexible|flexible_rk4|flexible_tool|rigid [PERIODS [SETTLE]] "
                        "(PERIODS + SETTLE <= %ld)\n", PERIODS_MAX);
        return 2;
    }
    bench_loop_move(cmd, n, settle);
    hg_board_params_default(0, pl->default_variant, &bp);
    if (rigid)
        bp.plant.v[hg_plant_param_find(pl, pl->default_variant, "k_axial")] = 0.0;
    if (rk4)
        bp.integrator = HG_INTEGRATOR_RK4;
    for (j = 0; j < JOBS; j++) {
        bench_loop_gains(&cfg[j], j);
        memset(&jobs[j], 0, sizeof jobs[j]);
        jobs[j].cfg = &cfg[j];
        jobs[j].params = &bp;
        jobs[j].cmd_mm = cmd;
        jobs[j].n = settle + n;
        jobs[j].skip_tool_error = !tool;
    }
    if (hg_batch_run(jobs, JOBS, 1, res) != 0)
        return 1;
    for (j = 0; j < JOBS; j++)
        sum += res[j].sum.peak_ferror_mm[0] + res[j].sum.peak_tool_error_mm;
    printf("profile_loop %s: %d runs of %ld periods (%ld at rest first), codes %d %d, sum of peaks %.17g\n",
           argv[1], JOBS, settle + n, settle, res[0].rc, res[1].rc, sum);
    return res[0].rc || res[1].rc;
}
