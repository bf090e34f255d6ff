/* cli_parse.c - argument parsing shared by the subcommands: the option
 * scanner (--opt value, --opt=value, --help), numbers, lists, --set. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "hg_text.h"

void cli_args_init(cli_args *a, const char *cmd, const char *usage, const cli_opt *opts, int argc,
                   char **argv)
{
    a->cmd = cmd;
    a->usage = usage;
    a->opts = opts;
    a->argc = argc;
    a->argv = argv;
    a->i = 0;
    a->only_positional = 0;
    memset(a->given, 0, sizeof a->given);
    memset(a->seen, 0, sizeof a->seen);
}

/* k, or CLI_BAD after a message when once-only option k was given before (value v now). */
static int once(cli_args *a, int k, const char *v)
{
    const cli_opt *o = &a->opts[k];
    if (o->has_value == CLI_REPEAT || k >= CLI_MAX_OPTS)
        return k;
    if (a->given[k]) {
        fprintf(stderr, "hexaglide %s: %s given twice (%s and %s); give it once\n", a->cmd, o->name,
                a->given[k], v);
        return CLI_BAD;
    }
    a->given[k] = v;
    return k;
}

int cli_next(cli_args *a, const char **value)
{
    const char *arg, *eq;
    size_t len;
    int k;
    *value = 0;
    if (a->i >= a->argc)
        return CLI_DONE;
    arg = a->argv[a->i++];
    if (!a->only_positional && strcmp(arg, "--") == 0) {   /* the rest is positional */
        a->only_positional = 1;
        return cli_next(a, value);
    }
    /* "-5" and "-" are values, not options: only "--name" and -h are options */
    if (a->only_positional || strncmp(arg, "--", 2) != 0) {
        if (!a->only_positional && strcmp(arg, "-h") == 0) {
            fputs(a->usage, stdout);
            return CLI_HELP;
        }
        *value = arg;
        return CLI_ARG;
    }
    eq = strchr(arg, '=');
    len = eq ? (size_t)(eq - arg) : strlen(arg);
    if (len == 6 && strncmp(arg, "--help", 6) == 0 && !eq) {
        fputs(a->usage, stdout);
        return CLI_HELP;
    }
    for (k = 0; a->opts && a->opts[k].name; k++) {
        const cli_opt *o = &a->opts[k];
        if (strlen(o->name) != len || strncmp(o->name, arg, len) != 0)
            continue;
        if (k < CLI_MAX_OPTS)
            a->seen[k] = 1;
        if (!o->has_value) {
            if (eq) {
                fprintf(stderr, "hexaglide %s: %s takes no value (got '%s')\n", a->cmd, o->name, arg);
                return CLI_BAD;
            }
            return k;
        }
        if (!eq && a->i >= a->argc) {
            fprintf(stderr, "hexaglide %s: %s needs a value (%s VALUE or %s=VALUE)\n", a->cmd, o->name,
                    o->name, o->name);
            return CLI_BAD;
        }
        *value = eq ? eq + 1 : a->argv[a->i++];
        if (!**value) {                /* (an empty path would write ".csv" or fail late) */
            fprintf(stderr, "hexaglide %s: %s: an empty value; give one\n", a->cmd, o->name);
            return CLI_BAD;
        }
        return once(a, k, *value);
    }
    fprintf(stderr, "hexaglide %s: unknown option '%.*s' ('hexaglide %s --help' lists the options)\n",
            a->cmd, (int)len, arg, a->cmd);
    return CLI_BAD;
}

int cli_list_only(const cli_args *a, const char *list_opt, const char *const keep[])
{
    int k, j, kept;
    for (k = 0; k < CLI_MAX_OPTS && a->opts[k].name; k++) {
        if (!a->seen[k] || strcmp(a->opts[k].name, list_opt) == 0)
            continue;
        for (kept = 0, j = 0; keep[j]; j++)
            kept |= strcmp(a->opts[k].name, keep[j]) == 0;
        if (!kept) {
            fprintf(stderr, "hexaglide %s: %s prints a list and runs nothing: %s would not be used; leave it "
                    "out, or leave out %s to run\n", a->cmd, list_opt, a->opts[k].name, list_opt);
            return 2;
        }
    }
    return 0;
}

int cli_strtod(const char *text, double *out)
{
    double v;
    while (*text == ' ' || *text == '\t')   /* (as strtod, and hg_csv.number) */
        text++;
    if (hg_text_is_nonfinite_word(text, strlen(text)))
        return 2;
    if (!hg_text_is_decimal(text, strlen(text))) {  /* the one rule: no hex float, no "nan(...)" */
        const char *p = text + (text[0] == '+' || text[0] == '-');
        return p[0] == '0' && (p[1] == 'x' || p[1] == 'X') ? 3 : 1;
    }
    errno = 0;
    v = strtod(text, 0);
    if (!isfinite(v) || (errno == ERANGE && fabs(v) > 1.0)) /* overflow; underflow to a denormal or 0 is a number */
        return 2;
    *out = v;
    return 0;
}

const char *cli_strtod_hint(int rc)
{
    return rc == 3 ? " (hexadecimal is not read: give it in decimal)" : "";
}

const char *cli_num(double v, char buf[CLI_NUM_LEN])
{
    int p;
    for (p = 6; p < 17; p++) {         /* %g's 6 digits where they read back, more where not */
        snprintf(buf, CLI_NUM_LEN, "%.*g", p, v);
        if (strtod(buf, 0) == v)
            return buf;
    }
    snprintf(buf, CLI_NUM_LEN, "%.17g", v);
    return buf;
}

int cli_parse_double(const char *cmd, const char *text, const char *what, double *out)
{
    int rc = cli_strtod(text, out);
    if (rc)
        fprintf(stderr, "hexaglide %s: %s: '%s' is not a %snumber%s\n", cmd, what, text, rc == 2 ? "finite " : "",
                cli_strtod_hint(rc));
    return rc ? -1 : 0;
}

int cli_parse_list(const char *cmd, const char *opt, const char *text, const char *const names[], int n,
                   double *out)
{
    const char *p = text;
    int k;
    for (k = 0; k < n; k++) {
        const char *comma = strchr(p, ',');
        size_t len = comma ? (size_t)(comma - p) : strlen(p);
        char *item, what[96];
        int rc;
        if (!comma && k != n - 1) {
            fprintf(stderr, "hexaglide %s: %s: need %d comma-separated values, got %d in '%s'\n", cmd, opt, n,
                    k + 1, text);
            return -1;
        }
        if (comma && k == n - 1) {
            fprintf(stderr, "hexaglide %s: %s: need %d comma-separated values, got more in '%s'\n", cmd, opt, n,
                    text);
            return -1;
        }
        snprintf(what, sizeof what, "%s %s", opt, names[k]);
        item = malloc(len + 1);        /* the item whole: any length a single number may have */
        if (!item) {
            fprintf(stderr, "hexaglide %s: %s: out of memory\n", cmd, what);
            return -1;
        }
        memcpy(item, p, len);
        item[len] = '\0';
        rc = cli_parse_double(cmd, item, what, &out[k]);
        free(item);
        if (rc)
            return -1;
        p = comma ? comma + 1 : p + len;
    }
    return 0;
}

/* Edits (insert, delete, replace one character) from a to b, at most 64 characters each. */
static int edit_distance(const char *a, const char *b)
{
    int row[65], i, j, la = (int)strlen(a), lb = (int)strlen(b);
    if (la > 64 || lb > 64)
        return 65;
    for (j = 0; j <= lb; j++)
        row[j] = j;
    for (i = 1; i <= la; i++) {
        int diag = row[0];
        row[0] = i;
        for (j = 1; j <= lb; j++) {
            int up = row[j], best = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < best)
                best = up + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            diag = up;
            row[j] = best;
        }
    }
    return row[lb];
}

/* The number after NAME's last '_' (NAME_N: channel N's parameter), or -1. */
static int channel_suffix(const char *name)
{
    const char *us = strrchr(name, '_'), *q;
    if (!us || !us[1])
        return -1;
    for (q = us + 1; *q; q++)
        if (*q < '0' || *q > '9' || q - us > 3)
            return -1;
    return atoi(us + 1);
}

/* What to say after "unknown parameter NAME" of the plant's model: for
 * NAME_N, where the model's parameters have channel numbers, the name of
 * channel N a typo explains (at most 2 edits), else channel N's names
 * (serial XYZA: mass_3 -> axis 3 is rotary: inertia_3, ...), or that
 * there is no channel N; for another name, the closest name a typo
 * explains (2 edits, 3 for names of 9 characters or more). */
static void unknown_param_hint(const hg_plant *pl, int variant, const char *name, char *buf, size_t len)
{
    hg_param_info e;
    int i, n = channel_suffix(name), numbered = 0, in_channel = 0, best = -1;
    int best_d = (int)strlen(name) >= 9 ? 4 : 3, found = 0;
    buf[0] = '\0';
    for (i = 0; hg_plant_param(pl, variant, i, &e) == 0; i++) {
        numbered |= channel_suffix(e.name) >= 0;
        in_channel |= n >= 0 && channel_suffix(e.name) == n;
    }
    for (i = 0; hg_plant_param(pl, variant, i, &e) == 0; i++) {
        int d = edit_distance(name, e.name);
        if (d < best_d && (!in_channel || channel_suffix(e.name) == n)) {
            best_d = d;
            best = i;
        }
    }
    if (n >= 0 && numbered && !in_channel) {
        snprintf(buf, len, "; the model has no channel %d", n);
    } else if (best >= 0 && hg_plant_param(pl, variant, best, &e) == 0) {
        snprintf(buf, len, "; did you mean '%s'?", e.name);
    } else if (in_channel) {       /* another channel m has NAME's base: say channel n's own names */
        size_t base = (size_t)(strrchr(name, '_') - name);
        int m = -1;
        for (i = 0; m < 0 && hg_plant_param(pl, variant, i, &e) == 0; i++)
            if (strncmp(e.name, name, base) == 0 && e.name[base] == '_' && channel_suffix(e.name) >= 0)
                m = channel_suffix(e.name);
        for (i = 0; m >= 0 && hg_plant_param(pl, variant, i, &e) == 0; i++) {
            char other[64], head[48];
            if (channel_suffix(e.name) != n)
                continue;
            snprintf(other, sizeof other, "%.*s_%d", (int)(strrchr(e.name, '_') - e.name), e.name, m);
            if (hg_plant_param_find(pl, variant, other) >= 0)
                continue;                                  /* channel m has it too: not n's kind */
            snprintf(head, sizeof head, "; channel %d has ", n);
            hg_text_add(buf, len, found++ ? ", " : head);  /* (hg_text_add truncates, never overruns) */
            hg_text_add(buf, len, e.name);
        }
        if (found) {
            char tail[64];
            snprintf(tail, sizeof tail, " instead (an axis of another kind than channel %d)", m);
            hg_text_add(buf, len, tail);
        }
    }
}

int cli_parse_set(const char *cmd, const char *text, int plant, int variant, hg_plant_params *p)
{
    char name[64], what[72];
    const char *eq = strchr(text, '=');
    double v;
    int i;
    if (!eq || eq == text) {
        fprintf(stderr, "hexaglide %s: --set: expected name=value, got '%s'\n", cmd, text);
        return -1;
    }
    if ((size_t)(eq - text) >= sizeof name) {
        fprintf(stderr, "hexaglide %s: --set: unknown parameter '%.*s...': longer than any parameter's name "
                "(hexaglide sim --list-params lists them)\n", cmd, 20, text);
        return -1;
    }
    memcpy(name, text, (size_t)(eq - text));
    name[eq - text] = '\0';
    i = hg_plant_param_find(hg_plant_at(plant), variant, name);
    if (i < 0) {
        char model[HG_PLANT_TEXT_LEN], hint[512];
        const hg_plant *pl = hg_plant_at(plant);
        unknown_param_hint(pl, variant, name, hint, sizeof hint);
        fprintf(stderr, "hexaglide %s: --set: unknown parameter '%s' of plant %s, model %s%s (hexaglide sim "
                "--list-params lists them)\n", cmd, name, pl->name, cli_variant_name(plant, variant, model), hint);
        return -1;
    }
    snprintf(what, sizeof what, "--set %s", name);
    if (cli_parse_double(cmd, eq + 1, what, &v))
        return -1;
    p->v[i] = v;
    return i;
}
