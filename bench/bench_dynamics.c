/* bench_dynamics.c - wall time of one hg_step per parametrization at the
 * 1 ms servo period under a smooth servo motion (a P controller on a
 * 20 mm, 0.5 Hz sine per carriage about the holding voltage), each step
 * timed alone with clock_gettime(CLOCK_MONOTONIC) over BENCH_STEPS steps
 * after a warm-up; median and 99th percentile. Also prints the paper's
 * Table 1 (2011 PC) with the ratios, and the flop counts of the
 * generated functions each step calls (SymPy count_ops, from the
 * generator). Then one hg_board_step of the whole board, defaults and
 * the drives off (the machine sinking from HOME, reset every 3 s), what
 * bench/hal_step_time.sh measures inside HAL. Last, hg_board_step in
 * periods that each apply a new geometry (the most a parameter change
 * costs the servo thread). Machine lines:
 *   BENCH dyn_<model> median_us=<x> p99_us=<y> flops=<n> iters=<n>
 *   BENCH board_<model> median_us=<x> p99_us=<y> iters=<n>
 *   BENCH change_<model> median_us=<x> p99_us=<y> max_us=<z> iters=<n>
 * bench_dynamics board MODEL prints the board line of that model alone;
 * bench_dynamics N times N steps instead of BENCH_STEPS (a smoke run:
 * tests/check/test_bench_builds). The hg_step lines run rigid trains
 * (k_axial 0, the machine of bench_baseline and make profile): a single
 * 1 ms step cannot integrate the flexible default's axial mode, which the
 * board runs in substeps (the board_ lines). Exit 1 if any run failed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hg_board.h"
#include "hg_dynamics.h"
#include "hg_errors.h"
#include "hg_gen_reduced.h"
#include "hg_gen_standard.h"
#include "bench_timing.h"

#define BENCH_STEPS 200000
#define WARMUP 2000
static int steps = BENCH_STEPS;         /* timed steps per measurement (fewer in a smoke run) */
#define DT_S 1e-3
#define PI 3.14159265358979323846

/* DAC volts of the servo motion at time t. */
static void servo(const hg_model *m, double t, const double z[6], double v[6])
{
    const hg_params *p = &m->p;
    double hold = p->g_mps2 * (p->m_head_kg + 6 * (p->m_bar_kg + p->m_carriage_kg)) / 6 /
                  m->force_per_volt_n;
    int k;
    for (k = 0; k < 6; k++) {
        double ref = 0.02 * sin(2 * PI * 0.5 * t + k * PI / 3);
        v[k] = fmax(-10.0, fmin(10.0, hold + 300.0 * (ref - z[k])));
    }
}

/* Median and p99 (us) of `steps` timed steps of one parametrization. */
static int bench(hg_model_kind kind, double *ns, double *median, double *p99)
{
    hg_params p;
    static hg_model m;
    hg_data d;
    int s, rc;
    hg_params_default(&p);
    p.k_axial_n_per_m = 0.0;            /* rigid trains: one step per period (see the top) */
    if ((rc = hg_model_init(&m, &p, kind, 0, 0)) || (rc = hg_data_reset(&m, &d)))
        return rc;
    for (s = 0; s < WARMUP + steps; s++) {
        double v[6], t0, t1;
        servo(&m, d.t_s, d.z_m, v);
        t0 = bench_now_us();
        rc = hg_step(&m, &d, v, DT_S);
        t1 = bench_now_us();
        if (rc)
            return rc;
        if (s >= WARMUP)
            ns[s - WARMUP] = t1 - t0;
    }
    bench_percentiles(ns, steps, median, p99);
    return 0;
}

/* Median and p99 (us) of `steps` hg_board_step calls with the drives
 * off (E-STOP loop open): the machine sinks from HOME; a reset every 3000
 * periods keeps it far from the stops. */
static int bench_board(hg_model_kind kind, double *ns, double *median, double *p99)
{
    static hg_board b;
    static hg_board_inputs in;
    static hg_board_outputs out;
    int s, rc = hg_board_init(&b, 0, kind, 0);
    if (rc)
        return rc;
    hg_board_inputs_default(&b, &in);
    in.dac_written = 1;
    for (s = 0; s < WARMUP + steps; s++) {
        double t0, t1;
        in.reset = s % 3000 == 0;
        t0 = bench_now_us();
        hg_board_step(&b, &in, &out, 1000000L);
        t1 = bench_now_us();
        if (out.fault)
            return out.fault_code;
        if (s >= WARMUP)
            ns[s - WARMUP] = t1 - t0;
    }
    bench_percentiles(ns, steps, median, p99);
    return 0;
}

/* Median, p99 and largest (us) of BENCH_CHANGES periods that each apply a new
 * geometry (l alternates by 1 mm): the check, the model rebuild, the
 * stability test at the running period, the restart at HOME and the step,
 * the worst a parameter change costs the servo thread. */
#define BENCH_CHANGES 2000
static int bench_board_change(hg_model_kind kind, double *ns, double *median, double *p99,
                              double *worst)
{
    static hg_board b;
    static hg_board_inputs in;
    static hg_board_outputs out;
    int s, rc = hg_board_init(&b, 0, kind, 0);
    double l0;
    if (rc)
        return rc;
    hg_board_inputs_default(&b, &in);
    in.dac_written = 1;
    l0 = in.params.plant.v[0];                  /* l: the Hexaglide's first parameter */
    hg_board_step(&b, &in, &out, 1000000L);     /* the running period is known */
    for (s = 0; s < BENCH_CHANGES; s++) {
        double t0, t1;
        in.params.plant.v[0] = l0 + (s % 2 == 0 ? 1e-3 : 0.0);
        t0 = bench_now_us();
        hg_board_step(&b, &in, &out, 1000000L);
        t1 = bench_now_us();
        if (out.fault)
            return out.fault_code;
        if (!(out.events & HG_EV_GEOMETRY_RESTART))
            return HG_ERR_BAD_PARAM;            /* the change was not applied */
        ns[s] = t1 - t0;
    }
    bench_percentiles(ns, BENCH_CHANGES, median, p99);
    *worst = ns[0];
    for (s = 1; s < BENCH_CHANGES; s++)
        *worst = ns[s] > *worst ? ns[s] : *worst;
    return 0;
}

/* bench_dynamics board MODEL: the board line of one model alone (what
 * run_bench.sh measures just before and after the in-HAL run, so that
 * both see the same load on the machine). */
static int board_only(const char *name)
{
    static double ns[BENCH_STEPS];
    double bm = 0.0, bp = 0.0;
    int kind = hg_model_from_name(name), rc;
    if (kind < 0) {
        fprintf(stderr, "bench_dynamics: unknown model '%s'\n", name);
        return 2;
    }
    rc = bench_board((hg_model_kind)kind, ns, &bm, &bp);
    if (rc) {
        printf("%-18s failed: %s\n", name, hg_strerror(rc));
        return 1;
    }
    printf("BENCH board_%s median_us=%.3f p99_us=%.3f iters=%d\n", name, bm, bp, steps);
    return 0;
}

int main(int argc, char **argv)
{
    static double ns[BENCH_STEPS];
    static const double paper_us[HG_MODEL_COUNT] = {144.6, 76.8, 40.6, 40.6};
    static const char *const paper_name[HG_MODEL_COUNT] = {
        "Standard", "Reduced Joints", "Reduced Cartesian", "(future work)"};
    const int flops[HG_MODEL_COUNT] = {
        HG_GEN_STANDARD_TERMS_FLOPS + HG_GEN_STANDARD_CONSTRAINTS_FLOPS,
        HG_GEN_REDUCED_TERMS_FLOPS + HG_GEN_REDUCED_CONSTRAINTS_FLOPS,
        HG_GEN_CARTESIAN_TERMS_FLOPS + HG_GEN_REDUCED_STABILIZE_FLOPS,
        HG_GEN_FUSED_STEP_FLOPS};
    double timer, med[HG_MODEL_COUNT], p99[HG_MODEL_COUNT];
    int kind, i, failed = 0;
    if (argc == 3 && strcmp(argv[1], "board") == 0)
        return board_only(argv[2]);
    if (argc == 2 && ((steps = atoi(argv[1])) < 10 || steps > BENCH_STEPS)) {
        fprintf(stderr, "usage: bench_dynamics [STEPS: 10..%d] | board MODEL\n", BENCH_STEPS);
        return 2;
    }
    {   /* the cost of the two clock reads around each step */
        double t0 = bench_now_us(), t1;
        for (i = 0; i < 1000000; i++)
            t1 = bench_now_us();
        timer = (t1 - t0) / 1e6;
    }
    printf("one hg_step at dt = 1 ms (rigid trains), %d timed steps per model after %d warm-up steps\n"
           "(each step timed alone; one clock_gettime costs %.3f us and is included)\n\n",
           steps, WARMUP, timer);
    printf("%-18s %10s %10s %14s %11s %11s\n", "model", "median us", "p99 us",
           "paper 2011 us", "paper/ours", "gen. flops");
    for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
        int rc = bench((hg_model_kind)kind, ns, &med[kind], &p99[kind]);
        if (rc) {
            printf("%-18s failed: %s\n", hg_model_name((hg_model_kind)kind), hg_strerror(rc));
            failed = 1;
            continue;
        }
        printf("%-18s %10.3f %10.3f %9.1f%-5s %11.0f %11d\n", hg_model_name((hg_model_kind)kind),
               med[kind], p99[kind], paper_us[kind], kind == 3 ? " (RC)" : "",
               paper_us[kind] / med[kind], flops[kind]);
    }
    if (!failed) {
        printf("\nratios between parametrizations (paper: Standard/RJ %.2f, RJ/RC %.2f)\n",
               144.6 / 76.8, 76.8 / 40.6);
        printf("ours: Standard/RJ %.2f, RJ/RC %.2f, RC/fused %.2f\n", med[0] / med[1], med[1] / med[2],
               med[2] / med[3]);
        printf("paper names: %s, %s, %s; fused = the paper's future work\n", paper_name[0],
               paper_name[1], paper_name[2]);
    }
    for (kind = 0; kind < HG_MODEL_COUNT && !failed; kind++)
        printf("BENCH dyn_%s median_us=%.3f p99_us=%.3f flops=%d iters=%d\n",
               hg_model_name((hg_model_kind)kind), med[kind], p99[kind], flops[kind], steps);
    printf("\none hg_board_step (the whole board: drives off, the machine sinking), %d timed periods\n",
           steps);
    for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
        double bm = 0.0, bp = 0.0;
        int rc = bench_board((hg_model_kind)kind, ns, &bm, &bp);
        if (rc) {
            printf("%-18s failed: %s\n", hg_model_name((hg_model_kind)kind), hg_strerror(rc));
            failed = 1;
            continue;
        }
        printf("%-18s %10.3f %10.3f\n", hg_model_name((hg_model_kind)kind), bm, bp);
        printf("BENCH board_%s median_us=%.3f p99_us=%.3f iters=%d\n", hg_model_name((hg_model_kind)kind),
               bm, bp, steps);
    }
    printf("\none hg_board_step that applies a new geometry (l by 1 mm, a restart at HOME), %d periods\n",
           BENCH_CHANGES);
    printf("%-18s %10s %10s %10s\n", "model", "median us", "p99 us", "max us");
    for (kind = 0; kind < HG_MODEL_COUNT; kind++) {
        double cm = 0.0, cp = 0.0, cw = 0.0;
        int rc = bench_board_change((hg_model_kind)kind, ns, &cm, &cp, &cw);
        if (rc) {
            printf("%-18s failed: %s\n", hg_model_name((hg_model_kind)kind), hg_strerror(rc));
            failed = 1;
            continue;
        }
        printf("%-18s %10.3f %10.3f %10.3f\n", hg_model_name((hg_model_kind)kind), cm, cp, cw);
        printf("BENCH change_%s median_us=%.3f p99_us=%.3f max_us=%.3f iters=%d\n",
               hg_model_name((hg_model_kind)kind), cm, cp, cw, BENCH_CHANGES);
    }
    return failed;
}
