/* cli_board.c - the board the subcommands drive (hg_board.h): build it
 * from a parameter block, naming every refused field. */
#include <stdio.h>
#include <stdlib.h>
#include "cli.h"
#include "hg_errors.h"

hg_board *cli_board_new(const char *cmd, int kind, const hg_board_params *p)
{
    const char *why[HG_BOARD_WHY_LEN];
    unsigned long long mask;
    hg_board *b = malloc(sizeof *b);
    int i, n, rc;
    hg_params_table(&n);
    if (!b) {
        fprintf(stderr, "hexaglide %s: out of memory\n", cmd);
        return 0;
    }
    if (hg_board_params_check(p, &mask, why)) {
        for (i = 0; i < HG_BOARD_WHY_LEN; i++)
            if ((mask >> i) & 1u)
                fprintf(stderr, "hexaglide %s: bad parameter '%s': %s\n", cmd,
                        i < n ? hg_params_table(0)[i].name : i == HG_BOARD_BIT_SUBSTEPS ? "--substeps"
                                                                                        : "--integrator",
                        why[i] ? why[i] : "invalid");
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
