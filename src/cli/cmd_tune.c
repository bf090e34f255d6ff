/* cmd_tune.c - the tune subcommand: PID and feed-forward gains tuned against
 * the model. The closed loop is C (src/hg_loop.c through
 * build/libhexaglide.so); the search (scipy) and the plots (matplotlib) are
 * tools/hexaglide_tune.py, which this command runs with the arguments given
 * (docs/tuning.md) under the first Python 3 that imports numpy, scipy and
 * matplotlib ($HEXAGLIDE_PYTHON, else each python3 on $PATH).
 *   hexaglide tune [--trajectory FILE] [--output FILE] [--plots DIR] [...] */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli.h"

#define TUNE_MODULES "numpy scipy matplotlib"
#define TUNE_WHY "the tuner's search is scipy's differential evolution and its plots are matplotlib's"

const char cli_usage_tune[] =
    "usage: hexaglide tune [--trajectory FILE] [--ini FILE] [--output FILE] [--plots DIR]\n"
    "                      [--evaluate] [--set KEY=value]... [...]\n"
    "  PID and feed-forward gains tuned against the model (docs/tuning.md); every option is\n"
    "  tools/hexaglide_tune.py's, whose --help lists them all.\n"
    "  Python: the tuner needs numpy, scipy and matplotlib. It runs under $HEXAGLIDE_PYTHON if\n"
    "  set, else under the first python3 on $PATH that imports them (on Debian 12 the system's\n"
    "  /usr/bin/python3 with python3-numpy python3-scipy python3-matplotlib installed; a pyenv\n"
    "  or venv python3 without them is skipped).\n";

int cmd_tune(int argc, char **argv)
{
    char script[PATH_MAX], lib[PATH_MAX], python[PATH_MAX];
    char **args;
    int i, help = 0;
    for (i = 0; i < argc; i++)
        help |= strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0;
    if (cli_tree_path("tools/hexaglide_tune.py", script, sizeof script) || access(script, R_OK) != 0) {
        fprintf(stderr, "hexaglide tune: tools/hexaglide_tune.py not found beside this program: run the "
                "hexaglide of a source tree (build/hexaglide)\n");
        if (help)
            fputs(cli_usage_tune, stdout);
        return help ? 0 : 1;
    }
    if (cli_find_python("tune", TUNE_MODULES, TUNE_WHY, python, sizeof python)) {
        if (help)                      /* the usage still; the message above says what is missing */
            fputs(cli_usage_tune, stdout);
        return help ? 0 : 1;
    }
    if (cli_beside_path("libhexaglide.so", lib, sizeof lib) == 0 && access(lib, R_OK) == 0)
        setenv("HEXAGLIDE_LIB", lib, 0);   /* the core this hexaglide was built with */
    args = calloc((size_t)argc + 3, sizeof *args);
    if (!args)
        return 1;
    args[0] = python;
    args[1] = script;
    for (i = 0; i < argc; i++)
        args[i + 2] = argv[i];
    fflush(stdout);
    execv(python, args);
    fprintf(stderr, "hexaglide tune: cannot run %s (%s)\n", python, strerror(errno));
    free(args);
    return 1;
}
