/* cmd_tune.c - the tune subcommand: PID and feed-forward gains tuned against
 * the model. The closed loop is C (src/hg_loop.c through
 * build/libhexaglide.so); the search (scipy) and the plots (matplotlib) are
 * tools/hexaglide_tune.py, which this command runs with the arguments given
 * (docs/tuning.md).
 *   hexaglide tune [--trajectory FILE] [--output FILE] [--plots DIR] [...] */
#include "cli.h"

int cmd_tune(int argc, char **argv)
{
    return cli_run_python("tune", "hexaglide_tune.py", argc, argv);
}
