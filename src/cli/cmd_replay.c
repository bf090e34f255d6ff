/* cmd_replay.c - the replay subcommand: re-run a recorded LinuxCNC run
 * (tools/hg_record.py) through hg_board, period by period, and compare
 * the outputs with the recorded ones; or, with --set/--model/--substeps/
 * --integrator, run the same inputs into a changed board (what-if) and
 * write both runs side by side (docs/replay.md). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "cli.h"
#include "hg_board.h"
#include "hg_board_rec.h"
#include "hg_errors.h"
#include "hg_record.h"
#include "hg_units.h"

#define REPLAY_MAX_SETS 64
#define REPLAY_MAX_BYTES (4LL << 30)  /* refuse record files above 4 GiB */

typedef struct {
    const char *file, *csv, *plot, *model;
    const char *set[REPLAY_MAX_SETS];
    int nset;
    long substeps;                    /* -1: as recorded */
    int integrator;                   /* -1: as recorded */
} replay_opts;

/* What the comparison found. */
typedef struct {
    long samples;
    long long max_count_diff;
    double max_pos_diff_mm, max_pose_diff;
    long first_mismatch;              /* sample, -1 if none */
    long mismatched_samples;
} replay_stats;

const char cli_usage_replay[] =
    "usage: hexaglide replay FILE [--csv OUT] [--plot PNG] [--set name=value]...\n"
    "                        [--model NAME] [--substeps N] [--integrator NAME]\n"
    "       hexaglide replay --list-columns   (the record pin set)\n"
    "FILE: a record of tools/hg_record.py (docs/replay.md). Without --set, --model,\n"
    "--substeps, --integrator: replays and compares, exit 0 only if bit-exact.\n"
    "With them (what-if): the same inputs into the changed board (written to\n"
    "FILE.whatif.png.csv and plotted to FILE.whatif.png unless --csv/--plot say\n"
    "otherwise); --set takes the spec name and SI unit (hexaglide sim --list-params).\n"
    "--plot runs tools/plot_replay.py under the first python3 that imports numpy and\n"
    "matplotlib ($HEXAGLIDE_PYTHON, else $PATH).\n";

/* The record pin set: one line per column, name, HAL type, direction. */
static void list_columns(void)
{
    static hg_board_rec_field f[HG_BOARD_REC_MAX];
    static const char *const type[] = {"float", "s32", "u32", "bit", "u32"};
    int i, n = hg_board_rec_fields(f, HG_BOARD_REC_MAX);
    for (i = 0; i < n; i++)
        printf("%-28s %-5s %s%s\n", f[i].name, type[f[i].type],
               f[i].side == HG_BRS_OUT ? "output, compared" : "input of hg_board_step",
               f[i].type == HG_BRF_PACK ? ", bits packed"
               : f[i].nonfinite ? ", 0 when NaN/inf (then in in.nonfinite-*)"
               : f[i].side == HG_BRS_NFMASK ? ", 2 bits per NaN/inf-capable input" : "");
}

enum { OPT_CSV, OPT_PLOT, OPT_SET, OPT_MODEL, OPT_SUBSTEPS, OPT_INTEGRATOR, OPT_LIST };
static const cli_opt replay_options[] = {
    {"--csv", 1}, {"--plot", 1}, {"--set", 1}, {"--model", 1}, {"--substeps", 1}, {"--integrator", 1},
    {"--list-columns", 0}, {0, 0},
};

/* Parse the options; 0, 2 (usage error, message printed), -1 (done: listed or --help). */
static int parse_opts(int argc, char **argv, replay_opts *o)
{
    cli_args a;
    const char *v;
    int opt;
    memset(o, 0, sizeof *o);
    o->substeps = -1;
    o->integrator = -1;
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
            if (hg_model_from_name(v) < 0) {
                fprintf(stderr, "hexaglide replay: --model %s unknown; use standard, reduced-joints, "
                        "reduced-cartesian or fused-cartesian\n", v);
                return 2;
            }
            o->model = v;
            break;
        case OPT_SUBSTEPS: {
            char *end = 0;
            errno = 0;
            o->substeps = strtol(v, &end, 10);
            if (end == v || *end || errno || o->substeps < 1 || o->substeps > (long)HG_SUBSTEPS_MAX) {
                fprintf(stderr, "hexaglide replay: --substeps %s: give an integer 1..%u\n", v, HG_SUBSTEPS_MAX);
                return 2;
            }
            break;
        }
        case OPT_INTEGRATOR:
            o->integrator = hg_integrator_from_name(v);
            if (o->integrator < 0) {
                fprintf(stderr, "hexaglide replay: --integrator %s unknown; use improved-euler, heun or rk4\n", v);
                return 2;
            }
            break;
        default:                       /* OPT_LIST */
            list_columns();
            return -1;
        }
    }
    if (!o->file) {
        fprintf(stderr, "hexaglide replay: give a record FILE ('hexaglide replay --help' for the usage)\n");
        return 2;
    }
    return 0;
}

/* The --set options as (offset in hg_params, value) pairs; 0 or 2 with a message. */
static int parse_sets(const replay_opts *o, unsigned long *off, double *val)
{
    int i;
    for (i = 0; i < o->nset; i++) {
        hg_params p;
        int k, np;
        const hg_param_info *t = hg_params_table(&np);
        const char *eq = strchr(o->set[i], '=');
        size_t n = eq ? (size_t)(eq - o->set[i]) : 0;
        hg_params_default(&p);
        if (cli_parse_set("replay", o->set[i], &p))
            return 2;
        for (k = 0; k < np; k++)      /* cli_parse_set found the name in this table */
            if (strlen(t[k].name) == n && strncmp(t[k].name, o->set[i], n) == 0) {
                off[i] = t[k].offset;
                memcpy(&val[i], (const char *)&p + t[k].offset, sizeof val[i]);
            }
    }
    return 0;
}

/* 1 if a and b differ in any bit. */
static int bits_differ(double a, double b)
{
    uint64_t x, y;
    memcpy(&x, &a, sizeof x);
    memcpy(&y, &b, sizeof y);
    return x != y;
}

/* One CSV row: sample, time, recorded and replayed joints (mm), counts, pose (mm, deg). */
static void csv_row(FILE *f, long n, const double *row, const int *col_z, const int *col_count,
                    const int *col_pose, const hg_board_outputs *o)
{
    int k;
    fprintf(f, "%ld,%.17g", n, o->sim_time_s);
    for (k = 0; k < 6; k++)
        fprintf(f, ",%.17g", row[col_z[k]] * HG_MM_PER_M);
    for (k = 0; k < 6; k++)
        fprintf(f, ",%.17g", o->z_m[k] * HG_MM_PER_M);
    for (k = 0; k < 6; k++)
        fprintf(f, ",%.0f", row[col_count[k]]);
    for (k = 0; k < 6; k++)
        fprintf(f, ",%d", o->count[k]);
    for (k = 0; k < 6; k++)
        fprintf(f, ",%.17g", row[col_pose[k]] * (k < 3 ? HG_MM_PER_M : HG_DEG_PER_RAD));
    for (k = 0; k < 6; k++)
        fprintf(f, ",%.17g", o->pose[k] * (k < 3 ? HG_MM_PER_M : HG_DEG_PER_RAD));
    fprintf(f, ",%d,%d\n", (int)row[col_count[6]], o->fault_code);
}

static void csv_header(FILE *f)
{
    int k;
    fprintf(f, "sample,t_s");
    for (k = 0; k < 6; k++)
        fprintf(f, ",z%d_rec_mm", k);
    for (k = 0; k < 6; k++)
        fprintf(f, ",z%d_mm", k);
    for (k = 0; k < 6; k++)
        fprintf(f, ",count%d_rec", k);
    for (k = 0; k < 6; k++)
        fprintf(f, ",count%d", k);
    for (k = 0; k < 6; k++)
        fprintf(f, ",%c_rec", "xyzabc"[k]);
    for (k = 0; k < 6; k++)
        fprintf(f, ",%c", "xyzabc"[k]);
    fprintf(f, ",fault_code_rec,fault_code\n");
}

/* Run the source tree's tools/plot_replay.py on csv -> png. */
static int run_plot(const char *csv, const char *png)
{
    char script[4096], python[4096];
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
    pid = fork();
    if (pid == 0) {
        char *args[] = {python, script, (char *)csv, (char *)png, 0};
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

int cmd_replay(int argc, char **argv)
{
    replay_opts o;
    char *buf = 0, text[64];
    size_t len = 0;
    static hg_record r;
    static hg_board b;
    static hg_board_rec_field fld[HG_BOARD_REC_MAX];
    static double row[HG_RECORD_MAX_COLS];
    int col[HG_BOARD_REC_MAX], col_z[6], col_count[7], col_pose[6], col_period = 0, col_model = 0;
    hg_record_error e;
    hg_board_inputs in;
    hg_board_outputs out;
    unsigned long set_off[REPLAY_MAX_SETS];
    double set_val[REPLAY_MAX_SETS];
    replay_stats st = {0, 0, 0.0, 0.0, -1, 0};
    int nf, i, k, rc, whatif, kind = -1, status = 0;
    long period = 0;
    FILE *csv = 0;
    cli_out csv_out;
    char csv_auto[4096], png_auto[4000];
    const char *csv_path;

    rc = parse_opts(argc, argv, &o);
    if (rc)
        return rc < 0 ? 0 : rc;
    whatif = o.nset > 0 || o.model || o.substeps > 0 || o.integrator >= 0;
    if (parse_sets(&o, set_off, set_val)) /* checked before reading the file */
        return 2;
    if (cli_read_file("replay", o.file, "a record file (tools/hg_record.py); split larger recordings", REPLAY_MAX_BYTES, &buf, &len))
        return 1;
    nf = hg_board_rec_fields(fld, HG_BOARD_REC_MAX);
    if (nf < 0) {
        fprintf(stderr, "hexaglide replay: internal: record table too long\n");
        free(buf);
        return 1;
    }
    rc = hg_record_open(&r, buf, len, &e);
    for (i = 0; rc == 0 && i < nf; i++) {
        col[i] = hg_record_need(&r, fld[i].name, &e);
        if (col[i] < 0)
            rc = e.code;
        else
            hg_record_set_kind(&r, col[i], fld[i].type == HG_BRF_F64 ? HG_REC_F64
                               : fld[i].type == HG_BRF_S32 ? HG_REC_S32
                               : fld[i].type == HG_BRF_BIT ? HG_REC_BIT : HG_REC_U32);
    }
    if (rc) {
        fprintf(stderr, "hexaglide replay: %s: %s\n", o.file, e.msg);
        free(buf);
        return 1;
    }
    if (r.ncols - 1 > nf)
        fprintf(stderr, "hexaglide replay: note: %s has %d columns this version does not use (recorded "
                "by a newer board?)\n", o.file, r.ncols - 1 - nf);
    for (k = 0; k < 6; k++) {
        snprintf(text, sizeof text, "out.z-%d", k);
        col_z[k] = hg_record_column(&r, text);
        snprintf(text, sizeof text, "out.count-%02d", k);
        col_count[k] = hg_record_column(&r, text);
        snprintf(text, sizeof text, "out.pose-%c", "xyzabc"[k]);
        col_pose[k] = hg_record_column(&r, text);
    }
    col_count[6] = hg_record_column(&r, "out.fault-code");
    for (i = 0; i < nf; i++) {         /* the step's other arguments */
        if (fld[i].side == HG_BRS_PERIOD)
            col_period = col[i];
        if (fld[i].side == HG_BRS_MODEL)
            col_model = col[i];
    }

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
            return 1;
        }
        csv = csv_out.f;
        csv_header(csv);
    }

    while ((rc = hg_record_next(&r, row, &e)) == 1) {
        long n = (long)row[0];
        int mismatch = 0;
        if (n == 0) {                  /* power-up, as at loadrt: model and defaults */
            kind = o.model ? hg_model_from_name(o.model) : (int)row[col_model];
            if (kind < 0 || kind >= HG_MODEL_COUNT) {
                fprintf(stderr, "hexaglide replay: %s: line %ld: in.model %d is not a model (0..%d); "
                        "the record is damaged, or give --model\n", o.file, r.line, kind, HG_MODEL_COUNT - 1);
                status = 1;
                break;
            }
            rc = hg_board_init(&b, (hg_model_kind)kind, 0);
            if (rc) {
                fprintf(stderr, "hexaglide replay: the board refused its defaults: %s\n", hg_strerror(rc));
                status = 1;
                break;
            }
            hg_board_inputs_default(&b, &in);
        }
        for (i = 0; i < nf; i++)
            hg_board_rec_set(fld, nf, i, &in, row[col[i]]);
        period = (long)row[col_period];
        if (whatif) {                  /* the recorded block with the user's changes on top */
            for (k = 0; k < o.nset; k++)
                memcpy((char *)&in.params.model + set_off[k], &set_val[k], sizeof set_val[k]);
            if (o.substeps > 0)
                in.params.substeps = (unsigned)o.substeps;
            if (o.integrator >= 0)
                in.params.integrator = (unsigned)o.integrator;
        }
        hg_board_step(&b, &in, &out, period);
        if (whatif && (out.events & HG_EV_PARAM_REFUSED)) {
            const char *why[HG_BOARD_WHY_LEN];
            unsigned long long mask = 0;
            int bit;
            memset(why, 0, sizeof why);
            hg_board_params_check(&in.params, &mask, why);
            fprintf(stderr, "hexaglide replay: sample %ld: the board refused the changed parameters:", n);
            for (bit = 0; bit < 64; bit++)
                if (mask & (1ull << bit))
                    fprintf(stderr, " %s (%s)", hg_board_param_hal_name(bit) ? hg_board_param_hal_name(bit) : "?",
                            why[bit] ? why[bit] : "invalid");
            fprintf(stderr, "; the run goes on with the previous set: change --set\n");
            status = 1;
            break;
        }
        for (i = 0; i < nf; i++) {
            double rec, rep, d;
            if (fld[i].side != HG_BRS_OUT)
                continue;
            rec = row[col[i]];
            rep = hg_board_rec_get(fld, nf, i, &in, &out, period, kind);
            if (!bits_differ(rec, rep))
                continue;
            d = fabs(rep - rec);
            if (strncmp(fld[i].name, "out.count-", 10) == 0 && d > (double)st.max_count_diff)
                st.max_count_diff = (long long)d;
            if (strncmp(fld[i].name, "out.z-", 6) == 0 && d * HG_MM_PER_M > st.max_pos_diff_mm)
                st.max_pos_diff_mm = d * HG_MM_PER_M;
            if (strncmp(fld[i].name, "out.pose-", 9) == 0 && d > st.max_pose_diff)
                st.max_pose_diff = d;
            if (st.first_mismatch < 0 && !whatif) {
                if (!mismatch)
                    printf("first mismatch at sample %ld (line %ld):\n", n, r.line);
                printf("  %-22s recorded %.17g  replayed %.17g  difference %.3g\n", fld[i].name, rec, rep,
                       rep - rec);
            }
            mismatch = 1;
        }
        if (mismatch) {
            if (st.first_mismatch < 0)
                st.first_mismatch = n;
            st.mismatched_samples++;
        }
        if (csv)
            csv_row(csv, n, row, col_z, col_count, col_pose, &out);
        st.samples++;
    }
    if (rc < 0) {
        fprintf(stderr, "hexaglide replay: %s: %s\n", o.file, e.msg);
        status = 1;
    }
    if (csv && cli_out_close("replay", &csv_out, 1))   /* the rows up to a failure are kept */
        status = 1;
    free(buf);
    if (status)
        return status;
    if (st.samples == 0) {
        fprintf(stderr, "hexaglide replay: %s: no rows after the header: nothing recorded; was "
                "LinuxCNC's servo thread running? (docs/replay.md)\n", o.file);
        return 1;
    }
    if (st.first_mismatch < 0)
        snprintf(text, sizeof text, "none (bit-exact)");
    else
        snprintf(text, sizeof text, "sample %ld (%ld samples differ)", st.first_mismatch, st.mismatched_samples);
    printf("%s: samples %ld, max |count diff| %lld, max |pos diff| %.3g mm, max |pose diff| %.3g m/rad, "
           "first mismatch %s\n", whatif ? "what-if" : "replay", st.samples, st.max_count_diff,
           st.max_pos_diff_mm, st.max_pose_diff, text);
    if (o.plot && run_plot(csv_path, o.plot))
        return 1;
    return (whatif || st.first_mismatch < 0) ? 0 : 1;
}
