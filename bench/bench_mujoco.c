/* bench_mujoco.c - MuJoCo, the peer a user would pick instead of the
 * project's dynamics, stepping the same machine (bench/hg_mujoco_model.c)
 * at the 1 ms servo period under a smooth servo motion.
 *
 * Prints the median and 99th percentile wall time of one mj_step (RK4, the
 * accurate setting used by tests/engine, and Euler, MuJoCo's cheapest), the
 * largest loop-closure error MuJoCo leaves, and, when the project's
 * dynamics is linked in, the time of one hg_step per model kind with the
 * same motion and the ratio MuJoCo / project. Machine lines:
 *   BENCH mujoco median_us=<x> p99_us=<y> iters=<n>
 *   BENCH mujoco_euler median_us=<x> p99_us=<y> iters=<n>
 * bench_mujoco --mjcf prints the generated model instead. */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hg_dynamics.h"
#include "hg_mujoco_model.c"
#include "bench_timing.h"

/* The project's dynamics may not be built yet: link it weakly. */
#pragma weak hg_model_init
#pragma weak hg_data_reset
#pragma weak hg_step
#pragma weak hg_model_name

#define STEPS 100000
#define WARMUP 1000
#define DT_S 1e-3

/* Servo motion: a P controller (kp V/m) on a 20 mm, 0.5 Hz sine per
 * carriage, phases 60 degrees apart (the head translates and tilts), plus
 * the voltage that holds the weight. */
typedef struct {
    double hold_v, kp_v_per_m;
} bench_servo;

static void bench_servo_init(bench_servo *s, const hg_params *p)
{
    double w = p->g_mps2 * (p->m_head_kg + 6.0 * (p->m_bar_kg + p->m_carriage_kg));
    s->hold_v = w / 6.0 / hgmj_force_per_volt(p);
    s->kp_v_per_m = 300.0;
}

/* DAC volts for time t and carriage heights z. */
static void bench_servo_volts(const bench_servo *s, double t, const double z[6], double v[6])
{
    int k;
    for (k = 0; k < 6; k++) {
        double ref = 0.02 * sin(2.0 * M_PI * 0.5 * t + k * M_PI / 3.0);
        v[k] = fmax(-10.0, fmin(10.0, s->hold_v + s->kp_v_per_m * (ref - z[k])));
    }
}

/* Time mj_step with the given integrator; 0 or -1. */
static int bench_mujoco(const hg_params *p, const char *integrator, const char *name,
                        double *us, double *median_out)
{
    hgmj_options o;
    hgmj_index ix;
    bench_servo s;
    char err[1000];
    mjModel *m;
    mjData *d;
    double z[6], v[6], zmax = 0.0, viol = 0.0, viol_t = 0.0, viol_steady = 0.0, median, p99;
    int i, k;

    hgmj_options_default(&o);
    o.integrator = integrator;
    m = hgmj_load(p, &o, err, sizeof err);
    if (!m || hgmj_index_build(m, &ix) != 0) {
        fprintf(stderr, "bench_mujoco: cannot load the MuJoCo model: %s\n", m ? "names missing" : err);
        return -1;
    }
    d = mj_makeData(m);
    bench_servo_init(&s, p);
    for (i = 0; i < WARMUP + STEPS; i++) {
        double t0, t1;
        hgmj_joints(d, &ix, z);
        bench_servo_volts(&s, d->time, z, v);
        for (k = 0; k < 6; k++)
            d->ctrl[k] = v[k];
        t0 = bench_now_us();
        mj_step(m, d);
        t1 = bench_now_us();
        if (i >= WARMUP)
            us[i - WARMUP] = t1 - t0;
        /* outside the timed region: the loop closure of the new state */
        mj_kinematics(m, d);
        if (hgmj_connect_violation(d, &ix) > viol) {
            viol = hgmj_connect_violation(d, &ix);
            viol_t = d->time;
        }
        if (d->time > 1.0) /* after the servo's start-up transient */
            viol_steady = fmax(viol_steady, hgmj_connect_violation(d, &ix));
        for (k = 0; k < 6; k++)
            zmax = fmax(zmax, fabs(d->qpos[ix.slide_qpos[k]]));
    }
    bench_percentiles(us, STEPS, &median, &p99);
    printf("mujoco %-8s nq=%d nv=%d equality rows=%d: median %.2f us, p99 %.2f us per mj_step; "
           "max |z| %.1f mm, loop-closure error: max %.3g m (at t = %.3f s), max after 1 s %.3g m, over %.0f s\n",
           integrator, m->nq, m->nv, 3 * m->neq, median, p99, zmax * 1e3, viol, viol_t, viol_steady, d->time);
    printf("BENCH %s median_us=%.3f p99_us=%.3f iters=%d\n", name, median, p99, STEPS);
    *median_out = median;
    mj_deleteData(d);
    mj_deleteModel(m);
    return 0;
}

/* Time hg_step of one model kind with the same motion; 0, or -1 when the
 * kind is not available. */
static int bench_project(const hg_params *p, hg_model_kind kind, double *us, double *median_out,
                         double *p99_out)
{
    static hg_model m; /* large: keep off the stack */
    static hg_data d;
    const char *bad = 0, *why = 0;
    bench_servo s;
    double v[6], median, p99;
    int i;

    if (hg_model_init(&m, p, kind, &bad, &why) != 0 || hg_data_reset(&m, &d) != 0)
        return -1;
    bench_servo_init(&s, p);
    for (i = 0; i < WARMUP + STEPS; i++) {
        double t0, t1;
        int rc;
        bench_servo_volts(&s, d.t_s, d.z_m, v);
        t0 = bench_now_us();
        rc = hg_step(&m, &d, v, DT_S);
        t1 = bench_now_us();
        if (rc != 0)
            return -1;
        if (i >= WARMUP)
            us[i - WARMUP] = t1 - t0;
    }
    bench_percentiles(us, STEPS, &median, &p99);
    *median_out = median;
    *p99_out = p99;
    return 0;
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
    hg_params p;
    double *us;
    double mj_rk4, mj_euler;
    int kind;

    hg_params_default(&p);
    if (argc > 1 && !strcmp(argv[1], "--mjcf"))
        return print_mjcf(&p);
    if (argc > 1) {
        fprintf(stderr, "usage: %s [--mjcf]\n", argv[0]);
        return 2;
    }
    us = malloc(STEPS * sizeof *us);
    if (!us || bench_mujoco(&p, "RK4", "mujoco", us, &mj_rk4) != 0 ||
        bench_mujoco(&p, "Euler", "mujoco_euler", us, &mj_euler) != 0)
        return 1;
    if (!hg_step) {
        printf("project dynamics not linked (src/hg_dynamics.c missing): no ratios\n");
    } else {
        for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
            double median, p99;
            if (bench_project(&p, (hg_model_kind)kind, us, &median, &p99) != 0) {
                printf("project %-18s not available\n", hg_model_name((hg_model_kind)kind));
                continue;
            }
            printf("project %-18s median %.2f us, p99 %.2f us per hg_step: MuJoCo RK4 takes %.1fx, Euler %.1fx as long\n",
                   hg_model_name((hg_model_kind)kind), median, p99, mj_rk4 / median, mj_euler / median);
        }
    }
    free(us);
    return 0;
}
