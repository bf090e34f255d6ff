/* bench_kinematics.c - time per inverse and forward kinematics call and
 * forward iterations over many random poses of the working volume. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "hg_errors.h"
#include "hg_kinematics.h"
#include "hg_guard.h"
#include "hg_params.h"
#include "bench_timing.h"

#define NPOSES 20000
#define DEG (3.14159265358979323846 / 180.0)

static double uniform(unsigned *s, double lo, double hi)
{
    *s = *s * 1664525u + 1013904223u;
    return lo + (hi - lo) * (*s >> 8) / 16777216.0;
}

int main(void)
{
    static double poses[NPOSES][6], joints[NPOSES][6], t_ik[NPOSES], t_fk_home[NPOSES],
        t_fk_near[NPOSES];
    hg_params p;
    hg_fk_report rep;
    unsigned seed = 12345;
    int n = 0, i, k, it_home = 0, it_near = 0, max_home = 0, reps = 8;
    double med, p99, sink = 0;
    hg_params_default(&p);
    while (n < NPOSES) {
        double *c = poses[n];
        c[0] = uniform(&seed, -0.12, 0.12); c[1] = uniform(&seed, -0.12, 0.12);
        c[2] = uniform(&seed, -0.2, 0.2);   c[3] = uniform(&seed, -20, 20) * DEG;
        c[4] = uniform(&seed, -20, 20) * DEG; c[5] = uniform(&seed, -25, 25) * DEG;
        if (hg_inverse_kinematics(&p.geo, c, joints[n]) == HG_OK)
            n++;
    }
    for (i = 0; i < NPOSES; i++) {
        double z[6], t0 = bench_now_us();
        for (k = 0; k < reps; k++)
            hg_inverse_kinematics(&p.geo, poses[i], z);
        t_ik[i] = (bench_now_us() - t0) / reps;
        sink += z[0];
    }
    for (i = 0; i < NPOSES; i++) {
        double c[6] = {0, 0, 0, 0, 0, 0}, t0 = bench_now_us();
        hg_forward_kinematics(&p.geo, joints[i], c, 0, &rep);
        t_fk_home[i] = bench_now_us() - t0;
        it_home += rep.iterations;
        if (rep.iterations > max_home)
            max_home = rep.iterations;
    }
    /* motion's case: the guess is last cycle's answer, 1 um / 1 mrad away */
    for (i = 0; i < NPOSES; i++) {
        double c[6], t0;
        for (k = 0; k < 6; k++)
            c[k] = poses[i][k] + 1e-6;
        t0 = bench_now_us();
        hg_forward_kinematics(&p.geo, joints[i], c, 0, &rep);
        t_fk_near[i] = bench_now_us() - t0;
        it_near += rep.iterations;
    }
    printf("kinematics over %d random poses (X,Y +-120 mm, Z +-200 mm, A,B +-20 deg, C +-25 deg)\n", NPOSES);
    bench_percentiles(t_ik, NPOSES, &med, &p99);
    printf("  inverse:              median %.3f us, p99 %.3f us\n", med, p99);
    printf("BENCH kins-inverse median_us=%.4f p99_us=%.4f\n", med, p99);
    bench_percentiles(t_fk_home, NPOSES, &med, &p99);
    printf("  forward from HOME:    median %.3f us, p99 %.3f us, %.2f iterations (max %d)\n", med,
           p99, (double)it_home / NPOSES, max_home);
    printf("BENCH kins-forward-from-home median_us=%.4f p99_us=%.4f iters=%.2f\n", med, p99,
           (double)it_home / NPOSES);
    bench_percentiles(t_fk_near, NPOSES, &med, &p99);
    printf("  forward from 1e-6 away (motion's case): median %.3f us, p99 %.3f us, %.2f iterations\n",
           med, p99, (double)it_near / NPOSES);
    printf("BENCH kins-forward-tracking median_us=%.4f p99_us=%.4f iters=%.2f\n", med, p99,
           (double)it_near / NPOSES);
    return sink == 12345.678 ? 1 : 0;
}
