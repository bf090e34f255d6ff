/* profile_step.c - the workloads bench/profile_step.sh runs under
 * callgrind, with the default model (reduced-cartesian, Heun, sliding and
 * static friction, bus-limited windings, the guard) and rigid drive trains
 * (k_axial 0: the machine of commit d20d9e5, which --baseline profiles,
 * and one step per period) under bench_dynamics'
 * servo motion (a P controller on 20 mm, 0.5 Hz sines, phases 60 degrees
 * apart) at 1 ms: `step`, hg_step alone as bench_dynamics times it;
 * `board`, the virtual board (hg_board_step, the code LinuxCNC runs every
 * servo period: the DAC's 13 bits, the step, encoders, switches, ADC) with
 * the amplifiers on and the references as motion's joint commands (the
 * tool-path error's). WARMUP periods, then PERIODS profiled ones, each
 * through profiled_step or profiled_board (callgrind
 * --toggle-collect=profiled_* counts only those). Prints the periods and
 * how many of them ended with a carriage stuck.
 * Usage: profile_step step|board [PERIODS] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hg_board.h"
#include "hg_dynamics.h"
#if __has_include("hg_plant_hexaglide.h")  /* today's tree: the board runs a plant */
#include "hg_plant_hexaglide.h"
#define PLANT_INTERFACE 1
#else                                       /* d20d9e5's (--baseline): the board is the Hexaglide */
#define PLANT_INTERFACE 0
#endif

#define WARMUP 2000
#define PI 3.14159265358979323846

/* DAC volts of the servo motion at time t for carriage heights z, and its
 * references (m) into ref unless 0. */
static void servo(const hg_model *m, double t, const double z[6], double v[6], double *ref)
{
    const hg_params *p = &m->p;
    double hold = p->g_mps2 * (p->m_head_kg + 6 * (p->m_bar_kg + p->m_carriage_kg)) / 6 /
                  m->force_per_volt_n;
    int k;
    for (k = 0; k < 6; k++) {
        double r = 0.02 * sin(2 * PI * 0.5 * t + k * PI / 3);
        v[k] = fmax(-10.0, fmin(10.0, hold + 300.0 * (r - z[k])));
        if (ref)
            ref[k] = r;
    }
}

/* hg_step and hg_board_step of the profiled periods (never inlined: the
 * profile counts only what runs inside them). */
__attribute__((noinline)) int profiled_step(const hg_model *m, hg_data *d, const double v[6])
{
    return hg_step(m, d, v, 1e-3);
}

__attribute__((noinline)) void profiled_board(hg_board *b, const hg_board_inputs *in,
                                              hg_board_outputs *out)
{
    hg_board_step(b, in, out, 1000000L);
}

/* PERIODS hg_steps after WARMUP: 0, or 1 when a step fails. */
static int run_step(long n)
{
    static hg_model m;
    static hg_data d;
    hg_params p;
    long s, stuck = 0;
    hg_params_default(&p);
#if PLANT_INTERFACE
    p.k_axial_n_per_m = 0.0;
#endif
    if (hg_model_init(&m, &p, HG_MODEL_REDUCED_CARTESIAN, 0, 0) || hg_data_reset(&m, &d))
        return 1;
    for (s = 0; s < WARMUP + n; s++) {
        double v[6];
        int rc;
        servo(&m, d.t_s, d.z_m, v, 0);
        if ((rc = s < WARMUP ? hg_step(&m, &d, v, 1e-3) : profiled_step(&m, &d, v)) != 0) {
            fprintf(stderr, "profile_step: hg_step failed (code %d) at step %ld\n", rc, s);
            return 1;
        }
        stuck += s >= WARMUP && d.stuck != 0;
    }
    printf("profile_step step: %ld profiled steps after %d warm-up, %ld with a stuck carriage, "
           "z0 %.6f m\n", n, WARMUP, stuck, d.z_m[0]);
    return 0;
}

/* PERIODS board periods after WARMUP: 0, or 1 when the board faults. */
static int run_board(long n)
{
    static hg_board b;
    static hg_board_inputs in;
    static hg_board_outputs out;
    const hg_model *m;
    const hg_data *d;
    long s, stuck = 0;
#if PLANT_INTERFACE
    hg_board_params bp;
    hg_board_params_default(0, HG_MODEL_REDUCED_CARTESIAN, &bp);
    bp.plant.v[hg_plant_param_find(hg_plant_at(0), HG_MODEL_REDUCED_CARTESIAN, "k_axial")] = 0.0;
    if (hg_board_init(&b, 0, HG_MODEL_REDUCED_CARTESIAN, &bp) != 0)
        return 1;
    m = hg_hexaglide_model(&b.m);
    d = hg_hexaglide_data(&b.d);
#else
    if (hg_board_init(&b, HG_MODEL_REDUCED_CARTESIAN, 0) != 0)
        return 1;
    m = &b.m;
    d = &b.d;
#endif
    hg_board_inputs_default(&b, &in);
    in.dout_values = 1u << 7;          /* the E-STOP loop (out-07) closed: amplifiers on */
    for (s = 0; s < WARMUP + n; s++) {
        int k;
#if PLANT_INTERFACE
        servo(m, d->t_s, d->z_m, in.dac_v, in.pos_cmd);   /* motion's commands: the tool-path error's */
#else
        servo(m, d->t_s, d->z_m, in.dac_v, 0);
#endif
        for (k = 6; k < HG_BOARD_DACS; k++)
            in.dac_v[k] = 0.0;
        in.dac_written = 1;
        if (s < WARMUP)
            hg_board_step(&b, &in, &out, 1000000L);
        else
            profiled_board(&b, &in, &out);
        if (out.fault) {
            fprintf(stderr, "profile_step: the board faulted (code %d) at period %ld\n", out.fault_code, s);
            return 1;
        }
        stuck += s >= WARMUP && d->stuck != 0;
    }
    printf("profile_step board: %ld profiled periods after %d warm-up, %ld with a stuck carriage, "
           "z0 %.6f m\n", n, WARMUP, stuck, d->z_m[0]);
    return 0;
}

int main(int argc, char **argv)
{
    long n = argc > 2 ? atol(argv[2]) : 10000;
    if (argc < 2 || n < 1 || (strcmp(argv[1], "step") && strcmp(argv[1], "board"))) {
        fprintf(stderr, "usage: profile_step step|board [PERIODS]\n");
        return 2;
    }
    return strcmp(argv[1], "step") == 0 ? run_step(n) : run_board(n);
}
