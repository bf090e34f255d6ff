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

const char cli_usage_sim[] =
    "usage: hexaglide sim [--model standard|reduced-joints|reduced-cartesian|fused-cartesian]\n"
    "                     [--time S] [--dt S] [--volts V0,V1,V2,V3,V4,V5]\n"
    "                     [--substeps N] [--integrator improved-euler|heun|rk4]\n"
    "                     [--ini FILE] [--set name=value]... [--csv FILE] [--list-params]\n"
    "  the virtual board with constant DAC volts, amplifiers on, one CSV row per servo period:\n"
    "  t_s, z0_mm..z5_mm (joints), zd0_mm_s..zd5_mm_s (joint velocities), x_mm y_mm z_mm,\n"
    "  a_deg b_deg c_deg (head pose)\n"
    "defaults: reduced-cartesian, 1 s, dt 0.001 s, 0 V, CSV to stdout; --substeps and --integrator\n"
    "as the board loads them (motenc-hexaglide.N.substeps, .integrator).\n"
    "--dt is the board's servo period (whole ns); --volts go through the board's 13-bit DAC;\n"
    "--list-params prints every parameter: spec name, SI unit, default, HAL name and INI key\n"
    CLI_USAGE_MODEL;

static void list_params(void)
{
    int i, n;
    const hg_param_info *t = hg_params_table(&n);
    hg_params p;
    hg_params_default(&p);
    for (i = 0; i < n; i++) {
        const char *key = cli_ini_key_of(t[i].name);
        printf("%-16s %-8s %-14.9g %s (HAL: %s, %s", t[i].name, t[i].unit, *hg_params_field(&p, t[i].name),
               t[i].what, t[i].hal_name, t[i].hal_unit);
        if (key)
            printf("; INI: [HEXAGLIDE]%s, %s", key, t[i].hal_unit);
        printf(")\n");
    }
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

/* The CSV header: units in every name, none like an option. */
static void write_header(FILE *f)
{
    int k;
    fprintf(f, "t_s");
    for (k = 0; k < 6; k++)
        fprintf(f, ",z%d_mm", k);
    for (k = 0; k < 6; k++)
        fprintf(f, ",zd%d_mm_s", k);
    fprintf(f, ",x_mm,y_mm,z_mm,a_deg,b_deg,c_deg\n");
}

enum { OPT_MODEL, OPT_TIME, OPT_DT, OPT_VOLTS, OPT_SUBSTEPS, OPT_INTEGRATOR, OPT_INI, OPT_SET, OPT_CSV,
       OPT_LIST };
static const cli_opt sim_opts[] = {
    {"--model", 1}, {"--time", 1}, {"--dt", 1}, {"--volts", 1}, {"--substeps", 1}, {"--integrator", 1},
    {"--ini", 1}, {"--set", 1}, {"--csv", 1}, {"--list-params", 0}, {0, 0},
};
static const char *const volt_names[6] = {"V0", "V1", "V2", "V3", "V4", "V5"};

int cmd_sim(int argc, char **argv)
{
    hg_board_params bp;
    hg_board *b;
    hg_board_inputs in;
    hg_board_outputs out;
    cli_args a;
    cli_out csv;
    double t_end = 1.0, dt = 0.001, volts[6] = {0, 0, 0, 0, 0, 0}, substeps = 1;
    const char *csv_path = 0, *ini = 0, *v;
    char *sets[argc > 0 ? argc : 1];
    int kind = HG_MODEL_REDUCED_CARTESIAN, k, o, nset = 0, rc = 0;
    long n, s, period_ns;
    if (cli_board_defaults(&bp)) {
        fprintf(stderr, "hexaglide sim: out of memory\n");
        return 1;
    }
    cli_args_init(&a, "sim", cli_usage_sim, sim_opts, argc, argv);
    while ((o = cli_next(&a, &v)) != CLI_DONE) {
        switch (o) {
        case CLI_HELP:
            return 0;
        case CLI_BAD:
            return 2;
        case CLI_ARG:
            fprintf(stderr, "hexaglide sim: unexpected argument '%s' ('hexaglide sim --help' lists the "
                    "options)\n", v);
            return 2;
        case OPT_LIST:
            list_params();
            return 0;
        case OPT_MODEL:
            kind = hg_model_from_name(v);
            if (kind < 0) {
                fprintf(stderr, "hexaglide sim: unknown model '%s' (standard, reduced-joints, "
                                "reduced-cartesian, fused-cartesian)\n", v);
                return 2;
            }
            break;
        case OPT_INTEGRATOR: {
            int which = hg_integrator_from_name(v);
            if (which < 0) {
                fprintf(stderr, "hexaglide sim: unknown integrator '%s' (improved-euler, heun, rk4)\n", v);
                return 2;
            }
            bp.integrator = (unsigned)which;
            break;
        }
        case OPT_SUBSTEPS:
            if (cli_parse_double(v, "--substeps", &substeps))
                return 2;
            if (!(substeps >= 1 && substeps <= HG_SUBSTEPS_MAX && substeps == floor(substeps))) {
                fprintf(stderr, "hexaglide sim: --substeps must be an integer in 1..%u, got %s\n",
                        HG_SUBSTEPS_MAX, v);
                return 2;
            }
            bp.substeps = (unsigned)substeps;
            break;
        case OPT_TIME:
            if (cli_parse_double(v, "--time", &t_end))
                return 2;
            break;
        case OPT_DT:
            if (cli_parse_double(v, "--dt", &dt))
                return 2;
            break;
        case OPT_VOLTS:
            if (cli_parse_list("sim", "--volts", v, volt_names, 6, volts))
                return 2;
            break;
        case OPT_INI:
            if (ini) {
                fprintf(stderr, "hexaglide sim: --ini given twice (%s and %s)\n", ini, v);
                return 2;
            }
            ini = v;
            break;
        case OPT_SET:
            sets[nset++] = (char *)v;
            break;
        default:                       /* OPT_CSV */
            csv_path = v;
        }
    }
    if (cli_params_build("sim", ini, sets, nset, &bp.model))
        return 2;
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
    if (cli_out_open("sim", csv_path, &csv)) {
        free(b);
        return 1;
    }
    hg_board_inputs_default(b, &in);
    in.dout_values = 1u << in.estop_loop_out;   /* E-STOP loop closed: amplifiers on */
    for (k = 0; k < 6; k++)
        in.dac_v[k] = volts[k];
    hg_board_peek(b, &out);
    write_header(csv.f);
    write_row(csv.f, 0.0, &out);
    for (s = 0; s < n; s++) {
        hg_board_step(b, &in, &out, period_ns);
        if (out.events & HG_EV_SUBSTEPS_AUTO) {
            char why[HG_BOARD_TEXT_LEN];
            hg_board_describe_stiffness(b, &out, period_ns, 0, why);
            fprintf(stderr, "hexaglide sim: %s: running %u substeps per period instead of %u\n", why,
                    out.substeps_run, out.params.substeps);
        }
        if (out.fault && out.fault_cause == HG_FAULT_STIFF) {
            char why[HG_BOARD_TEXT_LEN];
            hg_board_describe_stiffness(b, &out, period_ns, 0, why);
            fprintf(stderr, "hexaglide sim: %s: %s even with %u substeps; give a softer value, another "
                            "--integrator or a shorter --dt\n", why, hg_strerror(out.fault_code), HG_SUBSTEPS_MAX);
            rc = out.fault_code;
            break;
        }
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
        write_row(csv.f, (double)(s + 1) * dt, &out);   /* no drift from summing dt */
    }
    if (cli_out_close("sim", &csv, 1))       /* the rows before a failure are kept */
        rc = rc ? rc : -1;
    free(b);
    return rc ? 1 : 0;
}
