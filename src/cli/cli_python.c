/* cli_python.c - subcommands whose work is Python (scipy, matplotlib): run
 * /usr/bin/python3 on a script of the source tree's tools/ with the arguments
 * given and the library beside the binary (build/libhexaglide.so, through
 * HEXAGLIDE_LIB), as tune, identify and excite do. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli.h"

#define CLI_PYTHON "/usr/bin/python3"

int cli_run_python(const char *cmd, const char *script_name, int argc, char **argv)
{
    char exe[PATH_MAX], script[PATH_MAX + 64], lib[PATH_MAX + 64], *slash;
    char **args;
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    int i;
    script[0] = 0;
    if (n <= 0) {
        fprintf(stderr, "hexaglide %s: cannot find my own path (/proc/self/exe): %s\n", cmd, strerror(errno));
        return 1;
    }
    exe[n] = 0;
    slash = strrchr(exe, '/');              /* .../build/hexaglide -> .../build */
    *slash = 0;
    snprintf(lib, sizeof lib, "%s/libhexaglide.so", exe);
    /* the source tree: the nearest directory above with tools/SCRIPT
     * (build/hexaglide, build/asan/hexaglide) */
    for (i = 0; i < 4; i++) {
        slash = strrchr(exe, '/');
        if (!slash)
            break;
        *slash = 0;
        snprintf(script, sizeof script, "%s/tools/%s", exe, script_name);
        if (access(script, R_OK) == 0)
            break;
    }
    if (access(script, R_OK) != 0) {
        fprintf(stderr, "hexaglide %s: %s not found: run the hexaglide of a source tree (build/hexaglide)\n",
                cmd, script);
        return 1;
    }
    if (access(lib, R_OK) == 0)
        setenv("HEXAGLIDE_LIB", lib, 0);
    args = calloc((size_t)argc + 3, sizeof *args);
    if (!args)
        return 1;
    args[0] = CLI_PYTHON;
    args[1] = script;
    for (i = 0; i < argc; i++)
        args[i + 2] = argv[i];
    fflush(stdout);
    execv(CLI_PYTHON, args);
    fprintf(stderr, "hexaglide %s: cannot run %s (%s): install python3-scipy and python3-matplotlib "
            "(tools/install-deps.sh tune)\n", cmd, CLI_PYTHON, strerror(errno));
    free(args);
    return 1;
}
