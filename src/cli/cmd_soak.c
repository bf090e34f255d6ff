/* cmd_soak.c - the soak subcommand: hours of simulated time, offline and
 * faster than real time, of the machine following a random smooth
 * trajectory through six PID loops into the virtual board (hg_board.h, the
 * code LinuxCNC runs: DACs, amplifiers, encoders). Reports constraint
 * drift, energy balance, faults, following error and the wall time it took.
 *   hexaglide soak [--hours H] [--model NAME] [--seed N] [--dt S] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "cli.h"
#include "hg_dynamics.h"
#include "hg_errors.h"
#include "hg_pid.h"
#include "hg_units.h"

#define SOAK_HARMONICS 3

/* A smooth random pose trajectory: per coordinate a sum of sines. */
typedef struct {
    double amp[6][SOAK_HARMONICS];     /* m or rad */
    double omega[6][SOAK_HARMONICS];   /* rad/s */
    double phase[6][SOAK_HARMONICS];   /* rad */
} soak_trajectory;

static double uniform(unsigned long long *s, double lo, double hi)
{
    *s ^= *s >> 12; *s ^= *s << 25; *s ^= *s >> 27;
    return lo + (hi - lo) * (double)((*s * 2685821657736338717ull) >> 11) / 9007199254740992.0;
}

/* Random amplitudes within the working volume (X,Y 40 mm, Z 80 mm, angles 8 deg
 * summed over the harmonics), frequencies 0.03-0.4 Hz. */
static void trajectory_init(soak_trajectory *tr, unsigned long long seed)
{
    static const double reach[6] = {0.040, 0.040, 0.080, 8.0 / HG_DEG_PER_RAD,
                                    8.0 / HG_DEG_PER_RAD, 8.0 / HG_DEG_PER_RAD};
    int c, h;
    for (c = 0; c < 6; c++)
        for (h = 0; h < SOAK_HARMONICS; h++) {
            tr->amp[c][h] = uniform(&seed, 0.2, 1.0) * reach[c] / SOAK_HARMONICS;
            tr->omega[c][h] = 2 * HG_PI * uniform(&seed, 0.03, 0.4);
            tr->phase[c][h] = uniform(&seed, 0, 2 * HG_PI);
        }
}

/* Pose at time t, ramped in over the first 2 s so it starts at HOME at rest. */
static void trajectory_pose(const soak_trajectory *tr, double t, double pose[6])
{
    double ramp = t >= 2.0 ? 1.0 : 0.5 - 0.5 * cos(HG_PI * t / 2.0);
    int c, h;
    for (c = 0; c < 6; c++) {
        pose[c] = 0;
        for (h = 0; h < SOAK_HARMONICS; h++)
            pose[c] += tr->amp[c][h] * (sin(tr->omega[c][h] * t + tr->phase[c][h]) - sin(tr->phase[c][h]));
        pose[c] *= ramp;
    }
}

/* PID gains for this machine (LinuxCNC pid units: mm in, volts out):
 * about 20 Hz position bandwidth on ~60 kg per axis. */
static void soak_gains(const hg_model *m, hg_pid_gains *g)
{
    double mass = m->rotor_mass_kg + m->p.m_carriage_kg + m->p.m_bar_kg + m->p.m_head_kg / 6;
    double w = 2 * HG_PI * 20.0, fpv = m->force_per_volt_n;
    hg_pid_defaults(g);
    g->pgain = mass * w * w / fpv / HG_MM_PER_M;
    g->dgain = (2 * 0.7 * mass * w - m->p.c_visc_ns_per_m) / fpv / HG_MM_PER_M;
    if (g->dgain < 0)
        g->dgain = 0;
    g->igain = g->pgain * w / 8;
    g->ff1 = m->p.c_visc_ns_per_m / fpv / HG_MM_PER_M;
    g->maxoutput = 10.0;
    g->maxerror_i = 10.0 / (g->igain > 0 ? g->igain : 1);
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

int cmd_soak(int argc, char **argv)
{
    hg_board_params bp;
    hg_board *b;
    hg_board_inputs in;
    hg_board_outputs out;
    hg_pid_gains gains;
    hg_pid_state pid[6];
    soak_trajectory tr;
    double hours = 8.0, dt = 0.001, seed_d = 1, t0, wall, e0k, e0p, ek, ep;
    double work_j = 0, work_abs_j = 0, drift = 0, ferr_max = 0, z_prev[6], cmd_prev[6];
    int kind = HG_MODEL_REDUCED_CARTESIAN, i, k, rc = 0, faults = 0;
    long n, s, period_ns;
    for (i = 0; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--hours") == 0) {
            if (cli_parse_double(argv[i + 1], "--hours", &hours))
                return 2;
        } else if (strcmp(argv[i], "--dt") == 0) {
            if (cli_parse_double(argv[i + 1], "--dt", &dt))
                return 2;
        } else if (strcmp(argv[i], "--seed") == 0) {
            if (cli_parse_double(argv[i + 1], "--seed", &seed_d))
                return 2;
        } else if (strcmp(argv[i], "--model") == 0) {
            kind = hg_model_from_name(argv[i + 1]);
            if (kind < 0) {
                fprintf(stderr, "hexaglide soak: unknown model '%s'\n", argv[i + 1]);
                return 2;
            }
        } else {
            break;
        }
    }
    if (i != argc) {
        fprintf(stderr, "usage: hexaglide soak [--hours H] [--model NAME] [--seed N] [--dt S]\n");
        return 2;
    }
    if (!(hours > 0 && hours <= 1000) || !(dt > 0 && dt <= HG_DT_MAX_S)) {
        fprintf(stderr, "hexaglide soak: need 0 < --hours <= 1000 and 0 < --dt <= %g s\n", HG_DT_MAX_S);
        return 2;
    }
    if (cli_parse_period("soak", dt, &period_ns))
        return 2;
    dt = (double)period_ns * 1e-9;
    hg_params_default(&bp.model);
    bp.substeps = 1;
    bp.integrator = HG_INTEGRATOR_IMPROVED_EULER;
    b = cli_board_new("soak", kind, &bp);
    if (!b)
        return 1;
    hg_board_inputs_default(b, &in);
    in.dout_values = 1u << in.estop_loop_out;   /* E-STOP loop closed: amplifiers on */
    hg_board_peek(b, &out);
    soak_gains(&b->m, &gains);
    for (k = 0; k < 6; k++) {
        hg_pid_reset(&pid[k]);
        z_prev[k] = cmd_prev[k] = 0;
    }
    trajectory_init(&tr, (unsigned long long)fabs(seed_d) * 7919 + 1);
    hg_energy(&b->m, &b->d, &e0k, &e0p);
    n = (long)(hours * 3600.0 / dt + 0.5);
    t0 = now_s();
    for (s = 0; s < n; s++) {
        double t = (s + 1) * dt, pose[6], cmd[6];
        trajectory_pose(&tr, t, pose);
        if (hg_inverse_kinematics(&b->m.p.geo, pose, cmd)) {
            fprintf(stderr, "hexaglide soak: trajectory left the working volume at t = %.3f s\n", t);
            rc = 1;
            break;
        }
        for (k = 0; k < 6; k++) {
            double fe = fabs(cmd_prev[k] - out.z_m[k]);
            if (fe > ferr_max && t > 2.5)
                ferr_max = fe;
            in.dac_v[k] = hg_pid_calc(&gains, &pid[k], cmd[k] * HG_MM_PER_M, out.z_m[k] * HG_MM_PER_M, 1, 0,
                                      period_ns);
            cmd_prev[k] = cmd[k];
            z_prev[k] = out.z_m[k];
        }
        in.dac_written = 1;
        hg_board_step(b, &in, &out, period_ns);
        if (out.fault) {
            faults++;
            fprintf(stderr, "hexaglide soak: step failed at t = %.3f s: %s\n", t, hg_strerror(out.fault_code));
            break;
        }
        for (k = 0; k < 6; k++) {
            double dw = out.force_n[k] * (out.z_m[k] - z_prev[k]);
            work_j += dw;
            work_abs_j += fabs(dw);
        }
        if (out.residual_m > drift)
            drift = out.residual_m;
    }
    wall = now_s() - t0;
    hg_energy(&b->m, &b->d, &ek, &ep);
    printf("soak: %s, %.2f h simulated (%ld steps of %.3g s) in %.1f s wall (%.0fx real time, %.3f us/step)\n",
           hg_model_name((hg_model_kind)kind), s * dt / 3600.0, s, dt, wall, s * dt / (wall > 0 ? wall : 1),
           1e6 * wall / (s > 0 ? s : 1));
    printf("soak: constraint drift (max bar-length error after stabilization): %.3e m\n", drift);
    printf("soak: energy balance: change %.6g J, work of drives+friction+stops %.6g J, "
           "mismatch %.3e J = %.3e of the work moved (sum |dW| = %.6g J)\n",
           (ek + ep) - (e0k + e0p), work_j, (ek + ep) - (e0k + e0p) - work_j,
           fabs((ek + ep) - (e0k + e0p) - work_j) / (work_abs_j > 0 ? work_abs_j : 1), work_abs_j);
    printf("soak: max following error after the 2 s ramp-in: %.4f mm\n", ferr_max * HG_MM_PER_M);
    printf("soak: faults: %d\n", faults);
    printf("SOAK drift_m=%.3e energy_rel=%.3e faults=%d ferr_mm=%.4f wall_s=%.1f steps=%ld\n", drift,
           fabs((ek + ep) - (e0k + e0p) - work_j) / (work_abs_j > 0 ? work_abs_j : 1), faults,
           ferr_max * HG_MM_PER_M, wall, s);
    free(b);
    return (rc || faults) ? 1 : 0;
}
