/* cmd_replay.c - the replay subcommand: re-run a recorded LinuxCNC run
 * (tools/hg_record.py) through hg_board, period by period, and compare
 * the outputs with the recorded ones; or, with --set/--model/--substeps/
 * --integrator, run a changed board (what-if): by default closed loop,
 * LinuxCNC's six pid loops (hg_loop, the recorded gains) on the recorded
 * joint commands, reporting the following error and drive volts predicted
 * beside the recorded ones; with --open-loop, the recorded DAC volts into
 * the changed board. Both runs are written side by side (docs/replay.md). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "cli.h"
#include "hg_board.h"
#include "hg_board_rec.h"
#include "hg_board_rec_read.h"
#include "hg_errors.h"
#include "hg_loop.h"
#include "hg_record.h"
#include "hg_units.h"
#include "hg_scheme.h"

#define REPLAY_MAX_SETS 64
#define REPLAY_MAX_SPREAD 16          /* --spread: closed loops side by side */
#define SPREAD_STEP 7                 /* periods between the loops' program starts */
#define SPREAD_IDLE 20                /* unchanged commands after homing that make the idle to stretch */
#define RING 128                      /* periods kept for the delayed loops (> 7 * 15 + 1) */
#define REPLAY_MAX_BYTES (4LL << 30)  /* refuse record files above 4 GiB */

typedef struct {
    const char *file, *csv, *plot, *model, *plant;
    const char *set[REPLAY_MAX_SETS];
    int nset;
    long substeps;                    /* -1: as recorded */
    int integrator;                   /* -1: as recorded */
    int open_loop;                    /* --open-loop: recorded DAC volts, no pid */
    long from;                        /* --from: first sample of the f-error statistics, -1 auto */
    long spread;                      /* --spread: closed loops with the program started later */
    int format;                       /* --list-columns --format: the record format listed */
} replay_opts;

/* What a closed loop consumes in one period, kept for the delayed --spread loops. */
typedef struct {
    hg_board_inputs in;               /* the what-if board's inputs */
    double cmd[HG_CHANNELS_MAX];      /* joint commands (mm) */
    int enable[HG_CHANNELS_MAX];      /* pid.N.enable */
    unsigned ie_rec, prev_ie_rec, prev_latched_rec; /* index-enable edges as recorded */
    unsigned win;                     /* bit k: joint k counts in the f-error window */
    int reset;                        /* the window starts again here (a latch) */
    long period;
} period_in;

/* What the comparison found. */
typedef struct {
    long samples;
    long long max_count_diff;
    double max_pos_diff_mm, max_pose_diff;  /* linear channels (mm), the plant's own outputs */
    long first_mismatch;              /* sample, -1 if none */
    long mismatched_samples;
    double max_pos_diff_deg;          /* rotary channels (deg: LinuxCNC's unit) */
} replay_stats;

/* Following error and drive volts of one joint over the statistics window:
 * [0] recorded, [1] replayed or predicted. */
typedef struct {
    double peak_mm[2], sq[2], peak_v[2];
    long peak_at[2], n;
    double count_mm;                  /* one encoder count, in the joint's unit (the resolution) */
} joint_stats;

/* pid.c's setting pins (the footer's pid.N.<name> lines, tools/hg_record.py
 * PID_SETTINGS) are hg_pid_setting_at's table. */

const char cli_usage_replay[] =
    "usage: hexaglide replay FILE [--csv OUT] [--plot PNG] [--set name=value]...\n"
    "                        [--model NAME] [--substeps N] [--integrator NAME]\n"
    "                        [--open-loop] [--from SAMPLE] [--spread K] [--plant NAME]\n"
    "       hexaglide replay --list-columns [--plant NAME] [--format 1|2]   (the record pin set)\n"
    "--plant: the machine the record must be of (the record names its own, in.plant);\n"
    "a record of another plant is refused.\n"
    "FILE: a record of tools/hg_record.py (docs/replay.md). Without --set, --model,\n"
    "--substeps, --integrator: replays and compares, exit 0 only if bit-exact.\n"
    "With them (what-if): the changed board under LinuxCNC's pid loops with the\n"
    "recorded gains, on the recorded joint commands (closed loop), or fed the\n"
    "recorded DAC volts (--open-loop); written to FILE.whatif.png.csv and\n"
    "plotted to FILE.whatif.png unless --csv/--plot say otherwise (--csv -: the CSV\n"
    "to stdout, the report to stderr; not with --plot); --set takes\n"
    "the spec name and SI unit (hexaglide sim --list-params). Following-error\n"
    "statistics from --from SAMPLE (default: after the last index latch, homing).\n"
    "--spread K: K closed loops, the idle after homing stretched by 0, 7, ... periods\n"
    "(when LinuxCNC starts the program), predicted peaks as median and range.\n"
    "--plot runs tools/plot_replay.py under the first python3 that imports numpy and\n"
    "matplotlib ($HEXAGLIDE_PYTHON, else $PATH).\n";

/* The record pin set of plant in format (2: what the glue records): one
 * line per column, name, HAL type, direction. */
static void list_columns(int plant, int format)
{
    static hg_board_rec_field f[HG_BOARD_REC_MAX];
    static const char *const type[] = {"float", "s32", "u32", "bit", "u32"};
    int i, n = hg_board_rec_fields(f, HG_BOARD_REC_MAX, plant, hg_plant_at(plant)->default_variant, format);
    for (i = 0; i < n; i++)
        printf("%-28s %-5s %s%s\n", f[i].name, type[f[i].type],
               f[i].side == HG_BRS_OUT ? "output, compared" : "input of hg_board_step",
               f[i].type == HG_BRF_PACK ? ", bits packed"
               : f[i].nonfinite ? ", 0 when NaN/inf (then in in.nonfinite-*)"
               : f[i].side == HG_BRS_NFMASK ? ", 2 bits per NaN/inf-capable input" : "");
}

enum { OPT_CSV, OPT_PLOT, OPT_SET, OPT_MODEL, OPT_SUBSTEPS, OPT_INTEGRATOR, OPT_FROM, OPT_SPREAD,
       OPT_OPEN, OPT_LIST, OPT_PLANT, OPT_FORMAT };
static const cli_opt replay_options[] = {
    {"--csv", 1}, {"--plot", 1}, {"--set", CLI_REPEAT}, {"--model", 1}, {"--substeps", 1}, {"--integrator", 1},
    {"--from", 1}, {"--spread", 1}, {"--open-loop", 0}, {"--list-columns", 0}, {"--plant", 1}, {"--format", 1}, {0, 0},
};

/* Where the report goes: stdout, or stderr when the CSV is written to stdout (--csv -). */
static FILE *report;

/* An integer option in lo..hi; 0, or 2 after a message saying what to give. */
static int int_opt(const char *name, const char *v, long lo, long hi, const char *give, long *out)
{
    char *end = 0;
    errno = 0;
    *out = strtol(v, &end, 10);
    if (end == v || *end || errno || *out < lo || *out > hi) {
        fprintf(stderr, "hexaglide replay: %s %s: give %s\n", name, v, give);
        return 2;
    }
    return 0;
}

/* Parse the options; 0, 2 (usage error, message printed), -1 (done: listed or --help). */
static int parse_opts(int argc, char **argv, replay_opts *o)
{
    cli_args a;
    const char *v;
    int opt, list = 0;
    memset(o, 0, sizeof *o);
    o->substeps = -1;
    o->integrator = -1;
    o->from = -1;
    o->spread = 1;
    o->format = HG_BOARD_REC_FORMAT;
    cli_args_init(&a, "replay", cli_usage_replay, replay_options, argc, argv);
    while ((opt = cli_next(&a, &v)) != CLI_DONE) {
        switch (opt) {
        case CLI_HELP:
            return -1;
        case CLI_BAD:
            return 2;
        case CLI_ARG:
            if (o->file) {
                fprintf(stderr, "hexaglide replay: one record file only (got %s and %s)\n", o->file, v);
                return 2;
            }
            o->file = v;
            break;
        case OPT_CSV:
            o->csv = v;
            break;
        case OPT_PLOT:
            o->plot = v;
            break;
        case OPT_SET:
            if (o->nset == REPLAY_MAX_SETS) {
                fprintf(stderr, "hexaglide replay: more than %d --set options\n", REPLAY_MAX_SETS);
                return 2;
            }
            o->set[o->nset++] = v;
            break;
        case OPT_MODEL:
            o->model = v;             /* checked against the record's plant */
            break;
        case OPT_PLANT:
            o->plant = v;
            break;
        case OPT_FORMAT: {
            long n;
            if (int_opt("--format", v, 1, HG_BOARD_REC_FORMAT, "1 (d20d9e5 and before) or 2", &n))
                return 2;
            o->format = (int)n;
            break;
        }
        case OPT_SUBSTEPS: {
            long n;
            if (int_opt("--substeps", v, 1, (long)HG_SUBSTEPS_MAX, "an integer 1..64", &n))
                return 2;
            o->substeps = n;
            break;
        }
        case OPT_INTEGRATOR:
            o->integrator = hg_integrator_from_name(v);
            if (o->integrator < 0) {
                fprintf(stderr, "hexaglide replay: --integrator %s unknown; use improved-euler, heun or rk4\n", v);
                return 2;
            }
            break;
        case OPT_FROM:
            if (int_opt("--from", v, 0, LONG_MAX, "a sample number (0, 1, ...)", &o->from))
                return 2;
            break;
        case OPT_SPREAD: {
            long n;
            if (int_opt("--spread", v, 1, REPLAY_MAX_SPREAD, "an integer 1..16", &n))
                return 2;
            o->spread = (int)n;
            break;
        }
        case OPT_OPEN:
            o->open_loop = 1;
            break;
        default:                       /* OPT_LIST */
            list = 1;
        }
    }
    if (list) {
        static const char *const keep[] = {"--plant", "--format", 0};
        int p;
        if (cli_list_only(&a, "--list-columns", keep))
            return 2;
        p = cli_plant("replay", o->plant);
        if (o->file) {                 /* nothing given is silently left unused */
            fprintf(stderr, "hexaglide replay: --list-columns takes no record file (got '%s'): it lists the pins of "
                    "--plant's records; give either --list-columns or a record FILE\n", o->file);
            return 2;
        }
        if (p < 0)
            return 2;
        if (o->format == 1 && p != 0) {
            fprintf(stderr, "hexaglide replay: --format 1 was the Hexaglide's only\n");
            return 2;
        }
        list_columns(p, o->format);
        return -1;
    }
    if (!o->file) {
        fprintf(stderr, "hexaglide replay: give a record FILE ('hexaglide replay --help' for the usage)\n");
        return 2;
    }
    return 0;
}

/* The --set options as (table entry of plant, value) pairs; 0 or 2 with a message. */
static int parse_sets(const replay_opts *o, int plant, int variant, int *idx, double *val)
{
    int i;
    for (i = 0; i < o->nset; i++) {
        hg_plant_params p;
        idx[i] = cli_parse_set("replay", o->set[i], plant, variant, &p);
        if (idx[i] < 0)
            return 2;
        val[i] = p.v[idx[i]];
    }
    return 0;
}

/* 0 if the --set values (idx, val) make a valid machine wherever the record's own parameters
 * are one: the spec's defaults (a format-1 record's as then), then each time its events (ev, in
 * order) change them; else 2 after naming the refused fields and the sample (a what-if would stop
 * there: refused up front, as sim refuses them). */
static int sets_valid(const replay_opts *o, const char *const *sets, int plant, int variant, int format,
                      const hg_board_rec_event *ev, long nev, const int *idx, const double *val)
{
    static const char *why[HG_PLANT_PARAMS_MAX];
    const hg_plant *pl = hg_plant_at(plant);
    int np = pl->nparams(variant), k;
    long i = 0;
    unsigned long at = 0;
    hg_board_params p, q;
    hg_board_params_default(plant, variant, &p);
    if (format < HG_BOARD_REC_FORMAT)
        pl->legacy(format, variant, &p.plant);
    for (;;) {
        hg_bitset bad;
        q = p;
        for (k = 0; k < o->nset; k++)
            q.plant.v[idx[k]] = val[k];
        hg_bitset_clear(&bad);
        if (!pl->check(variant, &p.plant, &bad, why) &&   /* (the record's own refusals are its own) */
            cli_params_check_from("replay", plant, variant, &q.plant, 0, (char *const *)sets, o->nset)) {
            fprintf(stderr, "hexaglide replay: %s: with --set, the record's parameters in force from sample %lu on "
                    "are no valid machine: the what-if cannot run; change --set\n", o->file, at);
            return 2;
        }
        if (i >= nev)
            return 0;
        for (at = ev[i].at; i < nev && ev[i].at == at; i++)
            hg_board_rec_entry_set(&p, np, ev[i].entry, ev[i].value);
    }
}

/* 1 when the nj joint commands are equal (an idle period). */
static int same_commands(const double *a, const double *b, int nj)
{
    int k;
    for (k = 0; k < nj; k++)
        if (a[k] != b[k])
            return 0;
    return 1;
}

/* 1 if a and b differ in any bit. */
static int bits_differ(double a, double b)
{
    uint64_t x, y;
    memcpy(&x, &a, sizeof x);
    memcpy(&y, &b, sizeof y);
    return x != y;
}

/* Where a replay finds the record's columns and what it writes per joint. */
typedef struct {
    int nj;                           /* joints: the plant's channels */
    int z[HG_CHANNELS_MAX], count[HG_CHANNELS_MAX], cmd[HG_CHANNELS_MAX];
    int extra[HG_PLANT_EXTRA_MAX];    /* out.<rec_name> of the plant's float outputs, -1 if none */
    int fault_code;
    int pos_cmd;                      /* in.pos-cmd-0 (format 2: the tool-path error's commands), -1 if none */
    const hg_plant *plant;
} replay_cols;

/* 1 if the plant's output i is a recorded float (the CSV shows it). */
static int csv_extra(const hg_plant *p, int i)
{
    return p->outputs[i].rec_name && !p->outputs[i].is_u32;
}

/* One CSV row: sample, time, recorded and replayed joints (machine units:
 * mm, deg for a rotary axis), the replayed motors (the encoders' side),
 * counts, the plant's own outputs (its HAL units), the replayed tool-path
 * error (mm, -1 none: a format-1 record has no commands), fault codes; with
 * joint commands: f-errors (machine units) and drive volts. */
static void csv_row(FILE *f, long n, const double *row, const replay_cols *c, const hg_board_outputs *o,
                    const double (*fe)[HG_CHANNELS_MAX], const double (*volts)[HG_CHANNELS_MAX])
{
    const hg_plant *p = c->plant;
    int k, w;
    fprintf(f, "%ld,%.17g", n, o->sim_time_s);
    for (k = 0; k < c->nj; k++)
        fprintf(f, ",%.17g", row[c->z[k]] * cli_machine_unit(o->rotary, k));
    for (k = 0; k < c->nj; k++)
        fprintf(f, ",%.17g", o->pos[k] * cli_machine_unit(o->rotary, k));
    for (k = 0; k < c->nj; k++)
        fprintf(f, ",%.17g", o->motor_pos[k] * cli_machine_unit(o->rotary, k));
    for (k = 0; k < c->nj; k++)
        fprintf(f, ",%.0f", row[c->count[k]]);
    for (k = 0; k < c->nj; k++)
        fprintf(f, ",%d", o->count[k]);
    for (k = 0; k < p->noutputs; k++)
        if (csv_extra(p, k) && c->extra[k] >= 0)
            fprintf(f, ",%.17g", row[c->extra[k]] * p->outputs[k].hal_scale);
    for (k = 0; k < p->noutputs; k++)
        if (csv_extra(p, k) && c->extra[k] >= 0)
            fprintf(f, ",%.17g", o->extra[k] * p->outputs[k].hal_scale);
    fprintf(f, ",%.17g", c->pos_cmd >= 0 && o->tool_error >= 0.0 ? o->tool_error * HG_MM_PER_M : -1.0);
    fprintf(f, ",%d,%d", (int)row[c->fault_code], o->fault_code);
    if (fe)
        for (w = 0; w < 2; w++)
            for (k = 0; k < c->nj; k++)
                fprintf(f, ",%.17g,%.17g", fe[w][k], volts[w][k]);
    fputc('\n', f);
}

/* The CSV header (the plant's outputs by their short names: x, a, ...;
 * a joint's columns end in its machine unit, _mm or _deg as rotary says). */
static void csv_header(FILE *f, const replay_cols *c, int with_loop, unsigned rotary)
{
    const hg_plant *p = c->plant;
    int k, w;
    fprintf(f, "sample,t_s");
    for (k = 0; k < c->nj; k++)
        fprintf(f, ",z%d_rec_%s", k, cli_machine_unit_name(rotary, k));
    for (k = 0; k < c->nj; k++)
        fprintf(f, ",z%d_%s", k, cli_machine_unit_name(rotary, k));
    for (k = 0; k < c->nj; k++)
        fprintf(f, ",zm%d_%s", k, cli_machine_unit_name(rotary, k));
    for (k = 0; k < c->nj; k++)
        fprintf(f, ",count%d_rec", k);
    for (k = 0; k < c->nj; k++)
        fprintf(f, ",count%d", k);
    for (w = 0; w < 2; w++)
        for (k = 0; k < p->noutputs; k++)
            if (csv_extra(p, k) && c->extra[k] >= 0) {
                const char *r = p->outputs[k].rec_name, *dash = strchr(r, '-');
                fprintf(f, ",%s%s", dash ? dash + 1 : r, w ? "" : "_rec");
            }
    fprintf(f, ",tool_error_mm,fault_code_rec,fault_code");
    if (with_loop) {
        for (k = 0; k < c->nj; k++)
            fprintf(f, ",ferror%d_rec_%s,volts%d_rec", k, cli_machine_unit_name(rotary, k), k);
        for (k = 0; k < c->nj; k++)
            fprintf(f, ",ferror%d_%s,volts%d", k, cli_machine_unit_name(rotary, k), k);
    }
    fputc('\n', f);
}

/* Run the source tree's tools/plot_replay.py on csv -> png; the f-error
 * window from..to when from >= 0. */
static int run_plot(const char *csv, const char *png, long from, long to)
{
    char script[4096], python[4096], a_from[24], a_to[24];
    int status = 0;
    pid_t pid;
    if (cli_tree_path("tools/plot_replay.py", script, sizeof script) || access(script, R_OK) != 0) {
        fprintf(stderr, "hexaglide replay: --plot: tools/plot_replay.py not found beside this program; the CSV "
                "is in %s\n", csv);
        return 1;
    }
    if (cli_find_python("replay", "numpy matplotlib", "the plot is matplotlib's", python, sizeof python)) {
        fprintf(stderr, "hexaglide replay: no plot; the CSV is in %s\n", csv);
        return 1;
    }
    snprintf(a_from, sizeof a_from, "%ld", from);
    snprintf(a_to, sizeof a_to, "%ld", to);
    fflush(stdout);
    pid = fork();
    if (pid == 0) {
        char *args[] = {python, script, (char *)csv, (char *)png, a_from, a_to, 0};
        if (from < 0)
            args[4] = 0;
        execv(args[0], args);
        _exit(127);
    }
    if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "hexaglide replay: the plot failed (%s %s %s %s); the CSV is in %s\n", python, script,
                csv, png, csv);
        return 1;
    }
    return 0;
}

/* The closed loop's config from the record: the pid settings and DAC
 * scales of its footer, the wiring its header vouches for. 0, or 1 with
 * a message saying what is missing and what to do. */
static int loop_config(const hg_record *r, const char *file, const int *col_cmd, int nj, hg_loop_config *c)
{
    char key[96], val[96];
    int k, i, nset = 0;
    while (hg_pid_setting_at(nset))
        nset++;
    hg_loop_config_default(c);
    for (k = 0; k < nj; k++)
        if (col_cmd[k] < 0) {
            fprintf(stderr, "hexaglide replay: %s has no column joint.%d.motor-pos-cmd (recorded by an older "
                    "tools/hg_record.py?): the closed-loop what-if runs the pid loops on motion's joint "
                    "commands; record again, or give --open-loop\n", file, k);
            return 1;
        }
    if (!hg_record_meta_get(r, "closed-loop", val, sizeof val) || strcmp(val, "hexaglide.hal") != 0) {
        fprintf(stderr, "hexaglide replay: %s: the recorder did not find the loops wired as "
                "configs/hexaglide.hal wires them (header '# closed-loop %s'): the closed-loop what-if "
                "would not be the loop LinuxCNC ran; give --open-loop\n", file,
                hg_record_meta_get(r, "closed-loop", val, sizeof val) ? val : "missing");
        return 1;
    }
    for (k = 0; k < nj; k++)
        for (i = 0; i < nset + 2; i++) {
            const hg_pid_setting *ps = hg_pid_setting_at(i);
            double v;
            if (ps)
                snprintf(key, sizeof key, "pid.%d.%s", k, ps->pin);
            else
                snprintf(key, sizeof key, "motenc.0.dac-%02d-%s", k, i == nset ? "gain" : "offset");
            if (!hg_record_meta_get(r, key, val, sizeof val)) {
                fprintf(stderr, "hexaglide replay: %s has no line '# %s VALUE' after its last row: the "
                        "recorder writes the pid settings there when LinuxCNC stops; a recording cut "
                        "short or from an older recorder lacks them; record again, or give --open-loop\n",
                        file, key);
                return 1;
            }
            if (cli_strtod(val, &v)) {
                fprintf(stderr, "hexaglide replay: %s: '# %s %s': not a finite number; the pid "
                        "setting is damaged (LinuxCNC had it non-finite?); fix the line, or give "
                        "--open-loop\n", file, key, val);
                return 1;
            }
            if (!ps && i == nset)         /* the DAC's gain and offset after the pid settings */
                c->output_scale[k] = v;
            else if (!ps)
                c->output_offset[k] = v;
            else if (ps->kind == HG_PID_FLAG)
                c->pid[k].error_previous_target = v != 0.0;
            else
                memcpy((char *)&c->pid[k] + ps->offset, &v, sizeof v);
        }
    return 0;
}

/* Compare the outputs of one step with the recorded row into *st; print
 * the differing fields of the first mismatch when print_first. 1 if any differs. */
static int compare_row(const hg_board_rec_field *fld, int nf, const int *col, const double *row,
                       const hg_board_rec_ctx *ctx, long n, long line, int print_first, replay_stats *st)
{
    int i, mismatch = 0;
    for (i = 0; i < nf; i++) {
        double rec, rep, d;
        if (fld[i].side != HG_BRS_OUT)
            continue;
        rec = row[col[i]];
        rep = hg_board_rec_get(fld, nf, i, ctx);
        if (!bits_differ(rec, rep))
            continue;
        d = fabs(rep - rec);
        if (strncmp(fld[i].name, "out.count-", 10) == 0 && d > (double)st->max_count_diff)
            st->max_count_diff = (long long)d;
        if (strncmp(fld[i].name, "out.z-", 6) == 0) {   /* channel k, in its machine unit */
            int k = atoi(fld[i].name + 6);
            double *max = (ctx->out->rotary >> k) & 1u ? &st->max_pos_diff_deg : &st->max_pos_diff_mm;
            double du = d * cli_machine_unit(ctx->out->rotary, k);
            if (du > *max)
                *max = du;
        }
        if (fld[i].offset >= offsetof(hg_board_outputs, extra) &&
            fld[i].offset < offsetof(hg_board_outputs, extra) + sizeof ctx->out->extra &&
            fld[i].type == HG_BRF_F64 && d > st->max_pose_diff)   /* the plant's own outputs (the head pose) */
            st->max_pose_diff = d;
        if (st->first_mismatch < 0 && print_first) {
            if (!mismatch)
                fprintf(report, "first mismatch at sample %ld (line %ld):\n", n, line);
            fprintf(report, "  %-22s recorded %.17g  replayed %.17g  difference %.3g\n", fld[i].name, rec, rep,
                   rep - rec);
        }
        mismatch = 1;
    }
    if (mismatch) {
        if (st->first_mismatch < 0)
            st->first_mismatch = n;
        st->mismatched_samples++;
    }
    return mismatch;
}

/* Add sample n of one joint (f-error mm, drive volts; w 0 recorded, 1 predicted). */
static void joint_add(joint_stats *j, int w, long n, double fe, double v)
{
    if (fabs(fe) > j->peak_mm[w]) {
        j->peak_mm[w] = fabs(fe);
        j->peak_at[w] = n;
    }
    j->sq[w] += fe * fe;
    if (fabs(v) > j->peak_v[w])
        j->peak_v[w] = fabs(v);
}

/* The per-joint lines: recorded (and predicted) peak and RMS f-error (in
 * the joint's machine unit: deg for a rotary one, bit k of rotary), peak volts. */
static void joint_report(const joint_stats *js, int nj, unsigned rotary, int whatif, long from, long to,
                         int auto_from, int latched)
{
    int k;
    fprintf(report, "f-error window: samples %ld..%ld (%s), each joint while its amplifier is enabled\n", from, to,
           !auto_from ? "--from" : latched ? "from the 2nd period after the last index latch: homing done"
                                           : "the whole record: no index latch (homing) in it");
    for (k = 0; k < nj; k++) {
        const joint_stats *j = &js[k];
        double rms0 = j->n ? sqrt(j->sq[0] / (double)j->n) : 0.0, rms1 = j->n ? sqrt(j->sq[1] / (double)j->n) : 0.0;
        const char *u = cli_machine_unit_name(rotary, k);
        if (!whatif) {
            fprintf(report, "joint %d: peak |f-error| %.6f %s (sample %ld), RMS %.6f %s, peak volts %.4f V\n", k,
                   j->peak_mm[0], u, j->peak_at[0], rms0, u, j->peak_v[0]);
            continue;
        }
        fprintf(report, "joint %d: peak |f-error| recorded %.6f %s (sample %ld), predicted %.6f %s (sample %ld)",
               k, j->peak_mm[0], u, j->peak_at[0], j->peak_mm[1], u, j->peak_at[1]);
        if (j->peak_mm[0] > 0 && j->peak_mm[0] >= 0.5 * j->count_mm) /* below the resolution: means nothing */
            fprintf(report, " %+.1f%%", 100.0 * (j->peak_mm[1] / j->peak_mm[0] - 1.0));
        else if (j->n)
            fprintf(report, " (recorded peak below half an encoder count of %.3g %s: no change in %%)", j->count_mm, u);
        fprintf(report, "; RMS recorded %.6f, predicted %.6f %s; peak volts recorded %.4f, predicted %.4f V\n",
               rms0, rms1, u, j->peak_v[0], j->peak_v[1]);
    }
}

/* One period of a closed loop: index-enable as one HAL signal (encoder-read
 * clears it after this board's latch, motion's recorded rising edge sets it,
 * a recorded fall that was not the recorded board's latch cancels it), then
 * the servo thread on the recorded commands. */
static void closed_step(hg_loop *L, int *ie, const hg_board_inputs *in_w, unsigned ie_rec,
                        unsigned prev_ie_rec, unsigned prev_latched_rec, const double *cmd,
                        const int *enable, long period, hg_loop_sample *smp)
{
    int k;
    L->in = *in_w;
    for (k = 0; k < L->joints; k++) {
        if (L->out.index_latched[k])
            ie[k] = 0;
        if ((ie_rec >> k & 1u) && !(prev_ie_rec >> k & 1u))
            ie[k] = 1;
        if (!(ie_rec >> k & 1u) && (prev_ie_rec >> k & 1u) && !(prev_latched_rec >> k & 1u))
            ie[k] = 0;
        L->in.index_enable[k] = ie[k];
    }
    (void)hg_loop_step_io(L, cmd, enable, period, smp); /* a fault shows in the outputs, as in LinuxCNC */
}

/* Median of v[0..n), sorted in place. */
static double median(double *v, int n)
{
    int i, j;
    for (i = 1; i < n; i++)
        for (j = i; j > 0 && v[j - 1] > v[j]; j--) {
            double t = v[j];
            v[j] = v[j - 1];
            v[j - 1] = t;
        }
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* One period of --spread loop l (delay SPREAD_STEP * l): until it has held
 * the idle after homing (period hold_at - 1 again) that long, it runs the
 * same periods as loop 0; then the recorded periods that late. Its peak
 * |f-error| per joint over the window into pk. */
static void spread_step(hg_loop *L, int *ie, long *lag, int l, long n, long hold_at,
                        const period_in *ring, double *pk)
{
    const period_in *p;
    hg_loop_sample smp;
    int k, hold = hold_at >= 0 && n >= hold_at && *lag < (long)SPREAD_STEP * l;
    p = &ring[(hold ? hold_at - 1 : n - *lag) % RING];
    if (hold)
        (*lag)++;
    if (p->reset && !hold)
        for (k = 0; k < L->joints; k++)
            pk[k] = 0.0;
    closed_step(L, ie, &p->in, p->ie_rec, hold ? p->ie_rec : p->prev_ie_rec, hold ? 0u : p->prev_latched_rec,
                p->cmd, p->enable, p->period, &smp);
    for (k = 0; k < L->joints; k++)
        if ((p->win >> k & 1u) && fabs(smp.ferror_mm[k]) > pk[k])
            pk[k] = fabs(smp.ferror_mm[k]);
}

/* 1 if variants a and b of plant p have the same channels and parameter
 * table (names in order): a what-if --model then reads the recorded
 * block and DAC volts as the record meant them. */
static int same_params_layout(const hg_plant *p, int a, int b)
{
    hg_param_info x, y;
    int i, n = p->nparams(a);
    if (p->channels(a) != p->channels(b) || p->nparams(b) != n)
        return 0;
    for (i = 0; i < n; i++)
        if (p->param(a, i, &x) || p->param(b, i, &y) || strcmp(x.name, y.name) != 0)
            return 0;
    return 1;
}

/* The record's plant and model variant (in.plant and in.model of its
 * first row; format 1: the Hexaglide) and, for format 2, its parameter
 * events in the order they took effect (*ev malloc'd; free() it): one
 * pass over the rows before the replay. 0, or 1 after a message. Rows it
 * cannot read are left to the replay's own pass, which names them. */
static int prescan(const char *file, const char *buf, size_t len, int *plant, int *variant, double *model,
                   long *line0, hg_board_rec_event **ev, long *nev)
{
    static hg_record r;
    static double row[HG_RECORD_MAX_COLS];
    hg_record_error e;
    int cp = -1, cm, cs[HG_BOARD_REC_SLOTS][3], s, k;
    long cap = 0;
    double plant_rec = 0.0;            /* in.plant as recorded (for the message) */
    char named[64];
    *plant = 0;
    *variant = hg_plant_at(0)->default_variant;
    *model = *variant;
    *ev = 0;
    *nev = 0;
    *line0 = 0;
    if (hg_record_open(&r, buf, len, &e))
        return 0;
    if ((cm = hg_record_need(&r, "in.model", &e)) < 0 ||
        (r.format == 2 && (cp = hg_record_need(&r, "in.plant", &e)) < 0)) {
        fprintf(stderr, "hexaglide replay: %s: %s\n", file, e.msg);
        return 1;
    }
    if (r.format == 1) {               /* the Hexaglide; its parameters are columns */
        if (hg_record_next(&r, row, &e) == 1) {
            *model = row[cm];          /* (as recorded, for the message) */
            *variant = row[cm] >= 0 && row[cm] < 1000 ? (int)row[cm] : -1;
            *line0 = r.line;
        }
        return 0;
    }
    for (s = 0; s < HG_BOARD_REC_SLOTS; s++)
        for (k = 0; k < 3; k++) {
            static const char *const part[3] = {"entry", "value", "age"};
            char name[32];
            snprintf(name, sizeof name, "in.pev-%d-%s", s, part[k]);
            if ((cs[s][k] = hg_record_need(&r, name, &e)) < 0) {
                fprintf(stderr, "hexaglide replay: %s: %s\n", file, e.msg);
                return 1;
            }
        }
    while (hg_record_next(&r, row, &e) == 1) {
        unsigned long n = (unsigned long)row[0];
        if (n == 0) {
            plant_rec = row[cp];
            *plant = row[cp] >= 0 && row[cp] < 1000 && row[cp] == floor(row[cp]) ? (int)row[cp] : -1;
            *model = row[cm];
            *variant = row[cm] >= 0 && row[cm] < 1e6 ? (int)row[cm] : -1;
            *line0 = r.line;
        }
        for (s = 0; s < HG_BOARD_REC_SLOTS; s++) {
            hg_board_rec_event x;
            if (!hg_board_rec_event_of(row[cs[s][0]], row[cs[s][1]], row[cs[s][2]], n, &x))
                continue;
            if (*nev == cap) {
                hg_board_rec_event *m = realloc(*ev, (size_t)(cap = cap ? 2 * cap : 1024) * sizeof *m);
                if (!m) {
                    fprintf(stderr, "hexaglide replay: out of memory\n");
                    return 1;
                }
                *ev = m;
            }
            (*ev)[(*nev)++] = x;
        }
    }
    if (!hg_plant_at(*plant)) {
        fprintf(stderr, "hexaglide replay: %s: in.plant %.17g is not a plant this program knows (a newer "
                "recorder?); use that version's hexaglide\n", file, plant_rec);
        return 1;
    }
    if (hg_record_meta_get(&r, "plant", named, sizeof named) == 1 && hg_plant_find(named) != *plant) {
        fprintf(stderr, "hexaglide replay: %s: its header says '# plant %s' but its rows are of the %s "
                "(in.plant %d): the file was edited or put together from two records; record again\n", file,
                named, hg_plant_at(*plant)->name, *plant);
        return 1;
    }
    return 0;
}

/* Say why the what-if board faulted where the recorded one did not; 1
 * when the changed parameters cannot be integrated at all (the what-if
 * stops: nothing after it would mean anything), 0 for a fault the changed
 * machine runs into (a prediction: it goes on, drives off, as the board does). */
static int whatif_fault(const hg_board *wb, const hg_board_outputs *o, long n, long period_ns)
{
    char what[HG_PLANT_TEXT_LEN + HG_BOARD_TEXT_LEN]; /* room for either text */
    if (o->fault_cause == HG_FAULT_STIFF) {
        char remedy[HG_BOARD_TEXT_LEN];
        hg_board_describe_stiffness(wb, o, period_ns, 0, what);
        hg_board_stiff_remedy(o, "--integrator", 0, remedy);   /* the record's period stays */
        fprintf(stderr, "hexaglide replay: sample %ld: the changed board cannot integrate its parameters: %s: %s "
                "even with %u substeps; give (--set) %s\n", n, what, hg_strerror(o->fault_code),
                HG_SUBSTEPS_MAX, remedy);
        return 1;
    }
    hg_board_plant(wb)->describe(&o->fault_report, 0, what);
    fprintf(stderr, "hexaglide replay: sample %ld: the changed machine faulted (code %d): %s; its drives are off "
            "from here on (the recorded one's were not)\n", n, o->fault_code,
            what[0] ? what : hg_strerror(o->fault_code));
    return 0;
}

/* 1 if the variant is one of plant's, else 0 after a message naming the record, its line and
 * the value recorded there (model: in.model as a number, whatever variant it maps to). */
static int variant_known(const char *file, long line, int plant, int variant, double model)
{
    if (hg_plant_nparams_at(plant, variant))
        return 1;
    fprintf(stderr, "hexaglide replay: %s: line %ld: in.model %.17g is not a model of the %s; the record is "
            "damaged\n", file, line, model, hg_plant_name_at(plant));
    return 0;
}

int cmd_replay(int argc, char **argv)
{
    replay_opts o;
    char *buf = 0, text[64];
    size_t len = 0;
    static hg_record r;
    static hg_board bx, b;            /* the recorded run replayed; the open-loop what-if */
    static hg_loop L;                 /* the closed-loop what-if */
    int ie[HG_CHANNELS_MAX] = {0};    /* its index-enable signals */
    static hg_loop Ls[REPLAY_MAX_SPREAD]; /* --spread loops 1..K-1 (0 is L) */
    static int ies[REPLAY_MAX_SPREAD][HG_CHANNELS_MAX];
    static long lag[REPLAY_MAX_SPREAD];
    static double spk[REPLAY_MAX_SPREAD][HG_CHANNELS_MAX];
    static period_in ring[RING];
    long hold_at = -1, last_latch = -1, still = 0;
    static hg_board_rec_field fld[HG_BOARD_REC_MAX];
    static double row[HG_RECORD_MAX_COLS];
    static const char *why[HG_BOARD_WHY_LEN];
    int col[HG_BOARD_REC_MAX], col_period = 0, col_model = 0, col_plant = -1, col_fp = -1;
    int col_latched = -1, has_cmd = 1;
    replay_cols cols;
    hg_record_error e;
    hg_board_inputs in, in_w;
    hg_board_outputs out_w, out_x;
    hg_board_rec_ctx ctx;
    hg_board_params bp0;
    hg_board_rec_event *ev = 0;
    long nev = 0, next_ev = 0, line0;
    double model_rec;                 /* in.model as recorded */
    hg_loop_config lc;
    hg_loop_check_report lrep;
    int set_idx[REPLAY_MAX_SETS];
    double set_val[REPLAY_MAX_SETS];
    replay_stats st = {0, 0, 0.0, 0.0, -1, 0, 0.0}, stx = {0, 0, 0.0, 0.0, -1, 0, 0.0};
    joint_stats js[HG_CHANNELS_MAX];
    double prev_cmd[HG_CHANNELS_MAX] = {0}, fe[2][HG_CHANNELS_MAX], volts[2][HG_CHANNELS_MAX];
    int nf, np, i, k, rc, whatif, closed, kind = -1, status = 0, plant, variant, variant_w = -1, nj;
    unsigned prev_ie_rec = 0, prev_latched_rec = 0, jmask;
    long period = 0, win_from = 0;
    int latched = 0;                  /* the f-error window starts after an index latch */
    long settings_from = 0, first_enabled = -1, last_enabled = -1;
    FILE *csv = 0;
    int csv_header_written = 0;
    char csv_auto[4096], png_auto[4000], deg[40] = "";
    cli_out csv_out;
    const char *csv_path;
    const hg_plant *pl;

    rc = parse_opts(argc, argv, &o);
    if (rc)
        return rc < 0 ? 0 : rc;
    whatif = o.nset > 0 || o.model || o.substeps > 0 || o.integrator >= 0;
    closed = whatif && !o.open_loop;
    if (o.open_loop && !whatif) {
        fprintf(stderr, "hexaglide replay: --open-loop is for a what-if: give --set, --model, --substeps "
                "or --integrator too\n");
        return 2;
    }
    if (o.spread > 1 && !closed) {
        fprintf(stderr, "hexaglide replay: --spread is for the closed-loop what-if: give --set, --model, "
                "--substeps or --integrator, without --open-loop\n");
        return 2;
    }
    if (o.plant && cli_plant("replay", o.plant) < 0)
        return 2;
    report = cli_out_is_stdout(o.csv) && o.csv ? stderr : stdout;  /* stdout holds the CSV alone */
    if (cli_out_need_file("replay", "--plot", o.plot, "the plot is a PNG file") ||
        (o.plot && cli_out_need_file("replay", "--csv", o.csv, "with --plot: the plot reads the CSV from a file")) ||
        (o.plot && cli_out_need_regular("replay", "--plot", o.plot, "the plot is a PNG file with its CSV beside it")))
        return 2;
    if (o.csv && o.plot && cli_out_same(o.csv, o.plot)) {
        fprintf(stderr, "hexaglide replay: --csv %s and --plot %s name the same file; give two files\n", o.csv,
                o.plot);
        return 2;
    }
    if (cli_out_is_input("replay", "--csv", o.csv, "", o.file) || cli_out_is_input("replay", "--plot", o.plot, "", o.file))
        return 2;
    if (cli_read_file("replay", o.file, "a record file (tools/hg_record.py); split larger recordings", REPLAY_MAX_BYTES, &buf, &len))
        return 1;
    rc = hg_record_open(&r, buf, len, &e);
    if (rc) {
        fprintf(stderr, "hexaglide replay: %s: %s\n", o.file, e.msg);
        free(buf);
        return 1;
    }
    if (prescan(o.file, buf, len, &plant, &variant, &model_rec, &line0, &ev, &nev) ||
        !variant_known(o.file, line0, plant, variant, model_rec)) {
        free(buf);
        free(ev);
        return 1;
    }
    pl = hg_plant_at(plant);
    np = pl->nparams(variant);
    if (o.plant && hg_plant_find(o.plant) != plant) {
        fprintf(stderr, "hexaglide replay: %s is a record of the %s (in.plant %d), not of the %s: a replay "
                "runs the machine that was recorded; drop --plant or give the right record\n", o.file,
                pl->name, plant, o.plant);
        status = 2;
    }
    if (!status && o.model && (variant_w = cli_variant("replay", plant, o.model)) < 0)
        status = 2;
    if (!status && variant_w >= 0 && !same_params_layout(pl, variant, variant_w)) {
        char rec_name[HG_PLANT_TEXT_LEN];
        fprintf(stderr, "hexaglide replay: --model %s: the record's model is %s (%d channels, %d parameters); a "
                "what-if --model runs the recorded DAC volts and parameters, so its model needs the same channels "
                "with the same parameters (a serial machine: as many axes, each linear or rotary as recorded)\n",
                o.model, cli_variant_name(plant, variant, rec_name), pl->channels(variant), np);
        status = 2;
    }
    if (!status && parse_sets(&o, plant, variant_w >= 0 ? variant_w : variant, set_idx, set_val))
        status = 2;
    if (!status && o.nset)
        status = sets_valid(&o, o.set, plant, variant_w >= 0 ? variant_w : variant, r.format, ev, nev, set_idx,
                            set_val);
    if (status) {
        free(buf);
        free(ev);
        return status;
    }
    nf = hg_board_rec_fields(fld, HG_BOARD_REC_MAX, plant, variant, r.format);
    if (nf < 0) {
        fprintf(stderr, "hexaglide replay: internal: record table too long\n");
        free(buf);
        free(ev);
        return 1;
    }
    rc = hg_board_rec_bind(&r, fld, nf, col, &e);
    if (rc) {
        fprintf(stderr, "hexaglide replay: %s: %s\n", o.file, e.msg);
        free(buf);
        free(ev);
        return 1;
    }
    memset(&cols, 0, sizeof cols);
    memset(&out_x, 0, sizeof out_x);   /* (the rows start at sample 0, which builds the boards) */
    memset(&in, 0, sizeof in);
    cols.plant = pl;
    for (k = 0; k < pl->channels(variant); k++) {
        snprintf(text, sizeof text, "out.z-%d", k);
        cols.z[k] = hg_record_column(&r, text);
        snprintf(text, sizeof text, "out.count-%02d", k);
        cols.count[k] = hg_record_column(&r, text);
        snprintf(text, sizeof text, "joint.%d.motor-pos-cmd", k);
        cols.cmd[k] = hg_record_column(&r, text);
    }
    for (nj = 0; nj < pl->channels(variant) && cols.cmd[nj] >= 0; nj++)
        ;                              /* the joints whose commands were recorded */
    has_cmd = nj > 0;
    if (!has_cmd)
        nj = pl->channels(variant);
    cols.nj = nj;
    jmask = (1u << nj) - 1u;
    for (k = 0; k < pl->noutputs && k < HG_PLANT_EXTRA_MAX; k++) {
        cols.extra[k] = -1;
        if (csv_extra(pl, k)) {
            snprintf(text, sizeof text, "out.%s", pl->outputs[k].rec_name);
            cols.extra[k] = hg_record_column(&r, text);
        }
    }
    cols.fault_code = hg_record_column(&r, "out.fault-code");
    cols.pos_cmd = hg_record_column(&r, "in.pos-cmd-0");
    col_latched = hg_record_column(&r, "out.index-latched");
    {
        int used = nf + (has_cmd ? nj : 0);
        if (r.ncols - 1 > used)
            fprintf(stderr, "hexaglide replay: note: %s has %d columns replay does not use (extra pins, or "
                    "recorded by a newer board)\n", o.file, r.ncols - 1 - used);
    }
    for (i = 0; i < nf; i++) {         /* the step's other arguments */
        if (fld[i].side == HG_BRS_PERIOD)
            col_period = col[i];
        if (fld[i].side == HG_BRS_MODEL)
            col_model = col[i];
        if (fld[i].side == HG_BRS_PLANT)
            col_plant = col[i];
        if (fld[i].side == HG_BRS_PARAMS_FP)
            col_fp = col[i];
    }
    if (closed && !has_cmd) {
        char how[64];
        if (hg_record_meta_get(&r, "closed-loop", how, sizeof how) && strncmp(how, "no", 2) == 0)
            fprintf(stderr, "hexaglide replay: %s is an open-loop run (header '# closed-loop %s'): no pid "
                    "loops and no joint commands to run a closed-loop what-if on; give --open-loop\n", o.file, how);
        else
            fprintf(stderr, "hexaglide replay: %s has no column joint.0.motor-pos-cmd (recorded by an older "
                    "tools/hg_record.py?): the closed-loop what-if runs the pid loops on motion's joint "
                    "commands; record again, or give --open-loop\n", o.file);
        free(buf);
        free(ev);
        return 2;
    }
    if (closed && loop_config(&r, o.file, cols.cmd, nj, &lc)) {
        free(buf);
        free(ev);
        return 1;
    }
    if (hg_record_meta_get(&r, "settings-from-sample", text, sizeof text))
        settings_from = strtol(text, 0, 10);
    memset(js, 0, sizeof js);

    if (whatif && !o.csv && !o.plot) { /* a what-if always leaves its run and plot */
        snprintf(png_auto, sizeof png_auto, "%s.whatif.png", o.file);
        o.plot = png_auto;
        fprintf(stderr, "hexaglide replay: what-if: writing %s.csv and %s\n", png_auto, png_auto);
    }
    csv_path = o.csv;
    if (!csv_path && o.plot) {         /* the plot needs the CSV: put it beside the PNG */
        snprintf(csv_auto, sizeof csv_auto, "%s.csv", o.plot);
        csv_path = csv_auto;
    }
    if (csv_path) {                    /* written through a temporary file and a rename */
        if (cli_out_open("replay", csv_path, &csv_out)) {
            free(buf);
            free(ev);
            return 1;
        }
        csv = csv_out.f;               /* its header with the first row: the board knows the units then */
    }

    while ((rc = hg_record_next(&r, row, &e)) == 1) {
        long n = (long)row[0];
        int enable[HG_CHANNELS_MAX];
        unsigned ie_rec, latched_rec;
        if (n > 0 && (row[col_model] != model_rec || (col_plant >= 0 && row[col_plant] != plant))) {
            fprintf(stderr, "hexaglide replay: %s: sample %ld (line %ld): %s %.17g differs from the first row's "
                    "%.17g; the board chooses its machine at load, so it cannot change in a run: the record is "
                    "damaged (it replays only up to here)\n", o.file, n, r.line,
                    row[col_model] != model_rec ? "in.model" : "in.plant",
                    row[col_model] != model_rec ? row[col_model] : row[col_plant],
                    row[col_model] != model_rec ? model_rec : (double)plant);
            status = 1;
            break;
        }
        if (n == 0) {                  /* power-up, as at loadrt: model and defaults */
            kind = (int)row[col_model];   /* the recorded run is replayed as recorded */
            if (kind != variant) {        /* (the prescan read the same row) */
                status = 1;
                break;
            }
            /* power-up as the recording version did: its defaults (an earlier format's plant had fewer) */
            hg_board_params_default(plant, kind, &bp0);
            if (r.format < HG_BOARD_REC_FORMAT)
                pl->legacy(r.format, kind, &bp0.plant);
            rc = hg_board_init(&bx, plant, kind, &bp0);
            if (variant_w >= 0)
                kind = variant_w;
            if (!rc && whatif && !closed) {
                rc = hg_board_init(&b, plant, kind, &bp0);
                hg_board_peek(&b, &out_w);
            }
            if (closed) {
                lc.plant = plant;
                lc.variant = kind;
            }
            if (!rc && closed && hg_loop_config_check(&lc, &lrep)) {
                fprintf(stderr, "hexaglide replay: %s: the recorded %s.%d.%s = %.17g: %s; the closed-loop "
                        "what-if refuses it (give --open-loop)\n", o.file, lrep.component, lrep.joint, lrep.field,
                        lrep.value, lrep.why);
                status = 1;
                break;
            }
            if (!rc && closed)
                rc = hg_loop_init(&L, &lc, &bp0);
            for (i = 1; !rc && closed && i < o.spread; i++)
                rc = hg_loop_init(&Ls[i], &lc, &bp0);
            if (rc) {
                fprintf(stderr, "hexaglide replay: the board refused its defaults: %s\n", hg_strerror(rc));
                status = 1;
                break;
            }
            hg_board_inputs_default(&bx, &in);
            hg_board_peek(&bx, &out_x);
        }
        for (i = 0; i < nf; i++)
            hg_board_rec_set(fld, nf, i, &in, row[col[i]]);
        for (; next_ev < nev && ev[next_ev].at <= (unsigned long)n; next_ev++)  /* format 2's parameters */
            hg_board_rec_entry_set(&in.params, np, ev[next_ev].entry, ev[next_ev].value);
        if (col_fp >= 0 && (double)hg_board_rec_fingerprint(&in.params, np) != row[col_fp]) {
            fprintf(stderr, "hexaglide replay: %s: sample %ld (line %ld): the parameters in force then are not "
                    "in the record (in.params-fp does not match the events; more than %d changes waited at "
                    "once, rows are missing, or the record ends before they were sent): it replays only up to "
                    "here\n", o.file, n, r.line,
                    HG_BOARD_REC_QUEUE);
            status = 1;
            break;
        }
        period = (long)row[col_period];
        for (k = 0; k < nj; k++) {     /* the recorded run: motion's f-error, pid.N.enable */
            double fb = out_x.position[k];
            fe[0][k] = prev_cmd[k] - fb;
            enable[k] = (int)((in.dout_values >> (8 + k)) & 1u);
        }
        hg_board_step(&bx, &in, &out_x, period);
        ctx.in = &in;
        ctx.out = &out_x;
        ctx.period_ns = period;
        ctx.plant = plant;
        ctx.variant = (int)row[col_model];
        ctx.stream = 0;
        compare_row(fld, nf, col, row, &ctx, n, r.line, !whatif, &stx);
        for (k = 0; k < nj; k++)
            volts[0][k] = out_x.volts[k];
        if (whatif) {                  /* the recorded block with the user's changes on top */
            in_w = in;
            for (k = 0; k < o.nset; k++)
                in_w.params.plant.v[set_idx[k]] = set_val[k];
            if (o.substeps > 0)
                in_w.params.substeps = (unsigned)o.substeps;
            if (o.integrator >= 0)
                in_w.params.integrator = (unsigned)o.integrator;
        }
        ie_rec = 0;
        for (k = 0; k < nj; k++)
            ie_rec |= (in.index_enable[k] != 0) << k;
        latched_rec = col_latched >= 0 ? (unsigned)row[col_latched] : 0u;
        if (closed) {                  /* LinuxCNC's servo thread on the changed board */
            hg_loop_sample smp;
            double cmd[HG_CHANNELS_MAX];
            for (k = 0; k < nj; k++)
                cmd[k] = row[cols.cmd[k]];
            closed_step(&L, ie, &in_w, ie_rec, prev_ie_rec, prev_latched_rec, cmd, enable, period, &smp);
            out_w = L.out;
            for (k = 0; k < nj; k++) {
                fe[1][k] = smp.ferror_mm[k];
                volts[1][k] = out_w.volts[k];
            }
        } else if (whatif) {              /* open loop: the recorded DAC volts */
            for (k = 0; k < nj; k++)
                fe[1][k] = prev_cmd[k] - out_w.position[k];
            hg_board_step(&b, &in_w, &out_w, period);
            for (k = 0; k < nj; k++)
                volts[1][k] = out_w.volts[k];
        } else {
            out_w = out_x;
            for (k = 0; k < nj; k++) {
                fe[1][k] = fe[0][k];
                volts[1][k] = volts[0][k];
            }
        }
        if (whatif && (out_w.events & HG_EV_PARAM_REFUSED)) {
            const hg_board *wb = closed ? &L.board : &b;
            hg_bitset bad;
            int bit;
            hg_board_params_check(wb, &in_w.params, &bad, why);
            fprintf(stderr, "hexaglide replay: sample %ld: the board refused the changed parameters:", n);
            for (bit = 0; bit < HG_BOARD_WHY_LEN; bit++)
                if (hg_bitset_has(&bad, bit))
                    fprintf(stderr, " %s (%s)", hg_board_param_hal_name(wb, bit) ? hg_board_param_hal_name(wb, bit) : "?",
                            why[bit] ? why[bit] : "invalid");
            fprintf(stderr, "; the what-if stops here: change --set\n");
            status = 2;                /* the user's input, refused (as up front) */
            break;
        }
        if (whatif && (out_w.enc_scale_odd & ~out_x.enc_scale_odd)) {   /* (--set lead or counts_per_rev) */
            char name[48];
            snprintf(name, sizeof name, "sample %ld: in.enc-scale-%%02d", n);
            cli_enc_scale_notes("replay", closed ? &L.board : &b, out_w.enc_scale, nj, name);
        }
        if (whatif && (out_w.events & HG_EV_FAULT_LATCHED) && !out_x.fault &&
            whatif_fault(closed ? &L.board : &b, &out_w, n, period)) {
            status = 2;                /* the user's changes cannot run at the record's period */
            break;
        }
        if (whatif) {
            ctx.in = &in_w;
            ctx.out = &out_w;
            ctx.variant = kind;
            compare_row(fld, nf, col, row, &ctx, n, r.line, 0, &st);
        }
        if (has_cmd) {                 /* the f-error statistics */
            if (o.from < 0 && (prev_latched_rec & jmask)) {
                memset(js, 0, sizeof js); /* a latch (homing): the window starts again */
                win_from = n + 1;     /* in the period after the latch motion reports 0 */
                latched = 1;
            }
            if (o.from >= 0)
                win_from = o.from;
            for (k = 0; k < nj; k++) {
                if (!enable[k] || n < win_from)
                    continue;
                if (first_enabled < 0)
                    first_enabled = n;
                last_enabled = n;
                joint_add(&js[k], 0, n, fe[0][k], volts[0][k]);
                joint_add(&js[k], 1, n, fe[1][k], volts[1][k]);
                js[k].n++;
                js[k].count_mm = 1.0 / fabs(bx.enc_scale[k]);
            }
            for (k = 0; k < nj; k++)
                prev_cmd[k] = row[cols.cmd[k]];
        }
        if (closed && o.spread > 1) {  /* the delayed loops */
            period_in *p = &ring[n % RING];
            p->in = in_w;
            p->period = period;
            p->ie_rec = ie_rec;
            p->prev_ie_rec = prev_ie_rec;
            p->prev_latched_rec = prev_latched_rec;
            p->reset = o.from < 0 && (prev_latched_rec & jmask);
            p->win = 0;
            for (k = 0; k < nj; k++) {
                p->cmd[k] = row[cols.cmd[k]];
                p->enable[k] = enable[k];
                if (enable[k] && n >= win_from)
                    p->win |= 1u << k;
            }
            if (prev_latched_rec & jmask) {
                last_latch = n;
                still = 0;
            } else if (n > 0 && same_commands(p->cmd, ring[(n - 1) % RING].cmd, nj)) {
                still++;
            } else {
                still = 0;
            }
            if (hold_at < 0 && last_latch >= 0 && still >= SPREAD_IDLE)
                hold_at = n + 1;      /* idle after homing: the delayed loops hold period n */
            for (i = 1; i < o.spread; i++)
                spread_step(&Ls[i], ies[i], &lag[i], i, n, hold_at, ring, spk[i]);
        }
        prev_ie_rec = ie_rec;
        prev_latched_rec = latched_rec;
        if (csv && !csv_header_written) {
            csv_header(csv, &cols, has_cmd, out_w.rotary);
            csv_header_written = 1;
        }
        if (csv)
            csv_row(csv, n, row, &cols, &out_w, has_cmd ? (const double (*)[HG_CHANNELS_MAX])fe : 0,
                    (const double (*)[HG_CHANNELS_MAX])volts);
        stx.samples++;
        st.samples++;
    }
    if (rc < 0) {
        fprintf(stderr, "hexaglide replay: %s: %s\n", o.file, e.msg);
        status = 1;
    }
    if (csv && !csv_header_written)    /* no row replayed: the header alone (linear units) */
        csv_header(csv, &cols, has_cmd, 0);
    if (csv && cli_out_close("replay", &csv_out, !status))
        status = 1;
    free(buf);
    free(ev);
    if (status)
        return status;
    if (stx.samples == 0) {
        fprintf(stderr, "hexaglide replay: %s: no rows after the header: nothing recorded; was "
                "LinuxCNC's servo thread running? (docs/replay.md)\n", o.file);
        return 1;
    }
    if (closed && settings_from > 0 && first_enabled >= 0 && first_enabled < settings_from)
        fprintf(stderr, "hexaglide replay: note: the pid settings changed while the loops ran (in force "
                "from about sample %ld, the loops enabled from %ld); the closed loop uses the final ones "
                "throughout\n", settings_from, first_enabled);
    if (whatif && stx.first_mismatch >= 0)
        fprintf(stderr, "hexaglide replay: note: the recorded run does not replay bit-exact from sample %ld "
                "(run replay without options for the fields): the recorded f-errors are the replayed ones\n",
                stx.first_mismatch);
    if (has_cmd && first_enabled >= 0)
        joint_report(js, nj, out_x.rotary, whatif, win_from, last_enabled, o.from < 0, latched);
    else if (has_cmd && o.from >= stx.samples)
        fprintf(stderr, "hexaglide replay: note: --from %ld is past the record's last sample (%ld): no f-error "
                "statistics; give a --from below %ld\n", o.from, stx.samples - 1, stx.samples);
    else if (has_cmd)
        fprintf(stderr, "hexaglide replay: note: no joint's amplifier was enabled%s: no f-error statistics\n",
                o.from >= 0 ? " from --from on" : " in the window");
    else if (o.from >= 0)              /* (an option that selects nothing is said, not dropped) */
        fprintf(stderr, "hexaglide replay: note: --from %ld does nothing here: %s has no joint commands "
                "(joint.N.motor-pos-cmd), so no f-error statistics are taken\n", o.from, o.file);
    if (closed && o.spread > 1 && hold_at < 0)
        fprintf(stderr, "hexaglide replay: note: --spread: no idle after an index latch (homing) in %s: "
                "the %ld loops ran the same periods\n", o.file, o.spread);
    if (closed && o.spread > 1 && first_enabled >= 0)
        for (k = 0; k < nj; k++) {
            double v[REPLAY_MAX_SPREAD], m;
            v[0] = js[k].peak_mm[1];
            for (i = 1; i < o.spread; i++)
                v[i] = spk[i][k];
            m = median(v, (int)o.spread);
            fprintf(report, "joint %d: predicted peak |f-error| with the program started 0..%ld periods later "
                   "(%ld loops): median %.6f mm, range %.6f..%.6f mm\n", k, (o.spread - 1) * SPREAD_STEP,
                   o.spread, m, v[0], v[o.spread - 1]);
        }
    if (whatif) {
        fprintf(report, "what-if, %s\n", closed ? "closed loop: LinuxCNC's pid with the recorded settings on the "
                                        "recorded joint commands"
                                      : "open loop: the recorded DAC volts into the changed board");
        st.samples = stx.samples;
    } else {
        st = stx;
    }
    if (st.first_mismatch < 0)
        snprintf(text, sizeof text, "none (bit-exact)");
    else
        snprintf(text, sizeof text, "sample %ld (%ld samples differ)", st.first_mismatch, st.mismatched_samples);
    if (out_x.rotary)                  /* a rotary axis's difference in its own unit */
        snprintf(deg, sizeof deg, ", %.3g deg", st.max_pos_diff_deg);
    fprintf(report, "%s: samples %ld, max |count diff| %lld, max |pos diff| %.3g mm%s, max |pose diff| %.3g m/rad, "
           "first mismatch %s\n", whatif ? "what-if" : "replay", st.samples, st.max_count_diff,
           st.max_pos_diff_mm, deg, st.max_pose_diff, text);
    if (o.plot && run_plot(csv_path, o.plot, has_cmd && first_enabled >= 0 ? win_from : -1, last_enabled))
        return 1;
    return (whatif || st.first_mismatch < 0) ? 0 : 1;
}
