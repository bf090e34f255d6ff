/* bench_baseline.c - today's default hg_step (reduced-cartesian, Heun,
 * sliding and static friction, the windings, the guard) against commit
 * d20d9e5's, the step before issue 23's speed work, built in the same run
 * from git (bench/baseline.sh) with the same compiler and flags, timed
 * INTERLEAVED as bench_mujoco does: every round gives each engine one
 * block of steps (about 0.15 ms of wall time, each continuing its own run
 * of the same servo motion), the per-step time of a block is its time over
 * its steps, the ratio of two engines is taken within each round, then the
 * median over the rounds. Also a yardstick that needs no history: today's
 * frictionless improved-Euler step (the step before friction, the drive
 * and the guard were added, as far as today's code can still take it).
 * First, both defaults run the same 5,000 steps and their carriage
 * heights are compared (the speed work must not change the answers).
 * Machine lines:
 *   BENCH baseline_same_answers steps=<n> max_dz_m=<x>
 *   BENCH step_default median_us=<x> [old_median_us=<y>] iters=<n>
 *   BENCH ratio_step_vs_d20d9e5 old_over_new=<r>           (when the history has d20d9e5)
 *   BENCH ratio_step_vs_frictionless_euler default_over_euler=<r>
 * Built without -DHG_HAVE_BASELINE (no d20d9e5 in the repository) it says
 * so and prints the yardstick alone. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "hg_dynamics.h"
#include "bench_timing.h"

#define ROUNDS 4000
#define WARMUP_STEPS 1500
#define CHECK_STEPS 5000
#define BLOCK_US 150.0             /* short blocks, many rounds: load changes hit both engines of a round */
#define DT_S 1e-3
#define REF_STEPS 2000              /* the 0.5 Hz reference, one period at 1 ms */

void *now_engine_new(int kind, int integrator, int frictionless);
int now_engine_step(void *e, const double volts[6], double dt, double z[6]);
double now_engine_hold_volts(void *e);
void now_engine_free(void *e);
#ifdef HG_HAVE_BASELINE
void *old_engine_new(int kind, int integrator, int frictionless);
int old_engine_step(void *e, const double volts[6], double dt, double z[6]);
void old_engine_free(void *e);
#endif

typedef int (*step_fn)(void *e, const double volts[6], double dt, double z[6]);

/* One engine running its own servo motion. */
typedef struct {
    const char *name;
    void *h;
    step_fn step;
    long n;                         /* steps taken */
    double z[6];                    /* carriage heights after the last step */
    int block;
    double us[ROUNDS];
} engine;

static double ref_m[REF_STEPS], hold_v;

/* n steps of the servo motion (bench_mujoco's: hold + 300 V/m on a 20 mm
 * 0.5 Hz sine per carriage, phases a sixth of a period apart); 0 or -1. */
static int run(engine *e, int n)
{
    int i, k;
    for (i = 0; i < n; i++, e->n++) {
        double v[6];
        for (k = 0; k < 6; k++) {
            double u = hold_v + 300.0 * (ref_m[(e->n + k * (REF_STEPS / 6)) % REF_STEPS] - e->z[k]);
            v[k] = u > 10.0 ? 10.0 : (u < -10.0 ? -10.0 : u);
        }
        if (e->step(e->h, v, DT_S, e->z) != 0)
            return -1;
    }
    return 0;
}

static double median(const double *x, int n)
{
    static double tmp[ROUNDS];
    double med, p99;
    memcpy(tmp, x, (size_t)n * sizeof *x);
    bench_percentiles(tmp, n, &med, &p99);
    return med;
}

/* Median over the rounds of a's per-step time over b's. */
static double ratio(const engine *a, const engine *b)
{
    double r[ROUNDS];
    int i;
    for (i = 0; i < ROUNDS; i++)
        r[i] = a->us[i] / b->us[i];
    return median(r, ROUNDS);
}

int main(void)
{
    static engine eng[3];
    int ne = 0, i, r, k;
    for (i = 0; i < REF_STEPS; i++)
        ref_m[i] = 0.02 * sin(2.0 * M_PI * i / REF_STEPS);
    eng[ne].name = "today's default";
    eng[ne].step = now_engine_step;
    eng[ne++].h = now_engine_new(HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0);
    eng[ne].name = "today's frictionless improved Euler";
    eng[ne].step = now_engine_step;
    eng[ne++].h = now_engine_new(HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_IMPROVED_EULER, 1);
#ifdef HG_HAVE_BASELINE
    eng[ne].name = "d20d9e5's default";
    eng[ne].step = old_engine_step;
    eng[ne++].h = old_engine_new(HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0);
#else
    printf("no baseline: this repository has no commit d20d9e5 (a shallow clone?); the yardstick\n"
           "is today's frictionless improved-Euler step\n");
#endif
    for (i = 0; i < ne; i++)
        if (!eng[i].h) {
            fprintf(stderr, "bench_baseline: cannot build the engine '%s'\n", eng[i].name);
            return 1;
        }
    hold_v = now_engine_hold_volts(eng[0].h);
#ifdef HG_HAVE_BASELINE
    {   /* the same answers: both defaults through the same steps */
        double dz = 0.0;
        for (i = 0; i < CHECK_STEPS; i++) {
            if (run(&eng[0], 1) || run(&eng[2], 1))
                return 1;
            for (k = 0; k < 6; k++)
                dz = fmax(dz, fabs(eng[0].z[k] - eng[2].z[k]));
        }
        printf("today's and d20d9e5's default step over the same %d steps of the servo motion:\n"
               "largest carriage height difference %.3g m\n", CHECK_STEPS, dz);
        printf("BENCH baseline_same_answers steps=%d max_dz_m=%.3g\n", CHECK_STEPS, dz);
    }
#endif
    for (i = 0; i < ne; i++) {         /* warm up; block sizes from the fastest of 5 trial blocks */
        double t = INFINITY;
        if (run(&eng[i], WARMUP_STEPS))
            return 1;
        for (r = 0; r < 5; r++) {
            double t0 = bench_now_us();
            if (run(&eng[i], 100))
                return 1;
            t = fmin(t, (bench_now_us() - t0) / 100.0);
        }
        eng[i].block = (int)fmax(5.0, fmin(20000.0, BLOCK_US / t));
    }
    for (r = 0; r < ROUNDS; r++)
        for (i = 0; i < ne; i++) {
            double t0 = bench_now_us();
            if (run(&eng[i], eng[i].block))
                return 1;
            eng[i].us[r] = (bench_now_us() - t0) / eng[i].block;
        }
    printf("\ninterleaved: %d rounds, each engine one block of about %.0f us per round\n", ROUNDS,
           BLOCK_US);
    for (i = 0; i < ne; i++)
        printf("%-40s median %.3f us/step (blocks of %d)\n", eng[i].name, median(eng[i].us, ROUNDS),
               eng[i].block);
#ifdef HG_HAVE_BASELINE
    printf("d20d9e5's default step / today's: %.2f\n", ratio(&eng[2], &eng[0]));
    printf("BENCH step_default median_us=%.3f old_median_us=%.3f iters=%d\n",
           median(eng[0].us, ROUNDS), median(eng[2].us, ROUNDS), ROUNDS * eng[0].block);
    printf("BENCH ratio_step_vs_d20d9e5 old_over_new=%.2f\n", ratio(&eng[2], &eng[0]));
#else
    printf("BENCH step_default median_us=%.3f iters=%d\n", median(eng[0].us, ROUNDS),
           ROUNDS * eng[0].block);
#endif
    printf("today's default step / today's frictionless improved-Euler step: %.2f\n",
           ratio(&eng[0], &eng[1]));
    printf("BENCH ratio_step_vs_frictionless_euler default_over_euler=%.2f\n", ratio(&eng[0], &eng[1]));
    for (i = 0; i < ne; i++)
#ifdef HG_HAVE_BASELINE
        (i == 2 ? old_engine_free : now_engine_free)(eng[i].h);
#else
        now_engine_free(eng[i].h);
#endif
    return 0;
}
