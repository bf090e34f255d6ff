/* cmd_tune.c - the tune subcommand: PID and feed-forward gains tuned against
 * the model. The closed loop is C (src/hg_loop.c through
 * build/libhexaglide.so); the search (scipy) and the plots (matplotlib) are
 * tools/hexaglide_tune.py, which this command runs with the arguments given
 * (docs/tuning.md).
 *   hexaglide tune [--trajectory FILE] [--output FILE] [--plots DIR] [...] */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli.h"

#define TUNE_PYTHON "/usr/bin/python3"

int cmd_tune(int argc, char **argv)
{
    char exe[PATH_MAX], script[PATH_MAX + 64], lib[PATH_MAX + 64], *slash;
    char **args;
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    int i;
    if (n <= 0) {
        fprintf(stderr, "hexaglide tune: cannot find my own path (/proc/self/exe): %s\n", strerror(errno));
        return 1;
    }
    exe[n] = 0;
    slash = strrchr(exe, '/');              /* .../build/hexaglide -> .../build */
    *slash = 0;
    snprintf(lib, sizeof lib, "%s/libhexaglide.so", exe);
    slash = strrchr(exe, '/');              /* .../build -> the source tree */
    if (slash)
        *slash = 0;
    snprintf(script, sizeof script, "%s/tools/hexaglide_tune.py", exe);
    if (access(script, R_OK) != 0) {
        fprintf(stderr, "hexaglide tune: %s not found: run the hexaglide of a source tree (build/hexaglide)\n", script);
        return 1;
    }
    if (access(lib, R_OK) == 0)
        setenv("HEXAGLIDE_LIB", lib, 0);
    args = calloc((size_t)argc + 3, sizeof *args);
    if (!args)
        return 1;
    args[0] = TUNE_PYTHON;
    args[1] = script;
    for (i = 0; i < argc; i++)
        args[i + 2] = argv[i];
    fflush(stdout);
    execv(TUNE_PYTHON, args);
    fprintf(stderr, "hexaglide tune: cannot run %s (%s): install python3-scipy and python3-matplotlib "
            "(tools/install-deps.sh tune)\n", TUNE_PYTHON, strerror(errno));
    free(args);
    return 1;
}
