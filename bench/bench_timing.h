/* bench_timing.h - the clock and the statistics every bench program uses:
 * monotonic time in microseconds, median and 99th percentile of samples. */
#ifndef BENCH_TIMING_H
#define BENCH_TIMING_H
#include <stdlib.h>
#include <time.h>

/* Monotonic clock in microseconds. */
static inline double bench_now_us(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e6 + t.tv_nsec * 1e-3;
}

static inline int bench_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sort the n samples and return their median and 99th percentile. */
static inline void bench_percentiles(double *samples, int n, double *median, double *p99)
{
    qsort(samples, n, sizeof *samples, bench_cmp_double);
    *median = samples[n / 2];
    *p99 = samples[(int)(0.99 * (n - 1))];
}
#endif
