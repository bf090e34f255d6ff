/* cmd_sim.c - the sim subcommand: offline simulation of the virtual board
 * (hg_board.h, the code LinuxCNC runs) with constant DAC volts and the
 * amplifiers enabled, one CSV row per servo period (mm, mm/s, degrees). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "hg_dynamics.h"
#include "hg_errors.h"
#include "hg_units.h"

#define SIM_MAX_STEPS 100000000L   /* refuse runs longer than this many steps */

static void sim_usage(void)
{
    fprintf(stderr,
            "usage: hexaglide sim [--model standard|reduced-joints|reduced-cartesian|fused-cartesian]\n"
            "                     [--time S] [--dt S] [--volts V0,V1,V2,V3,V4,V5]\n"
            "                     [--substeps N] [--integrator improved-euler|heun|rk4]\n"
            "                     [--set name=value]... [--csv FILE] [--list-params]\n"
            "defaults: reduced-cartesian, 1 s, dt 0.001 s, 0 V, 1 substep, heun, CSV to stdout.\n"
            "--dt is the board's servo period (whole ns); --volts go through the board's 13-bit DAC;\n"
            "--set takes the spec name and SI unit (see --list-params; HAL uses the hyphenated name,\n"
            "lengths in mm)\n");
}

/* Parse "v0,...,v5" into volts; 0 or -1 with a message. */
static int parse_volts(const char *text, double volts[6])
{
    char buf[512], *tok, *save = 0;
    int n = 0;
    if (strlen(text) >= sizeof buf) {
        fprintf(stderr, "hexaglide sim: --volts: argument too long\n");
        return -1;
    }
    memcpy(buf, text, strlen(text) + 1);   /* length checked above */
    for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(0, ",", &save)) {
        char what[32];
        if (n == 6) {
            fprintf(stderr, "hexaglide sim: --volts: need exactly 6 comma-separated values, got more\n");
            return -1;
        }
        snprintf(what, sizeof what, "--volts V%d", n);
        if (cli_parse_double(tok, what, &volts[n]))
            return -1;
        n++;
    }
    if (n != 6) {
        fprintf(stderr, "hexaglide sim: --volts: need exactly 6 comma-separated values, got %d\n", n);
        return -1;
    }
    return 0;
}

/* Apply "name=value" to p; 0 or -1 with a message. */
static int parse_set(const char *text, hg_params *p)
{
    return cli_parse_set("sim", text, p);
}

static void list_params(void)
{
    int i, n;
    const hg_param_info *t = hg_params_table(&n);
    hg_params p;
    hg_params_default(&p);
    for (i = 0; i < n; i++)
        printf("%-16s %-8s %-14.9g %s (HAL: %s, %s)\n", t[i].name, t[i].unit,
               *hg_params_field(&p, t[i].name), t[i].what, t[i].hal_name, t[i].hal_unit);
}

static void write_row(FILE *f, double t, const hg_board_outputs *o)
{
    int k;
    fprintf(f, "%.9g", t);
    for (k = 0; k < 6; k++)
        fprintf(f, ",%.9g", o->z_m[k] * HG_MM_PER_M);
    for (k = 0; k < 6; k++)
        fprintf(f, ",%.9g", o->zd_mps[k] * HG_MM_PER_M);
    for (k = 0; k < 3; k++)
        fprintf(f, ",%.9g", o->pose[k] * HG_MM_PER_M);
    for (k = 3; k < 6; k++)
        fprintf(f, ",%.9g", o->pose[k] * HG_DEG_PER_RAD);
    fputc('\n', f);
}

int cmd_sim(int argc, char **argv)
{
    hg_board_params bp;
    hg_board *b;
    hg_board_inputs in;
    hg_board_outputs out;
    double t_end = 1.0, dt = 0.001, volts[6] = {0, 0, 0, 0, 0, 0}, substeps = 1;
    const char *csv = 0;
    int kind = HG_MODEL_REDUCED_CARTESIAN, i, k, rc = 0;
    long n, s, period_ns;
    FILE *out_f = stdout;
    hg_params_default(&bp.model);
    bp.substeps = 1;
    bp.integrator = HG_INTEGRATOR_HEUN;
    for (i = 0; i < argc; i++) {
        const char *a = argv[i];
        int has = i + 1 < argc;
        if (strcmp(a, "--list-params") == 0) {
            list_params();
            return 0;
        }
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            sim_usage();
            return 0;
        }
        if (strcmp(a, "--model") != 0 && strcmp(a, "--time") != 0 && strcmp(a, "--dt") != 0 &&
            strcmp(a, "--volts") != 0 && strcmp(a, "--set") != 0 && strcmp(a, "--csv") != 0 &&
            strcmp(a, "--substeps") != 0 && strcmp(a, "--integrator") != 0) {
            fprintf(stderr, "hexaglide sim: unknown %s '%s'\n",
                    strncmp(a, "--", 2) == 0 ? "option" : "argument", a);
            sim_usage();
            return 2;
        }
        if (!has) {
            fprintf(stderr, "hexaglide sim: missing value after '%s'\n", a);
            sim_usage();
            return 2;
        }
        if (strcmp(a, "--model") == 0) {
            kind = hg_model_from_name(argv[++i]);
            if (kind < 0) {
                fprintf(stderr, "hexaglide sim: unknown model '%s' (standard, reduced-joints, "
                                "reduced-cartesian, fused-cartesian)\n", argv[i]);
                return 2;
            }
        } else if (strcmp(a, "--integrator") == 0) {
            int which = hg_integrator_from_name(argv[++i]);
            if (which < 0) {
                fprintf(stderr, "hexaglide sim: unknown integrator '%s' (improved-euler, heun, rk4)\n", argv[i]);
                return 2;
            }
            bp.integrator = (unsigned)which;
        } else if (strcmp(a, "--substeps") == 0) {
            if (cli_parse_double(argv[++i], "--substeps", &substeps))
                return 2;
            if (!(substeps >= 1 && substeps <= HG_SUBSTEPS_MAX && substeps == floor(substeps))) {
                fprintf(stderr, "hexaglide sim: --substeps must be an integer in 1..%u, got %s\n",
                        HG_SUBSTEPS_MAX, argv[i]);
                return 2;
            }
            bp.substeps = (unsigned)substeps;
        } else if (strcmp(a, "--time") == 0) {
            if (cli_parse_double(argv[++i], "--time", &t_end))
                return 2;
        } else if (strcmp(a, "--dt") == 0) {
            if (cli_parse_double(argv[++i], "--dt", &dt))
                return 2;
        } else if (strcmp(a, "--volts") == 0) {
            if (parse_volts(argv[++i], volts))
                return 2;
        } else if (strcmp(a, "--set") == 0) {
            if (parse_set(argv[++i], &bp.model))
                return 2;
        } else {
            csv = argv[++i];
        }
    }
    if (!(t_end >= 0.0)) {
        fprintf(stderr, "hexaglide sim: --time must be >= 0 s, got %g\n", t_end);
        return 2;
    }
    if (!(dt > 0.0 && dt <= HG_DT_MAX_S)) {
        fprintf(stderr, "hexaglide sim: --dt must be positive and at most %g s, got %g\n",
                HG_DT_MAX_S, dt);
        return 2;
    }
    if (cli_parse_period("sim", dt, &period_ns))
        return 2;
    dt = (double)period_ns * 1e-9;           /* what the board integrates */
    if (floor(t_end / dt + 0.5) > (double)SIM_MAX_STEPS) {  /* compare before converting to long */
        fprintf(stderr, "hexaglide sim: %.3g steps is more than the %ld allowed; use a larger --dt "
                        "or a shorter --time\n", floor(t_end / dt + 0.5), SIM_MAX_STEPS);
        return 2;
    }
    n = (long)floor(t_end / dt + 0.5);
    b = cli_board_new("sim", kind, &bp);
    if (!b)
        return 2;
    if (csv) {
        out_f = fopen(csv, "w");
        if (!out_f) {
            perror(csv);
            free(b);
            return 1;
        }
    }
    hg_board_inputs_default(b, &in);
    in.dout_values = 1u << in.estop_loop_out;   /* E-STOP loop closed: amplifiers on */
    for (k = 0; k < 6; k++)
        in.dac_v[k] = volts[k];
    hg_board_peek(b, &out);
    fprintf(out_f, "t,j0,j1,j2,j3,j4,j5,v0,v1,v2,v3,v4,v5,x,y,z,a,b,c\n");
    write_row(out_f, 0.0, &out);
    for (s = 0; s < n; s++) {
        hg_board_step(b, &in, &out, period_ns);
        if (out.fault) {
            char what[HG_GUARD_TEXT_LEN];
            hg_guard_describe(&out.fault_guard, 0, what);
            fprintf(stderr, "hexaglide sim: the step from t = %.6f s to %.6f s failed: %s (code %d)%s%s; "
                            "the CSV stops at t = %.6f s\n",
                    s * dt, (s + 1) * dt, hg_strerror(out.fault_code), out.fault_code, what[0] ? ": " : "",
                    what, s * dt);
            rc = out.fault_code;
            break;
        }
        write_row(out_f, (double)(s + 1) * dt, &out);   /* no drift from summing dt */
    }
    if (out_f != stdout && fclose(out_f) != 0) {
        perror(csv);
        rc = rc ? rc : -1;
    }
    free(b);
    return rc ? 1 : 0;
}
