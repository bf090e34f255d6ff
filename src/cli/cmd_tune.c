/* cmd_tune.c - the tune subcommand: PID and feed-forward gains tuned against
 * the model. The closed loop is C (src/hg_loop.c through
 * build/libhexaglide.so); the search (scipy) and the plots (matplotlib) are
 * tools/hexaglide_tune.py, which this command runs with the arguments given
 * (docs/tuning.md).
 *   hexaglide tune [--trajectory FILE] [--output FILE] [--plots DIR] [...] */
#include "cli.h"

const char cli_usage_tune[] =
    "usage: hexaglide tune [--trajectory FILE] [--ini FILE] [--output FILE] [--plots DIR]\n"
    "                      [--evaluate] [--set KEY=value]... [...]\n"
    "  PID and feed-forward gains tuned against the model (docs/tuning.md); every option is\n"
    "  tools/hexaglide_tune.py's, whose --help lists them all. --plant serial (implied by an\n"
    "  --ini with a [SERIAL] section): a serial-axis machine's joints in the INI's units\n"
    "  (tools/hexaglide_tune_serial.py, docs/serial.md).\n"
    "  Python: the tuner needs numpy, scipy and matplotlib. It runs under $HEXAGLIDE_PYTHON if\n"
    "  set, else under the first python3 on $PATH that imports them (on Debian 12 the system's\n"
    "  /usr/bin/python3 with python3-numpy python3-scipy python3-matplotlib installed; a pyenv\n"
    "  or venv python3 without them is skipped).\n";

int cmd_tune(int argc, char **argv)
{
    return cli_run_python("tune", "hexaglide_tune.py", "numpy scipy matplotlib",
                          "the tuner's search is scipy's differential evolution and its plots are matplotlib's",
                          cli_usage_tune, argc, argv);
}
