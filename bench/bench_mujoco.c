/* bench_mujoco.c - MuJoCo, the peer a user would pick instead of the
 * project's dynamics, stepping the same machine (bench/hg_mujoco_model.c)
 * at the 1 ms servo period under a smooth servo motion, timed INTERLEAVED
 * with the project's hg_step in one process: every round gives each engine
 * one block of steps (about 0.5 ms of wall time, each engine continuing its
 * own run of the same motion), timed as a whole; the per-step time of a
 * block is its time over its steps, and the ratio of two engines is taken
 * within each round, then the median over the rounds. Load on the machine
 * hits all engines of a round alike, so the ratios repeat where the
 * absolute times do not.
 *
 * Engines: MuJoCo RK4 (the accurate setting used by tests/engine), MuJoCo
 * Euler (its cheapest), and hg_step of every model kind with the paper's
 * improved Euler (plus Heun for reduced- and fused-cartesian: the default
 * step), all on the peer set with Coulomb friction (hgmj_peer_params_friction:
 * MuJoCo's frictionloss on each slide, the project's stick-slip law with
 * f_static = f_coulomb; the current limit as the motors' force range). Also
 * prints the largest loop-closure error MuJoCo leaves. Machine lines:
 *   BENCH mujoco median_us=<x> p99_us=<y> iters=<n>
 *   BENCH mujoco_euler median_us=<x> p99_us=<y> iters=<n>
 *   BENCH ratio_<engine> rk4_over=<r> euler_over=<r>
 *   BENCH ratio_mujoco_friction with_over_without=<r>   (MuJoCo RK4, frictionloss on / off)
 * bench_mujoco --mjcf prints the generated model instead. */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hg_dynamics.h"
#include "hg_mujoco_model.c"
#include "bench_timing.h"

#define ROUNDS 1000
#define WARMUP_STEPS 1500           /* 1.5 s: past the servo's start-up transient */
#define BLOCK_US 500.0              /* wall time per engine per round */
#define DT_S 1e-3
#define REF_STEPS 2000              /* the 0.5 Hz reference, one period at 1 ms */
#define MAX_ENGINES 9

/* Servo motion: a P controller (kp V/m) on a 20 mm, 0.5 Hz sine per
 * carriage, phases a sixth of a period apart (the head translates and
 * tilts), plus the voltage that holds the weight. The sine is tabulated
 * so that the motion costs every engine the same few multiply-adds. */
typedef struct {
    double hold_v, kp_v_per_m;
    double ref_m[REF_STEPS];
} bench_servo;

static void bench_servo_init(bench_servo *s, const hg_params *p)
{
    double w = p->g_mps2 * (p->m_head_kg + 6.0 * (p->m_bar_kg + p->m_carriage_kg));
    int i;
    s->hold_v = w / 6.0 / hgmj_force_per_volt(p);
    s->kp_v_per_m = 300.0;
    for (i = 0; i < REF_STEPS; i++)
        s->ref_m[i] = 0.02 * sin(2.0 * M_PI * i / REF_STEPS);
}

/* DAC volts at step `step` for carriage heights z. */
static void bench_servo_volts(const bench_servo *s, long step, const double z[6], double v[6])
{
    int k;
    for (k = 0; k < 6; k++) {
        double ref = s->ref_m[(step + k * (REF_STEPS / 6)) % REF_STEPS];
        double u = s->hold_v + s->kp_v_per_m * (ref - z[k]);
        v[k] = u > 10.0 ? 10.0 : (u < -10.0 ? -10.0 : u);
    }
}

/* One engine: MuJoCo (mm, md) or the project (hm, hd). */
typedef struct {
    char name[40];
    mjModel *mm;
    mjData *md;
    hgmj_index ix;
    hg_model *hm;
    hg_data *hd;
    long step;                      /* steps taken */
    int block;                      /* steps per timed block */
    double us[ROUNDS];              /* per-step time of each round's block */
    double viol, viol_steady, zmax; /* MuJoCo: loop-closure error, stroke */
} engine;

/* Take n steps of engine e on the servo motion; 0 or -1. */
static int engine_run(engine *e, const bench_servo *s, int n, int check)
{
    double z[6], v[6];
    int i, k;
    for (i = 0; i < n; i++, e->step++) {
        if (e->mm) {
            hgmj_joints(e->md, &e->ix, z);
            bench_servo_volts(s, e->step, z, v);
            for (k = 0; k < 6; k++)
                e->md->ctrl[k] = v[k];
            mj_step(e->mm, e->md);
        } else {
            bench_servo_volts(s, e->step, e->hd->z_m, v);
            if (hg_step(e->hm, e->hd, v, DT_S) != 0)
                return -1;
        }
    }
    if (check && e->mm) {               /* outside the timed blocks */
        double c;
        mj_kinematics(e->mm, e->md);
        c = hgmj_connect_violation(e->md, &e->ix);
        e->viol = fmax(e->viol, c);
        if (e->md->time > 2.0)
            e->viol_steady = fmax(e->viol_steady, c);
        hgmj_joints(e->md, &e->ix, z);
        for (k = 0; k < 6; k++)
            e->zmax = fmax(e->zmax, fabs(z[k]));
    }
    return 0;
}

/* Set up a MuJoCo engine with `integrator`; 0 or -1. */
static int engine_mujoco(engine *e, const hg_params *p, const char *integrator)
{
    hgmj_options o;
    char err[1000];
    memset(e, 0, sizeof *e);
    hgmj_options_default(&o);
    o.integrator = integrator;
    snprintf(e->name, sizeof e->name, "mujoco %s", integrator);
    e->mm = hgmj_load(p, &o, err, sizeof err);
    if (!e->mm || hgmj_index_build(e->mm, &e->ix) != 0) {
        fprintf(stderr, "bench_mujoco: cannot load the MuJoCo model: %s\n", e->mm ? "names missing" : err);
        return -1;
    }
    e->md = mj_makeData(e->mm);
    return 0;
}

/* Set up a project engine of `kind` with `scheme`; 0 or -1 (not available). */
static int engine_project(engine *e, const hg_params *p, hg_model_kind kind, int scheme)
{
    memset(e, 0, sizeof *e);
    e->hm = malloc(sizeof *e->hm);
    e->hd = malloc(sizeof *e->hd);
    if (!e->hm || !e->hd || hg_model_init(e->hm, p, kind, 0, 0) != 0 ||
        hg_model_set_integrator(e->hm, scheme) != 0 || hg_data_reset(e->hm, e->hd) != 0)
        return -1;
    snprintf(e->name, sizeof e->name, "%s%s%s", hg_model_name(kind),
             scheme ? " " : "", scheme ? hg_integrator_name((hg_integrator)scheme) : "");
    return 0;
}

static double median_of(const double *x, int n)
{
    static double tmp[ROUNDS];
    double med, p99;
    memcpy(tmp, x, n * sizeof *x);
    bench_percentiles(tmp, n, &med, &p99);
    return med;
}

/* Median over rounds of a->us / b->us. */
static double ratio(const engine *a, const engine *b)
{
    double r[ROUNDS];
    int i;
    for (i = 0; i < ROUNDS; i++)
        r[i] = a->us[i] / b->us[i];
    return median_of(r, ROUNDS);
}

/* Print the MJCF of the default machine (bench_mujoco --mjcf). */
static int print_mjcf(const hg_params *p)
{
    static char xml[1 << 16];
    hgmj_options o;
    hgmj_options_default(&o);
    if (hgmj_write_mjcf(p, &o, xml, sizeof xml) < 0) {
        fprintf(stderr, "bench_mujoco: the parameter set cannot be written as MJCF\n");
        return 1;
    }
    fputs(xml, stdout);
    return 0;
}

int main(int argc, char **argv)
{
    static engine eng[MAX_ENGINES];
    static bench_servo servo;
    hg_params p;
    int ne = 0, i, r, kind;

    hgmj_peer_params_friction(&p);   /* both engines run the same physics, Coulomb friction included */
    if (argc > 1 && !strcmp(argv[1], "--mjcf"))
        return print_mjcf(&p);
    if (argc > 1) {
        fprintf(stderr, "usage: %s [--mjcf]\n", argv[0]);
        return 2;
    }
    bench_servo_init(&servo, &p);
    if (engine_mujoco(&eng[ne++], &p, "RK4") || engine_mujoco(&eng[ne++], &p, "Euler"))
        return 1;
    for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
        if (engine_project(&eng[ne], &p, (hg_model_kind)kind, 0) == 0)
            ne++;
        else
            printf("project %-18s not available\n", hg_model_name((hg_model_kind)kind));
    }
    if (engine_project(&eng[ne], &p, HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN) == 0)
        ne++;
    if (engine_project(&eng[ne], &p, HG_MODEL_FUSED_CARTESIAN, HG_INTEGRATOR_HEUN) == 0)
        ne++;
    {   /* last: MuJoCo RK4 without the friction, what frictionloss costs MuJoCo */
        hg_params q;
        hgmj_peer_params(&q);
        if (engine_mujoco(&eng[ne], &q, "RK4"))
            return 1;
        snprintf(eng[ne++].name, sizeof eng[0].name, "mujoco RK4 frictionless");
    }
    for (i = 0; i < ne; i++) {          /* warm up; block sizes from the warm-up's speed */
        double t0 = bench_now_us(), t;
        if (engine_run(&eng[i], &servo, WARMUP_STEPS, 0))
            return 1;
        t = (bench_now_us() - t0) / WARMUP_STEPS;
        eng[i].block = (int)fmax(5.0, fmin(20000.0, BLOCK_US / t));
    }
    for (r = 0; r < ROUNDS; r++)
        for (i = 0; i < ne; i++) {
            double t0 = bench_now_us(), t1;
            if (engine_run(&eng[i], &servo, eng[i].block, 0))
                return 1;
            t1 = bench_now_us();
            eng[i].us[r] = (t1 - t0) / eng[i].block;
            engine_run(&eng[i], &servo, 0, 1);
        }
    printf("interleaved: %d rounds, each engine one block of about %.0f us per round, its own run of\n"
           "the same servo motion (1 ms steps after %d warm-up steps); per-step time = block time /\n"
           "steps; ratios = median over rounds of the ratio within a round\n\n", ROUNDS, BLOCK_US,
           WARMUP_STEPS);
    for (i = 0; i < 2; i++) {
        double med, p99, tmp[ROUNDS];
        memcpy(tmp, eng[i].us, sizeof tmp);
        bench_percentiles(tmp, ROUNDS, &med, &p99);
        printf("%-28s nq=%d nv=%d: median %.2f us/step (blocks of %d), max |z| %.1f mm, "
               "loop-closure error max %.3g m, after 2 s %.3g m, over %.0f s\n", eng[i].name,
               eng[i].mm->nq, eng[i].mm->nv, med, eng[i].block, eng[i].zmax * 1e3, eng[i].viol,
               eng[i].viol_steady, eng[i].md->time);
        printf("BENCH %s median_us=%.3f p99_us=%.3f iters=%ld\n", i ? "mujoco_euler" : "mujoco",
               med, p99, (long)ROUNDS * eng[i].block);
    }
    printf("\n%-28s %12s %8s %16s %16s\n", "project hg_step", "median us", "block",
           "MuJoCo RK4 / it", "MuJoCo Euler / it");
    for (i = 2; i < ne - 1; i++) {
        double r4 = ratio(&eng[0], &eng[i]), re = ratio(&eng[1], &eng[i]);
        char tag[40];
        printf("%-28s %12.3f %8d %15.1fx %15.1fx\n", eng[i].name, median_of(eng[i].us, ROUNDS),
               eng[i].block, r4, re);
        snprintf(tag, sizeof tag, "%s", eng[i].name);
        for (r = 0; tag[r]; r++)
            if (tag[r] == ' ')
                tag[r] = '_';
        printf("BENCH ratio_%s rk4_over=%.1f euler_over=%.1f\n", tag, r4, re);
    }
    printf("\nMuJoCo RK4 with frictionloss / without (%s): %.2f\n", eng[ne - 1].name,
           ratio(&eng[0], &eng[ne - 1]));
    printf("BENCH ratio_mujoco_friction with_over_without=%.2f\n", ratio(&eng[0], &eng[ne - 1]));
    for (i = 0; i < ne; i++) {
        if (eng[i].mm) {
            mj_deleteData(eng[i].md);
            mj_deleteModel(eng[i].mm);
        }
        free(eng[i].hm);
        free(eng[i].hd);
    }
    return 0;
}
