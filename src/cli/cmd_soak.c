/* cmd_soak.c - the soak subcommand: hours of simulated time, offline and
 * faster than real time, of the machine following a random smooth
 * trajectory through the closed loop LinuxCNC runs (src/hg_loop.h: motion's
 * joint commands from the inverse kinematics, LinuxCNC's pid on the encoder
 * position with the config's gains and scales, the virtual board's DACs,
 * amplifiers, dynamics and encoders). Reports, each measured apart from
 * what the step says of itself:
 *   constraint drift  bar lengths |B_k - A_k| from the carriage heights and
 *                     the head pose by the kinematics' closed form
 *                     (hg_joint_points), against l;
 *   energy balance    change of kinetic + potential energy (hg_energy)
 *                     against the work of the carriage forces (drives,
 *                     friction, stops: each step's start-state force, which
 *                     improved Euler holds over the step, times the step's
 *                     displacement), in joules and relative to the net
 *                     change; improved Euler's mismatch halves with dt;
 *   following error   motion's f-error through the encoder (mm and counts),
 *                     and LinuxCNC's following-error trip of the config
 *                     (control.c: limit = max(FERROR |v| / MAX_VELOCITY, MIN_FERROR));
 *   faults and the wall time.
 * A long run says how far it is on stderr (progress_every); stdout holds the report alone. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "cli.h"
#include "hg_plant_hexaglide.h"
#include "hg_dynamics.h"
#include "hg_errors.h"
#include "hg_forces.h"
#include "hg_kinematics.h"
#include "hg_units.h"

#define SOAK_HARMONICS 3
#define SOAK_RAMP_S 2.0        /* the trajectory ramps in over this */
#define SOAK_SETTLED_S 2.5     /* following error counted from here on */
/* the longest soak: the 1000 h --hours takes at the default 1 ms period (about 9 h of wall time
 * at 9 us a period); a shorter --dt allows fewer hours, instead of a run that never ends */
#define SOAK_MAX_PERIODS 3600000000L
#define SOAK_MAX_HOURS 1000.0
/* progress lines on stderr, counted in periods (not wall time: the same lines on every machine): a run
 * of SOAK_PROGRESS_MIN periods or more prints one at each tenth of it, and at least every
 * SOAK_PROGRESS_MAX periods */
#define SOAK_PROGRESS_MIN 1000000L     /* about 9 s of wall at 9 us a period: shorter runs print none */
#define SOAK_PROGRESS_MAX 36000000L    /* 10 h at 1 ms, about 5 min of wall: 1000 h prints one each 1 % */

const char cli_usage_soak[] =
    "usage: hexaglide soak [--hours H] [--model NAME] [--seed N] [--dt S] [--integrator NAME]\n"
    "                      [--ini FILE] [--set name=value]...\n"
    "  H hours (default 8, at most 1000) of a random smooth trajectory through LinuxCNC's closed loop\n"
    "  (src/hg_loop.c: pid on the encoder position, the virtual board), then a health report:\n"
    "  constraint drift, energy balance, following error, faults, wall time. Exit 1 on a fault\n"
    "  or a following-error trip. A run of 1e6 periods or more prints its progress on stderr at\n"
    "  each tenth (at least every 3.6e7 periods); stdout holds the report alone.\n"
    "  --ini FILE  the config: [JOINT_0..5] P I D FF0 FF1 FF2 FF3 BIAS DEADBAND MAX_OUTPUT\n"
    "              MAX_ERROR_I INPUT_SCALE OUTPUT_SCALE OUTPUT_OFFSET (as configs/hexaglide.hal\n"
    "              wires them, each required as halcmd requires a setp's key; FF3 may be absent:\n"
    "              0; tune reads them alike), FERROR MIN_FERROR MAX_VELOCITY (the trip),\n"
    "              [EMCMOT]SERVO_PERIOD, [HEXAGLIDE] geometry (each key required), checked as\n"
    "              'hexaglide config --loop' checks them. Default: configs/hexaglide.ini\n"
    "              of the source tree this hexaglide was built in (../configs/ beside build/)\n"
    "  --dt S      servo period, whole ns (default the config's SERVO_PERIOD); H is a whole number\n"
    "              of periods, at most 3.6e9 of them (1000 h at 1 ms)\n"
    "  --seed N    the trajectory's random seed, a whole number from 0 to 2^53 in digits (default 1)\n"
    "  --model     standard|reduced-joints|reduced-cartesian|fused-cartesian (default reduced-cartesian)\n"
    "  --integrator improved-euler|heun|rk4 (default: the board's, as HAL loads it)\n"
    "  --set name=value  a model parameter (spec name, SI units), after the config\n";

/* A smooth random pose trajectory: per coordinate a sum of sines. */
typedef struct {
    double amp[6][SOAK_HARMONICS];     /* m or rad */
    double omega[6][SOAK_HARMONICS];   /* rad/s */
    double phase[6][SOAK_HARMONICS];   /* rad */
} soak_trajectory;

/* The config's following-error rule, per joint (mm, mm/s). */
typedef cli_ferror_rule soak_ferror_rule;

/* xorshift64* uniform in [lo, hi). */
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
    double ramp = t >= SOAK_RAMP_S ? 1.0 : 0.5 - 0.5 * cos(HG_PI * t / SOAK_RAMP_S);
    int c, h;
    for (c = 0; c < 6; c++) {
        pose[c] = 0;
        for (h = 0; h < SOAK_HARMONICS; h++)
            pose[c] += tr->amp[c][h] * (sin(tr->omega[c][h] * t + tr->phase[c][h]) - sin(tr->phase[c][h]));
        pose[c] *= ramp;
    }
}

/* Largest | |B_k - A_k| - l | over the bars (m): the bar lengths of the
 * carriage heights z and the head pose, by the kinematics' closed form. */
static double bar_length_error(const hg_geometry *g, const double z[6], const double pose[6])
{
    double B[6][3], A[6][3], worst = 0;
    int k;
    hg_joint_points(g, z, pose, B, A);
    for (k = 0; k < 6; k++) {
        double dx = B[k][0] - A[k][0], dy = B[k][1] - A[k][1], dz = B[k][2] - A[k][2];
        double e = fabs(sqrt(dx * dx + dy * dy + dz * dz) - g->l_m);
        if (!(e <= worst))             /* NaN is the worst */
            worst = e;
    }
    return worst;
}

/* Periods between progress lines in a run of n: a tenth of it (rounded up), at most
 * SOAK_PROGRESS_MAX; 0 (none) for a run shorter than SOAK_PROGRESS_MIN. */
static long progress_every(long n)
{
    long tenth = (n + 9) / 10;
    if (n < SOAK_PROGRESS_MIN)
        return 0;
    return tenth < SOAK_PROGRESS_MAX ? tenth : SOAK_PROGRESS_MAX;
}

/* Monotonic wall time in seconds (the summary's wall time and real-time factor). */
static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* The loop's settings from the config: gains, scales, trip rule, period
 * (period_ns > 0: --dt's, which replaces [EMCMOT]SERVO_PERIOD), checked as
 * `hexaglide config --loop` checks them (cli_ini_servo_loops). 0 or 2 after messages. */
static int read_config(const char *ini_path, long period_ns, int kind, hg_loop_config *c, soak_ferror_rule *r)
{
    cli_ini ini;
    int bad;
    if (cli_ini_read("soak", ini_path, &ini))
        return 2;
    if (cli_ini_plant_only("soak", &ini, 0)) {   /* its [JOINT_N] are another machine's */
        cli_ini_free(&ini);
        return 2;
    }
    hg_loop_config_default(c);
    c->variant = kind;
    bad = cli_ini_servo_loops("soak", &ini, period_ns, "--dt", c, r) != 0;
    cli_ini_free(&ini);
    if (bad) {
        fprintf(stderr, "hexaglide soak: fix %s (or give another with --ini)\n", ini_path);
        return 2;
    }
    return 0;
}

/* --seed's text as a seed: decimal digits (a '+' before them, as tune's and excite's --seed take
 * it), 0 to SOAK_SEED_MAX; nothing rounded (a double would read 2^53 + 1 as 2^53). 0, or -1
 * after a message naming the value and the bound. */
#define SOAK_SEED_MAX 9007199254740992ull   /* 2^53 */
static int parse_seed(const char *text, unsigned long long *seed)
{
    const char *p = text + (text[0] == '+');
    unsigned long long v = 0;
    double d;
    int digits = 0;
    if (cli_parse_double("soak", text, "--seed", &d))
        return -1;                     /* not a number: named as every option's */
    for (; *p >= '0' && *p <= '9' && v <= SOAK_SEED_MAX; p++, digits++)   /* (stops before it could overflow) */
        v = v * 10 + (unsigned long long)(*p - '0');
    if (!digits || *p || v > SOAK_SEED_MAX) {   /* a '-', a '.', an exponent, too many digits */
        fprintf(stderr, "hexaglide soak: --seed %s: must be a whole number from 0 to 2^53 (%llu), in digits\n", text,
                SOAK_SEED_MAX);
        return -1;
    }
    *seed = v;
    return 0;
}

enum { OPT_HOURS, OPT_DT, OPT_SEED, OPT_MODEL, OPT_INI, OPT_SET, OPT_INTEGRATOR };
static const cli_opt soak_opts[] = {
    {"--hours", 1}, {"--dt", 1}, {"--seed", 1}, {"--model", 1}, {"--ini", 1}, {"--set", CLI_REPEAT},
    {"--integrator", 1}, {0, 0},
};

int cmd_soak(int argc, char **argv)
{
    hg_loop_config cfg;
    hg_board_params bp;
    hg_loop *L;
    hg_loop_sample smp;
    soak_trajectory tr;
    soak_ferror_rule rule[HG_LOOP_JOINTS];
    cli_args a;
    char default_ini[4096], *sets[argc > 0 ? argc : 1];
    const char *ini = 0, *v;
    double hours = 8.0, dt = 0, t0, wall, e0k, e0p, ek, ep, net, mismatch;
    double work_j = 0, friction_j = 0, drift = 0, ferr_max = 0, ferr_counts = 0, cmd_prev[6] = {0}, cmd_prev2[6] = {0};
    double tool_max = 0;               /* the tool-path error after the ramp-in (mm; -1: a period without a pose) */
    int kind = HG_MODEL_REDUCED_CARTESIAN, k, o, nset = 0, rc = 0, faults = 0, trips = 0, ferr_joint = 0;
    int integrator = -1;
    long measured = 0;                 /* periods after the ramp-in: their errors measured */
    char ferr_text[96], tool_text[32];
    long n, s, every, period_ns = 0;   /* period_ns: --dt's, 0 without it */
    unsigned long long seed = 1;
    const hg_model *hm;
    const hg_data *hd;
    cli_args_init(&a, "soak", cli_usage_soak, soak_opts, argc, argv);
    while ((o = cli_next(&a, &v)) != CLI_DONE) {
        if (o == CLI_HELP)
            return 0;
        if (o == CLI_BAD)
            return 2;
        if (o == CLI_ARG) {
            fprintf(stderr, "hexaglide soak: unexpected argument '%s' ('hexaglide soak --help' lists the "
                    "options)\n", v);
            return 2;
        }
        if ((o == OPT_HOURS && cli_parse_double("soak", v, "--hours", &hours)) ||
            (o == OPT_DT && (cli_parse_double("soak", v, "--dt", &dt) || cli_parse_period("soak", dt, &period_ns))) ||
            (o == OPT_SEED && parse_seed(v, &seed)))
            return 2;
        if (o == OPT_MODEL && (kind = hg_model_from_name(v)) < 0) {
            fprintf(stderr, "hexaglide soak: unknown model '%s' (standard, reduced-joints, reduced-cartesian, "
                    "fused-cartesian)\n", v);
            return 2;
        }
        if (o == OPT_INTEGRATOR && (integrator = hg_integrator_from_name(v)) < 0) {
            fprintf(stderr, "hexaglide soak: unknown integrator '%s' (improved-euler, heun, rk4)\n", v);
            return 2;
        }
        if (o == OPT_INI)
            ini = v;
        if (o == OPT_SET)
            sets[nset++] = (char *)v;
    }
    if (!(hours > 0 && hours <= SOAK_MAX_HOURS)) {
        char num[CLI_NUM_LEN];
        fprintf(stderr, "hexaglide soak: --hours %s: must be in (0, %g] (simulated hours)\n", cli_num(hours, num),
                SOAK_MAX_HOURS);
        return 2;
    }
    if (!ini) {
        if (cli_tree_path("configs/hexaglide.ini", default_ini, sizeof default_ini) ||
            access(default_ini, R_OK) != 0) {
            fprintf(stderr, "hexaglide soak: no config beside this program (../configs/hexaglide.ini): give "
                    "--ini FILE, a LinuxCNC INI with [JOINT_0..5] gains\n");
            return 2;
        }
        ini = default_ini;
    }
    if (read_config(ini, period_ns, kind, &cfg, rule) ||
        cli_whole_periods("soak", "--hours", hours, 3600.0, "h", cfg.period_ns, 1, SOAK_MAX_PERIODS, &n))
        return 2;
    dt = (double)cfg.period_ns * 1e-9;
    L = malloc(sizeof *L);
    if (!L) {
        fprintf(stderr, "hexaglide soak: out of memory\n");
        return 1;
    }
    /* the board's load-time block (substeps, integrator), the model's parameters from the config */
    cli_board_defaults(0, kind, &bp);
    if (cli_params_build("soak", 0, kind, ini, sets, nset, &bp.plant) ||
        cli_params_check_from("soak", 0, kind, &bp.plant, ini, sets, nset)) {
        free(L);
        return 2;
    }
    if (integrator >= 0)
        bp.integrator = (unsigned)integrator;
    if (cli_board_integrable("soak", 0, kind, &bp, cfg.period_ns, sets, nset)) {
        free(L);
        return 2;
    }
    rc = hg_loop_init(L, &cfg, &bp);
    if (rc) {
        fprintf(stderr, "hexaglide soak: cannot build the loop: %s (code %d)\n", hg_strerror(rc), rc);
        free(L);
        return 2;
    }
    cli_enc_scale_notes("soak", &L->board, cfg.input_scale, L->joints, "[JOINT_%d]INPUT_SCALE");
    trajectory_init(&tr, seed * 7919 + 1);
    hm = hg_hexaglide_model(&L->board.m);
    hd = hg_hexaglide_data(&L->board.d);
    hg_energy(hm, hd, &e0k, &e0p);
    every = progress_every(n);
    t0 = now_s();
    rc = 0;
    for (s = 0; s < n; s++) {
        double t = (s + 1) * dt, pose[6], cmd[6], z0[6], zr0[6], f_passive[6], f_damper[6];
        static const double no_drive[6] = {0, 0, 0, 0, 0, 0};
        trajectory_pose(&tr, t, pose);
        if (hg_inverse_kinematics(&hm->p.geo, pose, cmd)) {
            fprintf(stderr, "hexaglide soak: trajectory left the working volume at t = %.3f s\n", t);
            rc = 1;
            break;
        }
        for (k = 0; k < 6; k++) {
            cmd[k] *= HG_MM_PER_M;
            z0[k] = L->out.pos[k];
            zr0[k] = hm->flexible ? hd->zr_m[k] : z0[k];   /* where the drives push: the rotors */
            /* a flexible train's damper: c dd while the flanks touch (its force less the spring's) */
            f_damper[k] = hm->flexible ? hg_drivetrain_force(&hm->train[k], hd->zr_m[k] - hd->z_m[k],
                                                             hd->zrd_mps[k] - hd->zd_mps[k]) -
                                         hg_drivetrain_force(&hm->train[k], hd->zr_m[k] - hd->z_m[k], 0)
                                       : 0;
        }
        /* viscous friction and stops alone: the smooth carriage forces without the drives */
        hg_carriage_forces(hm, hd->z_m, hd->zd_mps, no_drive, f_passive);
        if (hg_loop_step(L, cmd, &smp)) {
            char what[HG_PLANT_TEXT_LEN + 2 * HG_BOARD_TEXT_LEN];
            faults++;
            cli_fault_text(&L->board, &L->out, cfg.period_ns, what);
            fprintf(stderr, "hexaglide soak: step failed at t = %.3f s: %s\n", t, what);
            break;
        }
        for (k = 0; k < 6; k++) {
            /* motion compares with the previous period's command and velocity */
            double fe = fabs(smp.ferror_mm[k]), vel = fabs(cmd_prev[k] - cmd_prev2[k]) / dt;
            double limit = rule[k].ferror * vel / rule[k].max_velocity;
            if (limit < rule[k].min_ferror)
                limit = rule[k].min_ferror;
            if (fe > limit && !trips++)
                fprintf(stderr, "hexaglide soak: at t = %.3f s joint %d's following error %.4f mm exceeds "
                        "LinuxCNC's limit %.4f mm (FERROR %g, MIN_FERROR %g at %.1f mm/s): LinuxCNC would "
                        "stop here\n", t, k, fe, limit, rule[k].ferror, rule[k].min_ferror, vel);
            if (fe > ferr_max && t > SOAK_SETTLED_S) {
                ferr_max = fe;
                ferr_joint = k;
                ferr_counts = fe * fabs(cfg.input_scale[k]);
            }
            cmd_prev2[k] = cmd_prev[k];
            cmd_prev[k] = cmd[k];
            /* the step held the force of its start state: its work; behind a flexible train the
             * motor's on the rotor (the period's one step: substeps_run 1), the carriage's without
             * the train's (internal but for the damper, below) */
            if (hm->flexible)
                work_j += hd->work.motor_n[k] * (hd->zr_m[k] - zr0[k]) +
                          (f_passive[k] + hd->fric_n[k]) * (L->out.pos[k] - z0[k]);
            else
                work_j += L->out.force[k] * (L->out.pos[k] - z0[k]);
            /* + sliding and static friction, resolved over the step, and the train's damper */
            friction_j += (f_passive[k] + hd->fric_n[k]) * (L->out.pos[k] - z0[k]);
            if (hm->flexible) {
                double w = f_damper[k] * ((hd->zr_m[k] - hd->z_m[k]) - (zr0[k] - z0[k]));
                work_j -= w;
                friction_j -= w;
            }
        }
        measured += t > SOAK_SETTLED_S;   /* (a period whose errors count: above and here) */
        if (t > SOAK_SETTLED_S && tool_max >= 0 && (smp.tool_error_mm < 0 || smp.tool_error_mm > tool_max))
            tool_max = smp.tool_error_mm;
        {
            double e = bar_length_error(&hm->p.geo, L->out.pos, L->out.extra);   /* extra[0..5]: the head pose */
            if (!(e <= drift))
                drift = e;
        }
        if (trips)
            break;
        if (every && (s + 1) % every == 0 && s + 1 < n)
            fprintf(stderr, "hexaglide soak: %.0f %% (%.2f of %.2f h simulated, %ld of %ld periods)\n",
                    100.0 * (s + 1) / n, t / 3600.0, n * dt / 3600.0, s + 1, n);
    }
    wall = now_s() - t0;
    hg_energy(hm, hd, &ek, &ep);
    net = (ek + ep) - (e0k + e0p);
    mismatch = net - work_j;
    printf("soak: %s, config %s, %.2f h simulated (%ld periods of %.3g s) in %.1f s wall (%.0fx real time, "
           "%.3f us/period)\n", hg_model_name((hg_model_kind)kind), ini, s * dt / 3600.0, s, dt, wall,
           s * dt / (wall > 0 ? wall : 1), 1e6 * wall / (s > 0 ? s : 1));
    printf("soak: constraint drift (largest | |B-A| - l | of the closed-form bar lengths): %.3e m\n", drift);
    printf("soak: energy balance (%s): net change %.6g J; work of the drives %.6g J, of friction and stops "
           "%.6g J; mismatch %.3e J = %.3e of the net change\n",
           hg_integrator_name(hm->integrator), net, work_j - friction_j, friction_j,
           mismatch, fabs(mismatch) / (net != 0 ? fabs(net) : 1));
    if (hm->flexible && L->out.substeps_run > 1)
        printf("soak: (the flexible trains ran %u steps a period and the balance holds the forces of a "
               "period's last: a --dt of one step a period gives the balance its meaning)\n",
               L->out.substeps_run);
    if (measured)
        printf("soak: max following error after the %.1f s ramp-in: %.4f mm = %.2f counts (joint %d, through the "
               "encoder)\n", SOAK_SETTLED_S, ferr_max, ferr_counts, ferr_joint);
    else
        printf("soak: max following error after the %.1f s ramp-in: none measured (the run ended at %.3f s, "
               "before it)\n", SOAK_SETTLED_S, s * dt);
    if (!measured)
        printf("soak: max tool-path error after the ramp-in: none measured (the run ended at %.3f s, before it)\n",
               s * dt);
    else if (tool_max >= 0)
        printf("soak: max tool-path error after the ramp-in: %.4f mm (the tool tip against where the commanded "
               "joints put it)\n", tool_max);
    else
        printf("soak: tool-path error: some period's commands had no pose near the machine's\n");
    printf("soak: faults: %d, following-error trips: %d\n", faults, trips);
    /* the machine line: a value that was not measured is a word, never a number that reads as one */
    if (measured)
        snprintf(ferr_text, sizeof ferr_text, "ferr_mm=%.6f ferr_counts=%.3f", ferr_max, ferr_counts);
    else
        snprintf(ferr_text, sizeof ferr_text, "ferr_mm=none ferr_counts=none");
    if (measured && tool_max >= 0)
        snprintf(tool_text, sizeof tool_text, "%.6f", tool_max);
    else
        snprintf(tool_text, sizeof tool_text, "%s", measured ? "nopose" : "none");
    printf("SOAK drift_m=%.3e energy_net_j=%.6g energy_mismatch_j=%.3e energy_rel=%.3e friction_j=%.6g "
           "faults=%d trips=%d %s tool_mm=%s wall_s=%.1f steps=%ld\n", drift, net, mismatch,
           fabs(mismatch) / (net != 0 ? fabs(net) : 1), friction_j, faults, trips, ferr_text, tool_text, wall, s);
    free(L);
    return (rc || faults || trips) ? 1 : 0;
}
