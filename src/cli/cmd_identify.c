/* cmd_identify.c - the identify and excite subcommands: dynamic parameters
 * from recorded runs, and an excitation program to record them with
 * (docs/identification.md). The regressor is C (src/hg_regressor.c through
 * build/libhexaglide.so); the estimate, the trajectory optimisation (scipy)
 * and the plots (matplotlib) are tools/hexaglide_identify.py and
 * tools/hexaglide_excite.py, which these commands run.
 *   hexaglide identify RECORD... [--validate RECORD] [--output FILE] [...]
 *   hexaglide excite [--output FILE] [--ini FILE] [...] */
#include "cli.h"

const char cli_usage_identify[] =
    "usage: hexaglide identify RECORD... [--validate RECORD] [--output FILE] [--plots DIR] [...]\n"
    "  the model's dynamic parameters from recorded runs (docs/identification.md); every option\n"
    "  is tools/hexaglide_identify.py's, whose --help lists them all (Python 3 with numpy, scipy\n"
    "  and matplotlib: $HEXAGLIDE_PYTHON, else the first python3 on $PATH that has them).\n"
    "  A serial plant's board record: per axis mass, friction and net weight\n"
    "  (tools/hexaglide_identify_serial.py, docs/serial.md).\n";

const char cli_usage_excite[] =
    "usage: hexaglide excite [--output FILE] [--ini FILE] [...]\n"
    "  an excitation program (G-code) for identify, inside the config's limits\n"
    "  (docs/identification.md); every option is tools/hexaglide_excite.py's.\n";

#define ID_MODULES "numpy scipy matplotlib"
#define ID_WHY "the estimate and the trajectory optimisation are scipy's, the plots matplotlib's"

int cmd_identify(int argc, char **argv)
{
    return cli_run_python("identify", "hexaglide_identify.py", ID_MODULES, ID_WHY, cli_usage_identify,
                          argc, argv);
}

int cmd_excite(int argc, char **argv)
{
    return cli_run_python("excite", "hexaglide_excite.py", ID_MODULES, ID_WHY, cli_usage_excite, argc, argv);
}
