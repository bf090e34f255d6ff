/* cmd_identify.c - the identify and excite subcommands: dynamic parameters
 * from recorded runs, and an excitation program to record them with
 * (docs/identification.md). The regressor is C (src/hg_regressor.c through
 * build/libhexaglide.so); the estimate, the trajectory optimisation (scipy)
 * and the plots (matplotlib) are tools/hexaglide_identify.py and
 * tools/hexaglide_excite.py, which these commands run.
 *   hexaglide identify RECORD... [--validate RECORD] [--output FILE] [...]
 *   hexaglide excite [--output FILE] [--ini FILE] [...] */
#include "cli.h"

int cmd_identify(int argc, char **argv)
{
    return cli_run_python("identify", "hexaglide_identify.py", argc, argv);
}

int cmd_excite(int argc, char **argv)
{
    return cli_run_python("excite", "hexaglide_excite.py", argc, argv);
}
