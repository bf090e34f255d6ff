/* cli_board.c - the machine the subcommands drive: its plant, its
 * parameters (defaults, config, --set) and the board (hg_board.h), naming
 * every refused field. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "hg_errors.h"
#include "hg_units.h"

int cli_plant(const char *cmd, const char *name)
{
    int i, p = name ? hg_plant_find(name) : 0;
    if (p >= 0)
        return p;
    fprintf(stderr, "hexaglide %s: --plant %s: unknown plant; use", cmd, name);
    for (i = 0; hg_plant_at(i); i++)
        fprintf(stderr, "%s %s", i ? "," : "", hg_plant_at(i)->name);
    fprintf(stderr, "\n");
    return -1;
}

int cli_variant(const char *cmd, int plant, const char *name)
{
    const hg_plant *p = hg_plant_at(plant);
    int v = hg_plant_variant(p, name);
    if (v >= 0)
        return v;
    fprintf(stderr, "hexaglide %s: --model %s: not a model of the %s; use %s\n", cmd, name, p->name,
            p->variants_help);
    return -1;
}

const char *cli_variant_name(int plant, int variant, char *buf)
{
    if (hg_plant_at(plant)->variant_name(variant, buf, HG_PLANT_TEXT_LEN))
        snprintf(buf, HG_PLANT_TEXT_LEN, "?");
    return buf;
}

int cli_params_build(const char *cmd, int plant, int variant, const char *ini, char *const *sets, int nset,
                     hg_plant_params *v)
{
    int i;
    hg_plant_defaults_at(plant, variant, v);
    if (ini) {
        cli_ini f;
        int rc;
        if (cli_ini_read(cmd, ini, &f))
            return 2;
        rc = cli_ini_apply_plant(cmd, &f, plant, variant, v);
        cli_ini_free(&f);
        if (rc == -1)                  /* (-2: no such section, what to give said) */
            fprintf(stderr, "hexaglide %s: fix the [%s] section of %s\n", cmd, hg_plant_at(plant)->ini_section, ini);
        if (rc)
            return 2;
    }
    for (i = 0; i < nset; i++)
        if (cli_parse_set(cmd, sets[i], plant, variant, v) < 0)
            return 2;
    return 0;
}

static void report_refused(const char *cmd, int plant, int variant, const hg_bitset *bad, const char *const *why,
                           const hg_plant_params *v, const char *ini, char *const *sets, int nset);

int cli_hexaglide_params(const char *cmd, const char *ini, char *const *sets, int nset, hg_params *p)
{
    static const char *why[HG_BOARD_WHY_LEN];
    hg_bitset bad;
    hg_plant_params v;
    int i, n;
    const int variant = hg_plant_at(0)->default_variant;
    if (ini) {                         /* ik and fk take no --plant: another plant's config is not theirs */
        cli_ini f;
        if (cli_ini_read(cmd, ini, &f))
            return 2;
        i = cli_ini_plant_only(cmd, &f, 0);
        cli_ini_free(&f);
        if (i)
            return 2;
    }
    if (cli_params_build(cmd, 0, variant, ini, sets, nset, &v))
        return 2;
    hg_params_default(p);
    hg_params_table(&n);
    for (i = 0; i < n; i++)
        *hg_params_at(p, i) = v.v[i];
    memset(why, 0, sizeof why);
    if (hg_params_check_kinematics(p, &bad, why)) {   /* (what hexaglidekins refuses) */
        report_refused(cmd, 0, variant, &bad, why, &v, ini, sets, nset);
        return 2;
    }
    return 0;
}

double cli_machine_unit(unsigned rotary, int k)
{
    return (rotary >> k) & 1u ? HG_DEG_PER_RAD : HG_MM_PER_M;
}

const char *cli_machine_unit_name(unsigned rotary, int k)
{
    return (rotary >> k) & 1u ? "deg" : "mm";
}

void cli_fault_text(const hg_board *b, const hg_board_outputs *o, long period_ns,
                    char buf[HG_PLANT_TEXT_LEN + 2 * HG_BOARD_TEXT_LEN])
{
    char what[HG_PLANT_TEXT_LEN + HG_BOARD_TEXT_LEN]; /* room for either text */
    size_t n = HG_PLANT_TEXT_LEN + 2 * HG_BOARD_TEXT_LEN;
    if (o->fault_cause == HG_FAULT_STIFF) {
        char stiff[HG_BOARD_TEXT_LEN], remedy[HG_BOARD_TEXT_LEN];
        hg_board_describe_stiffness(b, o, period_ns, 0, stiff);
        hg_board_stiff_remedy(o, "--integrator", "--dt", remedy);
        snprintf(buf, n, "%s: %s even with %u substeps (code %d); give %s", stiff, hg_strerror(o->fault_code),
                 HG_SUBSTEPS_MAX, o->fault_code, remedy);
        return;
    }
    hg_board_plant(b)->describe(&o->fault_report, 0, what);
    snprintf(buf, n, "%s (code %d)%s%s", hg_strerror(o->fault_code), o->fault_code, what[0] ? ": " : "", what);
}

void cli_board_defaults(int plant, int variant, hg_board_params *bp)
{
    hg_board_params_default(plant, variant, bp);
}

/* Where parameter i of v came from, as " (...)" into buf: the last --set of
 * it, else the INI's key (value and line), else the default (without an
 * INI: the value, not changed by --set: replay's come from the record);
 * "" when unknown. */
static void origin(const char *cmd, int plant, int variant, int i, const hg_plant_params *v, const char *ini,
                   char *const *sets, int nset, char *buf, size_t len)
{
    hg_param_info e;
    int k;
    buf[0] = '\0';
    if (!sets && !ini)
        return;
    if (hg_plant_param_at(plant, variant, i, &e))
        return;
    for (k = sets ? nset - 1 : -1; k >= 0; k--) {
        const char *eq = strchr(sets[k], '=');
        if (eq && strncmp(sets[k], e.name, (size_t)(eq - sets[k])) == 0 && e.name[eq - sets[k]] == '\0') {
            snprintf(buf, len, " (--set %s)", sets[k]);
            return;
        }
    }
    if (ini && e.ini_key) {
        cli_ini f;
        const cli_ini_entry *en;
        if (cli_ini_read(cmd, ini, &f) == 0) {
            if (cli_ini_get(cmd, &f, hg_plant_at(plant)->ini_section, e.ini_key, &en) == 0 && en->value) {
                snprintf(buf, len, " ([%s]%s = %s %s, line %d of %s)", hg_plant_at(plant)->ini_section, e.ini_key,
                         en->value, e.hal_unit, en->line, ini);
                cli_ini_free(&f);
                return;
            }
            cli_ini_free(&f);
        }
    }
    if (!ini) {                        /* the default, or the record's (replay): not what --set changed */
        snprintf(buf, len, " (%.9g %s, not changed by --set)", v->v[i], e.unit);
        return;
    }
    snprintf(buf, len, " (the default, %.9g %s%s%s%s%s%s)", v->v[i], e.unit, e.ini_key ? "; " : "",
             e.ini_key ? ini : "", e.ini_key ? " does not set it" : "; no INI key sets it: give --set ",
             e.ini_key ? "" : e.name, e.ini_key ? "" : "=VALUE");
}

/* "; with what --set changed: name=value ..." on stderr (nothing without --set). */
static void print_sets(char *const *sets, int nset)
{
    int k;
    if (nset > 0)
        fprintf(stderr, "; with what --set changed:");
    for (k = 0; k < nset; k++)
        fprintf(stderr, " %s", sets[k]);
}

/* 1 when one of the nset --set values sets parameter name. */
static int set_by(const char *name, char *const *sets, int nset)
{
    size_t n = strlen(name);
    int k;
    for (k = 0; k < nset; k++)
        if (strncmp(sets[k], name, n) == 0 && sets[k][n] == '=')
            return 1;
    return 0;
}

/* One line per set bit: bit i < table length is parameter i, then the
 * board's substeps / integrator bits; with ini or sets, where each refused
 * parameter's value came from. */
static void report_refused(const char *cmd, int plant, int variant, const hg_bitset *bad, const char *const *why,
                           const hg_plant_params *v, const char *ini, char *const *sets, int nset)
{
    int i;
    for (i = 0; i < HG_BOARD_WHY_LEN; i++) {
        hg_param_info e;
        char from[600] = "";
        int is_param;
        if (!hg_bitset_has(bad, i))
            continue;
        is_param = hg_plant_param_at(plant, variant, i, &e) == 0;
        if (is_param && v)
            origin(cmd, plant, variant, i, v, ini, sets, nset, from, sizeof from);
        fprintf(stderr, "hexaglide %s: bad parameter '%s'%s: %s", cmd,
                is_param ? e.name : i == HG_BOARD_BIT_SUBSTEPS ? "--substeps" : "--integrator", from,
                why[i] ? why[i] : "invalid");
        if (is_param && strncmp(from, " (--set ", 8) != 0) /* a rule between parameters */
            print_sets(sets, nset);
        fputc('\n', stderr);
    }
}

int cli_params_check_from(const char *cmd, int plant, int variant, const hg_plant_params *v, const char *ini,
                          char *const *sets, int nset)
{
    static const char *why[HG_BOARD_WHY_LEN];
    hg_bitset bad;
    memset(why, 0, sizeof why);
    hg_bitset_clear(&bad);
    if (!hg_plant_at(plant)->check(variant, v, &bad, why))
        return 0;
    report_refused(cmd, plant, variant, &bad, why, v, ini, sets, nset);
    return 1;
}

/* Storage for a board of plant and variant, not yet built, when block p (0:
 * the defaults) passes the board's checks; else 0 after a message per field. */
static hg_board *board_storage(const char *cmd, int plant, int variant, const hg_board_params *p)
{
    static const char *why[HG_BOARD_WHY_LEN];
    hg_bitset bad;
    hg_board *b = calloc(1, sizeof *b);
    if (!b) {
        fprintf(stderr, "hexaglide %s: out of memory\n", cmd);
        return 0;
    }
    b->plant = plant;                 /* the checks need the plant and variant */
    b->variant = variant;
    if (p && hg_board_params_check(b, p, &bad, why)) {
        report_refused(cmd, plant, variant, &bad, why, 0, 0, 0, 0);
        free(b);
        return 0;
    }
    return b;
}

/* 0 when rc (hg_board_init's) built the board, else 1 after saying why. */
static int build_failed(const char *cmd, int rc)
{
    if (rc)
        fprintf(stderr, "hexaglide %s: cannot build the machine: %s (code %d)\n", cmd, hg_strerror(rc), rc);
    return rc != 0;
}

hg_board *cli_board_new(const char *cmd, int plant, int variant, const hg_board_params *p)
{
    hg_board *b = board_storage(cmd, plant, variant, p);
    if (b && build_failed(cmd, hg_board_init(b, plant, variant, p))) {
        free(b);
        return 0;
    }
    return b;
}

int cli_board_integrable(const char *cmd, int plant, int variant, const hg_board_params *p, long period_ns,
                         char *const *sets, int nset)
{
    hg_board *b = board_storage(cmd, plant, variant, p);
    hg_board_inputs in;
    hg_board_outputs out;
    int rc;
    if (!b)
        return 1;
    rc = hg_board_integrable(b, &in, plant, variant, p, period_ns, &out);   /* builds it, runs a period */
    if (rc == HG_ERR_STIFF) {
        char what[HG_PLANT_TEXT_LEN + 2 * HG_BOARD_TEXT_LEN];
        hg_param_info e;
        cli_fault_text(b, &out, period_ns, what);
        fprintf(stderr, "hexaglide %s: %s", cmd, what);
        if (hg_plant_param_at(plant, variant, out.stiff_param, &e) != 0 || !set_by(e.name, sets, nset))
            print_sets(sets, nset);
        fputc('\n', stderr);
    } else {
        build_failed(cmd, rc);
    }
    free(b);
    return rc != 0;
}

void cli_enc_scale_notes(const char *cmd, const hg_board *b, const double *scale, int n, const char *what)
{
    char why[HG_BOARD_TEXT_LEN], name[64], v[CLI_NUM_LEN];
    int k;
    for (k = 0; k < n; k++)
        if (!hg_board_enc_scale_fits(b, k, scale[k])) {
            hg_board_describe_enc_scale(b, k, scale[k], why);
            snprintf(name, sizeof name, what, k);
            fprintf(stderr, "hexaglide %s: warning: %s = %s %s\n", cmd, name, cli_num(scale[k], v), why);
        }
}

int cli_whole(double x, double *n)
{
    *n = floor(x + 0.5);
    return fabs(x - *n) <= CLI_WHOLE_ULPS * DBL_EPSILON * (fabs(x) > 1.0 ? fabs(x) : 1.0);
}

int cli_parse_period(const char *cmd, double dt, long *period_ns)
{
    double ns = dt * 1e9, whole;
    char v[CLI_NUM_LEN], n[CLI_NUM_LEN], lo[CLI_NUM_LEN], hi[CLI_NUM_LEN];
    if (!(ns >= 0.5 && ns < (double)HG_PERIOD_MAX_NS + 0.5) || !cli_whole(ns, &whole) || whole < 1.0 ||
        whole > (double)HG_PERIOD_MAX_NS) {
        if (ns >= 1.0 && ns <= (double)HG_PERIOD_MAX_NS)     /* in range: not whole */
            fprintf(stderr, "hexaglide %s: --dt %s s is %s ns: the board's period is a whole number of "
                            "nanoseconds; give %s or %s\n", cmd, cli_num(dt, v), cli_num(ns, n),
                    cli_num(floor(ns) * 1e-9, lo), cli_num(ceil(ns) * 1e-9, hi));
        else
            fprintf(stderr, "hexaglide %s: --dt must lie in [1e-9, %g] s (the board's period, whole "
                            "nanoseconds), got %s\n", cmd, (double)HG_PERIOD_MAX_NS * 1e-9, cli_num(dt, v));
        return -1;
    }
    *period_ns = (long)whole;
    return 0;
}

int cli_whole_periods(const char *cmd, const char *opt, double value, double unit_s, const char *unit,
                      long period_ns, long min, long max, long *n)
{
    double period_s = (double)period_ns * 1e-9, periods = value * unit_s * 1e9 / (double)period_ns, r;
    double lower = floor(periods), upper = ceil(periods);
    char v[CLI_NUM_LEN], p[CLI_NUM_LEN], x[CLI_NUM_LEN], lo[CLI_NUM_LEN], hi[CLI_NUM_LEN];
    cli_num(value, v);
    cli_num(period_s, p);
    if (!(periods <= (double)max + 0.5)) {   /* (also an overflow to inf: its number never printed) */
        fprintf(stderr, "hexaglide %s: %s %s %s is more than the %ld periods of %s s allowed (%s %s at most); give "
                        "a shorter %s or a longer --dt\n", cmd, opt, v, unit, max, p,
                cli_num((double)max * period_s / unit_s, hi), unit, opt);
        return -1;
    }
    if (cli_whole(periods, &r) && r >= (double)min) {
        *n = (long)r;
        return 0;
    }
    cli_num(periods, x);
    if (upper <= (double)min) {        /* (below min: only min itself is near) */
        char least[48] = "one servo period";
        if (min != 1)
            snprintf(least, sizeof least, "%ld servo periods", min);
        fprintf(stderr, "hexaglide %s: %s %s %s is shorter than %s of %s s (%s periods); give %s\n", cmd, opt, v,
                unit, least, p, x, cli_num((double)min * period_s / unit_s, hi));
    } else {                           /* the whole numbers either side (upper within max) */
        cli_num(lower * period_s / unit_s, lo);
        cli_num(upper * period_s / unit_s, hi);
        fprintf(stderr, "hexaglide %s: %s %s %s is %s periods of %s s: a run is a whole number of periods; "
                        "give %s%s%s\n", cmd, opt, v, unit, x, p, lo, upper <= (double)max ? " or " : "",
                upper <= (double)max ? hi : "");
    }
    return -1;
}
