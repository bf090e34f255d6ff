/* cli_board.c - the machine the subcommands drive: its parameters (defaults,
 * config, --set) and the board (hg_board.h), naming every refused field. */
#include <stdio.h>
#include <stdlib.h>
#include "cli.h"
#include "hg_errors.h"

int cli_params_build(const char *cmd, const char *ini, char *const *sets, int nset, hg_params *p)
{
    hg_params defaults;
    int i;
    hg_params_default(&defaults);
    *p = defaults;
    if (ini) {
        cli_ini f;
        int rc;
        if (cli_ini_read(cmd, ini, &f))
            return 2;
        rc = cli_ini_apply_hexaglide(cmd, &f, p);
        cli_ini_free(&f);
        if (rc) {
            fprintf(stderr, "hexaglide %s: fix the [HEXAGLIDE] section of %s\n", cmd, ini);
            return 2;
        }
    }
    for (i = 0; i < nset; i++)
        if (cli_parse_set(cmd, sets[i], p))
            return 2;
    return 0;
}

int cli_board_defaults(hg_board_params *bp)
{
    hg_board *b = malloc(sizeof *b);
    hg_board_inputs in;
    int rc;
    if (!b)
        return -1;
    rc = hg_board_init(b, HG_MODEL_REDUCED_CARTESIAN, 0);
    if (rc == 0) {
        hg_board_inputs_default(b, &in);   /* the block in force: HAL's load-time values */
        *bp = in.params;
    }
    free(b);
    return rc ? -1 : 0;
}

/* One line per set bit of mask: bit i < table length is parameter i, then
 * the board's substeps / integrator bits. */
static void report_refused(const char *cmd, unsigned long long mask, const char *const *why)
{
    int i, n;
    const hg_param_info *t = hg_params_table(&n);
    for (i = 0; i < 64; i++)
        if ((mask >> i) & 1u)
            fprintf(stderr, "hexaglide %s: bad parameter '%s': %s\n", cmd,
                    i < n ? t[i].name : i == HG_BOARD_BIT_SUBSTEPS ? "--substeps" : "--integrator",
                    why[i] ? why[i] : "invalid");
}

int cli_params_check(const char *cmd, const hg_params *p)
{
    const char *why[HG_BOARD_WHY_LEN] = {0};   /* report_refused reads up to 64 */
    unsigned long long mask = 0;
    if (!hg_params_check_all(p, &mask, why))
        return 0;
    report_refused(cmd, mask, why);
    return 1;
}

hg_board *cli_board_new(const char *cmd, int kind, const hg_board_params *p)
{
    const char *why[HG_BOARD_WHY_LEN];
    unsigned long long mask;
    hg_board *b = malloc(sizeof *b);
    int rc;
    if (!b) {
        fprintf(stderr, "hexaglide %s: out of memory\n", cmd);
        return 0;
    }
    if (hg_board_params_check(p, &mask, why)) {
        report_refused(cmd, mask, why);
        free(b);
        return 0;
    }
    rc = hg_board_init(b, (hg_model_kind)kind, p);
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
                        "nanoseconds), got %g\n", cmd, HG_DT_MAX_S, dt);
        return -1;
    }
    *period_ns = (long)(ns + 0.5);
    return 0;
}
