/* bench_loop.h - the closed-loop workload bench_batch times and
 * profile_loop counts (the shape of a tune generation): one cosine move of
 * every joint and candidate gains about tune's. */
#ifndef BENCH_LOOP_H
#define BENCH_LOOP_H

#include <math.h>
#include "hg_loop.h"

/* n periods of joint commands (mm, row-major x 6) after `settle` at rest:
 * joint k out 2 (10 + 2k) mm and back over the n periods. */
static inline void bench_loop_move(double *cmd, long n, long settle)
{
    long i;
    int k;
    for (i = 0; i < settle + n; i++)
        for (k = 0; k < 6; k++)
            cmd[6 * i + k] = i < settle ? 0.0
                                        : (10.0 + 2 * k) * (1 - cos(2 * 3.14159265358979323846 * (i - settle) / n));
}

/* Candidate j's loop: hg_loop_config_default with gains about tune's (P and I rising with j). */
static inline void bench_loop_gains(hg_loop_config *cfg, int j)
{
    int k;
    hg_loop_config_default(cfg);
    for (k = 0; k < 6; k++) {
        cfg->pid[k].pgain = 15.0 + j;
        cfg->pid[k].igain = 40.0 + 5 * j;
        cfg->pid[k].dgain = 0.026;
        cfg->pid[k].ff1 = 0.026;
        cfg->pid[k].ff2 = 0.00036;
        cfg->pid[k].bias = 0.26;
        cfg->pid[k].maxoutput = 10.0;
    }
}

#endif
