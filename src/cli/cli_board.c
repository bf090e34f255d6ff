/* cli_board.c - the machine the subcommands drive: its plant, its
 * parameters (defaults, config, --set) and the board (hg_board.h), naming
 * every refused field. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "hg_errors.h"

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
    int i, v = hg_plant_variant(p, name);
    if (v >= 0)
        return v;
    fprintf(stderr, "hexaglide %s: --model %s: not a model of the %s; use", cmd, name, p->name);
    for (i = 0; i < p->nvariants; i++)
        fprintf(stderr, "%s %s", i ? "," : "", p->variants[i]);
    fprintf(stderr, "\n");
    return -1;
}

int cli_params_build(const char *cmd, int plant, const char *ini, char *const *sets, int nset,
                     hg_plant_params *v)
{
    int i;
    hg_plant_params_defaults(plant, v);
    if (ini) {
        cli_ini f;
        int rc;
        if (cli_ini_read(cmd, ini, &f))
            return 2;
        rc = cli_ini_apply_plant(cmd, &f, plant, v);
        cli_ini_free(&f);
        if (rc) {
            fprintf(stderr, "hexaglide %s: fix the [%s] section of %s\n", cmd, hg_plant_at(plant)->ini_section, ini);
            return 2;
        }
    }
    for (i = 0; i < nset; i++)
        if (cli_parse_set(cmd, sets[i], plant, v) < 0)
            return 2;
    return 0;
}

int cli_hexaglide_params(const char *cmd, const char *ini, char *const *sets, int nset, hg_params *p)
{
    hg_plant_params v;
    int i, n;
    if (cli_params_build(cmd, 0, ini, sets, nset, &v) || cli_params_check(cmd, 0, &v))
        return 2;
    hg_params_table(&n);
    hg_params_default(p);
    for (i = 0; i < n; i++)
        *hg_params_at(p, i) = v.v[i];
    return 0;
}

void cli_board_defaults(int plant, hg_board_params *bp)
{
    hg_board_params_default(plant, bp);
}

/* One line per set bit: bit i < table length is parameter i, then the
 * board's substeps / integrator bits. */
static void report_refused(const char *cmd, int plant, const hg_bitset *bad, const char *const *why)
{
    int i, n;
    const hg_param_info *t = hg_plant_params_table(plant, &n);
    for (i = 0; i < HG_BOARD_WHY_LEN; i++)
        if (hg_bitset_has(bad, i))
            fprintf(stderr, "hexaglide %s: bad parameter '%s': %s\n", cmd,
                    i < n ? t[i].name : i == HG_BOARD_BIT_SUBSTEPS ? "--substeps" : "--integrator",
                    why[i] ? why[i] : "invalid");
}

int cli_params_check(const char *cmd, int plant, const hg_plant_params *v)
{
    static const char *why[HG_BOARD_WHY_LEN];
    hg_bitset bad;
    memset(why, 0, sizeof why);
    hg_bitset_clear(&bad);
    if (!hg_plant_at(plant)->check(v, &bad, why))
        return 0;
    report_refused(cmd, plant, &bad, why);
    return 1;
}

hg_board *cli_board_new(const char *cmd, int plant, int variant, const hg_board_params *p)
{
    static const char *why[HG_BOARD_WHY_LEN];
    hg_bitset bad;
    hg_board *b = calloc(1, sizeof *b);
    int rc;
    if (!b) {
        fprintf(stderr, "hexaglide %s: out of memory\n", cmd);
        return 0;
    }
    b->plant = plant;                 /* the checks need the plant */
    if (p && hg_board_params_check(b, p, &bad, why)) {
        report_refused(cmd, plant, &bad, why);
        free(b);
        return 0;
    }
    rc = hg_board_init(b, plant, variant, p);
    if (rc) {
        fprintf(stderr, "hexaglide %s: cannot build the machine: %s (code %d)\n", cmd, hg_strerror(rc), rc);
        free(b);
        return 0;
    }
    return b;
}

int cli_parse_period(const char *cmd, double dt, long *period_ns)
{
    double ns = dt * 1e9;
    if (!(ns >= 1.0 && ns <= (double)HG_PERIOD_MAX_NS)) {
        fprintf(stderr, "hexaglide %s: --dt must lie in [1e-9, %g] s (the board's period, whole "
                        "nanoseconds), got %g\n", cmd, (double)HG_PERIOD_MAX_NS * 1e-9, dt);
        return -1;
    }
    *period_ns = (long)(ns + 0.5);
    return 0;
}
