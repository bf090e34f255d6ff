/* cmd_sim.c - the sim subcommand: offline simulation of the virtual board
 * (hg_board.h, the code LinuxCNC runs) with constant DAC volts and the
 * amplifiers enabled, one CSV row per servo period (mm, mm/s, degrees). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "hg_board_rec.h"
#include "hg_scheme.h"
#include "hg_errors.h"
#include "hg_units.h"

#define SIM_MAX_STEPS 100000000L   /* refuse runs longer than this many steps */

const char cli_usage_sim[] =
    "usage: hexaglide sim [--plant hexaglide] [--model standard|reduced-joints|reduced-cartesian|fused-cartesian]\n"
    "                     [--time S] [--dt S] [--volts V0,V1,V2,V3,V4,V5]\n"
    "                     [--substeps N] [--integrator improved-euler|heun|rk4]\n"
    "                     [--ini FILE] [--set name=value]... [--csv FILE] [--record FILE] [--list-params]\n"
    "  the virtual board with constant DAC volts, amplifiers on, one CSV row per servo period:\n"
    "  t_s, z0_mm..z5_mm (joints: the carriages), zd0_mm_s..zd5_mm_s (joint velocities),\n"
    "  zm0_mm..zm5_mm (the motors: the encoders' side of the drive trains), x_mm y_mm z_mm,\n"
    "  a_deg b_deg c_deg (head pose); a rotary channel's columns are in deg, deg_s\n"
    "defaults: the hexaglide plant, its default model (reduced-cartesian), 1 s, dt 0.001 s, 0 V,\n"
    "CSV to stdout (also --csv -); --volts takes one value per channel of the plant; --substeps and --integrator\n"
    "as the board loads them (motenc-hexaglide.N.substeps, .integrator).\n"
    "--dt is the board's servo period (whole ns), --time a whole number of periods (at most 1e8);\n"
    "--volts go through the board's 13-bit DAC;\n"
    "--list-params prints every parameter: spec name, SI unit, value (the defaults, then --ini\n"
    "and --set, checked), HAL name and INI key, and runs nothing (it takes --plant, --model, --ini, --set alone);\n"
    "--record FILE writes the run as a record of the board's rec pins (hexaglide replay FILE), one row\n"
    "a period: --time of at least one period;\n"
    "--record - writes it to stdout, with --csv FILE (stdout holds one of them alone)\n"
    CLI_USAGE_MODEL;

/* Every parameter of v: spec name, SI unit, value, what it is, HAL name and INI key. */
static void list_params(int plant, int variant, const hg_plant_params *v)
{
    const hg_plant *pl = hg_plant_at(plant);
    int i, n = pl->nparams(variant);
    for (i = 0; i < n; i++) {
        hg_param_info t;
        pl->param(variant, i, &t);
        printf("%-16s %-8s %-14.9g %s (HAL: %s, %s", t.name, t.unit, v->v[i], t.what, t.hal_name, t.hal_unit);
        if (t.ini_key)
            printf("; INI: [%s]%s, %s", pl->ini_section, t.ini_key, t.hal_unit);
        printf(")\n");
    }
}

/* One CSV row of the board's outputs at time t, in write_header's column order. */
static void write_row(FILE *f, double t, const hg_plant *pl, const hg_board_outputs *o)
{
    int k;
    fprintf(f, "%.9g", t);
    for (k = 0; k < o->channels; k++)
        fprintf(f, ",%.9g", o->pos[k] * cli_machine_unit(o->rotary, k));
    for (k = 0; k < o->channels; k++)
        fprintf(f, ",%.9g", o->vel[k] * cli_machine_unit(o->rotary, k));
    for (k = 0; k < o->channels; k++)
        fprintf(f, ",%.9g", o->motor_pos[k] * cli_machine_unit(o->rotary, k));
    for (k = 0; k < pl->noutputs; k++)
        if (pl->outputs[k].csv_name)
            fprintf(f, ",%.9g", o->extra[k] * pl->outputs[k].hal_scale);
    fputc('\n', f);
}

/* The CSV header: units in every name, none like an option. */
static void write_header(FILE *f, const hg_plant *pl, const hg_board_outputs *o)
{
    int k;
    fprintf(f, "t_s");
    for (k = 0; k < o->channels; k++)
        fprintf(f, ",z%d_%s", k, cli_machine_unit_name(o->rotary, k));
    for (k = 0; k < o->channels; k++)
        fprintf(f, ",zd%d_%s_s", k, cli_machine_unit_name(o->rotary, k));
    for (k = 0; k < o->channels; k++)
        fprintf(f, ",zm%d_%s", k, cli_machine_unit_name(o->rotary, k));
    for (k = 0; k < pl->noutputs; k++)
        if (pl->outputs[k].csv_name)
            fprintf(f, ",%s", pl->outputs[k].csv_name);
    fputc('\n', f);
}

/* A record of the run in the format the HAL glue's rec pins carry (for
 * `hexaglide replay`): the table, the parameters' event stream, one row per period. */
typedef struct {
    cli_out out;
    hg_board_rec_field f[HG_BOARD_REC_MAX];
    int n, np;
    hg_board_rec_stream stream;
} sim_record;

/* Open path and write the record's header; 0, or -1 after a message. */
static int record_open(sim_record *r, const char *path, const hg_board *b)
{
    int k;
    r->n = hg_board_rec_fields(r->f, HG_BOARD_REC_MAX, b->plant, b->variant, HG_BOARD_REC_FORMAT);
    r->np = hg_board_plant(b)->nparams(b->variant);
    if (r->n < 0 || cli_out_open("sim", path, &r->out))
        return -1;
    hg_board_rec_stream_start(&r->stream, b->plant, b->variant);
    fprintf(r->out.f, "# hexaglide-record %d\n# source hexaglide sim (open loop, constant volts)\n# board 0\n"
                      "# plant %s\n# closed-loop no: an open-loop run of hexaglide sim\nsample",
            HG_BOARD_REC_FORMAT, hg_board_plant(b)->name);
    for (k = 0; k < r->n; k++)
        fprintf(r->out.f, ",%s", r->f[k].name);
    fputc('\n', r->out.f);
    return 0;
}

/* One row: period s's inputs and outputs, exactly (%.17g). */
static void record_row(sim_record *r, long s, const hg_board *b, const hg_board_inputs *in,
                       const hg_board_outputs *out, long period_ns)
{
    hg_board_rec_ctx c;
    int k;
    hg_board_rec_stream_step(&r->stream, &in->params, r->np);
    c.in = in;
    c.out = out;
    c.period_ns = period_ns;
    c.plant = b->plant;
    c.variant = b->variant;
    c.stream = &r->stream;
    fprintf(r->out.f, "%ld", s);
    for (k = 0; k < r->n; k++)
        fprintf(r->out.f, ",%.17g", hg_board_rec_get(r->f, r->n, k, &c));
    fputc('\n', r->out.f);
}

/* 1 after a message if parameter events that differ from the defaults (where a replay starts) still
 * wait in the stream after the record's rows: replay could not apply them. */
static int record_incomplete(const sim_record *r, const hg_board *b, long rows)
{
    hg_board_params d;
    int k, waiting = 0;
    if (hg_board_params_default(b->plant, b->variant, &d))
        return 0;
    for (k = 0; k < r->stream.count; k++) {
        const hg_board_rec_event *ev = &r->stream.q[(r->stream.head + k) % HG_BOARD_REC_QUEUE];
        double v = hg_board_rec_entry(&d, r->np, ev->entry);
        waiting += memcmp(&v, &ev->value, sizeof v) != 0; // NOLINT(bugprone-suspicious-memory-comparison): bitwise, as the fingerprint
    }
    if (!waiting)
        return 0;
    fprintf(stderr, "hexaglide sim: --record: %d parameter value%s other than the default did not fit into the "
                    "record's %ld row%s (%d events a period): replay stops at its first sample; record a longer "
                    "run (--time)\n", waiting, waiting == 1 ? "" : "s", rows, rows == 1 ? "" : "s",
            HG_BOARD_REC_SLOTS);
    return 1;
}

enum { OPT_MODEL, OPT_TIME, OPT_DT, OPT_VOLTS, OPT_SUBSTEPS, OPT_INTEGRATOR, OPT_INI, OPT_SET, OPT_CSV,
       OPT_LIST, OPT_PLANT, OPT_RECORD };
static const cli_opt sim_opts[] = {
    {"--model", 1}, {"--time", 1}, {"--dt", 1}, {"--volts", 1}, {"--substeps", 1}, {"--integrator", 1},
    {"--ini", 1}, {"--set", CLI_REPEAT}, {"--csv", 1}, {"--list-params", 0}, {"--plant", 1}, {"--record", 1}, {0, 0},
};
static const char *const volt_names[HG_CHANNELS_MAX] = {"V0", "V1", "V2", "V3", "V4", "V5", "V6", "V7"};

int cmd_sim(int argc, char **argv)
{
    hg_board_params bp;
    hg_board *b;
    hg_board_inputs in;
    hg_board_outputs out;
    cli_args a;
    cli_out csv;
    double t_end = 1.0, dt = 0.001, volts[HG_CHANNELS_MAX] = {0, 0, 0, 0, 0, 0, 0, 0}, substeps = 1;
    const char *csv_path = 0, *ini = 0, *v, *model = 0, *volts_text = 0, *integrator = 0, *record = 0;
    static sim_record rec;
    char *sets[argc > 0 ? argc : 1];
    int plant = 0, variant, k, o, nset = 0, rc = 0, list = 0, given_substeps = 0;
    long n, s, period_ns;
    const hg_plant *pl;
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
            list = 1;
            break;
        case OPT_PLANT:
            if ((plant = cli_plant("sim", v)) < 0)
                return 2;
            break;
        case OPT_MODEL:
            model = v;
            break;
        case OPT_INTEGRATOR:
            if (hg_integrator_from_name(v) < 0) {
                fprintf(stderr, "hexaglide sim: unknown integrator '%s' (improved-euler, heun, rk4)\n", v);
                return 2;
            }
            integrator = v;
            break;
        case OPT_SUBSTEPS:
            if (cli_parse_double("sim", v, "--substeps", &substeps))
                return 2;
            if (!(substeps >= 1 && substeps <= HG_SUBSTEPS_MAX && substeps == floor(substeps))) {
                fprintf(stderr, "hexaglide sim: --substeps must be an integer in 1..%u, got %s\n",
                        HG_SUBSTEPS_MAX, v);
                return 2;
            }
            given_substeps = 1;
            break;
        case OPT_TIME:
            if (cli_parse_double("sim", v, "--time", &t_end))
                return 2;
            break;
        case OPT_DT:
            if (cli_parse_double("sim", v, "--dt", &dt))
                return 2;
            break;
        case OPT_VOLTS:
            volts_text = v;
            break;
        case OPT_INI:
            ini = v;                   /* (each value option once: cli_next refuses a second) */
            break;
        case OPT_SET:
            sets[nset++] = (char *)v;
            break;
        case OPT_RECORD:
            record = v;
            break;
        default:                       /* OPT_CSV */
            csv_path = v;
        }
    }
    if (list) {                        /* what the listing reads; the rest would be unused */
        static const char *const keep[] = {"--plant", "--model", "--ini", "--set", 0};
        if (cli_list_only(&a, "--list-params", keep))
            return 2;
    }
    if (record && cli_out_is_stdout(csv_path) && cli_out_is_stdout(record)) {
        fprintf(stderr, "hexaglide sim: --record - and the CSV (%s) would both write standard output; give "
                "--csv FILE or --record FILE\n", csv_path ? "--csv -" : "standard output without --csv");
        return 2;
    }
    if (csv_path && record && cli_out_same(csv_path, record)) {
        fprintf(stderr, "hexaglide sim: --csv %s and --record %s name the same file; give two files\n", csv_path,
                record);
        return 2;
    }
    if (cli_out_is_input("sim", "--csv", csv_path, "--ini", ini) || cli_out_is_input("sim", "--record", record, "--ini", ini))
        return 2;
    pl = hg_plant_at(plant);
    if ((variant = cli_variant("sim", plant, model)) < 0)
        return 2;
    cli_board_defaults(plant, variant, &bp);
    if (given_substeps)
        bp.substeps = (unsigned)substeps;
    if (integrator)
        bp.integrator = (unsigned)hg_integrator_from_name(integrator);
    if (cli_params_build("sim", plant, variant, ini, sets, nset, &bp.plant) ||
        cli_params_check_from("sim", plant, variant, &bp.plant, ini, sets, nset))
        return 2;
    if (list) {                        /* the parameters in force: defaults, --ini, --set, checked */
        list_params(plant, variant, &bp.plant);
        return 0;
    }
    if (!(t_end >= 0.0)) {
        fprintf(stderr, "hexaglide sim: --time must be >= 0 s, got %g\n", t_end);
        return 2;
    }
    if (cli_parse_period("sim", dt, &period_ns))
        return 2;
    dt = (double)period_ns * 1e-9;           /* what the board integrates */
    if (cli_whole_periods("sim", "--time", t_end, 1.0, "s", period_ns, 0, SIM_MAX_STEPS, &n))
        return 2;
    if (record && n == 0) {            /* a record is its rows: replay refuses one without */
        char t[CLI_NUM_LEN], p[CLI_NUM_LEN];
        fprintf(stderr, "hexaglide sim: --record %s with --time %s: a run of no periods has no rows to record, and "
                "replay refuses a record without them; give --time of at least one period (%s s)\n", record,
                cli_num(t_end, t), cli_num(dt, p));
        return 2;
    }
    if (cli_board_integrable("sim", plant, variant, &bp, period_ns, sets, nset))
        return 2;                      /* before any output is opened */
    b = cli_board_new("sim", plant, variant, &bp);
    if (!b)
        return 2;
    if (record) {                      /* as at loadrt: the spec's defaults, the block applied by the first period */
        free(b);
        b = cli_board_new("sim", plant, variant, 0);
        if (!b)
            return 2;
    }
    if (volts_text && cli_parse_list("sim", "--volts", volts_text, volt_names, b->sense.channels, volts)) {
        free(b);
        return 2;
    }
    for (k = 0; k < b->sense.channels; k++)
        if (!(fabs(volts[k]) <= HG_DAC_VOLTS_MAX)) {  /* the DAC would clamp it: say so instead */
            char num[CLI_NUM_LEN];
            fprintf(stderr, "hexaglide sim: --volts: %s = %s V is outside the DAC's range of -%g to %g V\n",
                    volt_names[k], cli_num(volts[k], num), HG_DAC_VOLTS_MAX, HG_DAC_VOLTS_MAX);
            free(b);
            return 2;
        }
    if (cli_out_open("sim", csv_path, &csv)) {
        free(b);
        return 1;
    }
    if (record && record_open(&rec, record, b)) {
        cli_out_close("sim", &csv, 0);
        free(b);
        return 1;
    }
    hg_board_inputs_default(b, &in);
    in.params = bp;                            /* (in force already unless recording) */
    in.dout_values = 1u << in.estop_loop_out;   /* E-STOP loop closed: amplifiers on */
    for (k = 0; k < b->sense.channels; k++)
        in.dac_v[k] = volts[k];
    hg_board_peek(b, &out);
    write_header(csv.f, pl, &out);
    write_row(csv.f, 0.0, pl, &out);
    for (s = 0; s < n; s++) {
        hg_board_step(b, &in, &out, period_ns);
        if (record)
            record_row(&rec, s, b, &in, &out, period_ns);
        if (out.events & HG_EV_SUBSTEPS_AUTO && given_substeps) {  /* (without --substeps: as the step needs) */
            char why[HG_BOARD_TEXT_LEN];
            hg_board_describe_stiffness(b, &out, period_ns, 0, why);
            fprintf(stderr, "hexaglide sim: %s: running %u substeps per period instead of %u\n", why,
                    out.substeps_run, out.params.substeps);
        }
        if (out.fault) {
            char what[HG_PLANT_TEXT_LEN + 2 * HG_BOARD_TEXT_LEN];
            cli_fault_text(b, &out, period_ns, what);
            fprintf(stderr, "hexaglide sim: the step from t = %.6f s to %.6f s failed: %s; the CSV stops at "
                            "t = %.6f s\n", s * dt, (s + 1) * dt, what, s * dt);
            rc = out.fault_code;
            break;
        }
        write_row(csv.f, (double)(s + 1) * dt, pl, &out);   /* no drift from summing dt */
    }
    if (cli_out_close("sim", &csv, 1))       /* the rows before a failure are kept */
        rc = rc ? rc : -1;
    if (record && record_incomplete(&rec, b, s < n ? s + 1 : s))
        rc = rc ? rc : -1;
    if (record && cli_out_close("sim", &rec.out, 1))
        rc = rc ? rc : -1;
    free(b);
    return rc ? 1 : 0;
}
