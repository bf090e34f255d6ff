/* cli_python.c - subcommands whose work is Python (scipy, matplotlib): run
 * a script of the source tree's tools/ with the arguments given, under the
 * first Python 3 that imports the modules it needs ($HEXAGLIDE_PYTHON, else
 * each python3 on $PATH), with the library beside the binary
 * (build/libhexaglide.so, through HEXAGLIDE_LIB) and this executable's
 * path in HEXAGLIDE_CLI (the scripts read INI files through its `config`
 * command), as tune, identify and excite do. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli.h"

int cli_run_python(const char *cmd, const char *script_name, const char *modules, const char *why,
                   const char *usage, int argc, char **argv)
{
    char rel[256], script[PATH_MAX], lib[PATH_MAX], python[PATH_MAX];
    char **args;
    int i, help = 0;
    for (i = 0; i < argc; i++)
        help |= strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0;
    snprintf(rel, sizeof rel, "tools/%s", script_name);
    if (cli_tree_path(rel, script, sizeof script) || access(script, R_OK) != 0) {
        fprintf(stderr, "hexaglide %s: %s not found beside this program: run the hexaglide of a source "
                "tree (build/hexaglide)\n", cmd, rel);
        if (help)
            fputs(usage, stdout);
        return help ? 0 : 1;
    }
    if (cli_find_python(cmd, modules, why, python, sizeof python)) {
        if (help)                      /* the usage still; the message says what is missing */
            fputs(usage, stdout);
        return help ? 0 : 1;
    }
    if (cli_beside_path("libhexaglide.so", lib, sizeof lib) == 0 && access(lib, R_OK) == 0)
        setenv("HEXAGLIDE_LIB", lib, 0);   /* the core this hexaglide was built with */
    {                                  /* this executable: its INI reader (hexaglide config) */
        char self[PATH_MAX];
        ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
        if (n > 0) {
            self[n] = '\0';
            setenv("HEXAGLIDE_CLI", self, 1);
        }
    }
    args = calloc((size_t)argc + 3, sizeof *args);
    if (!args)
        return 1;
    args[0] = python;
    args[1] = script;
    for (i = 0; i < argc; i++)
        args[i + 2] = argv[i];
    fflush(stdout);
    execv(python, args);
    fprintf(stderr, "hexaglide %s: cannot run %s (%s)\n", cmd, python, strerror(errno));
    free(args);
    return 1;
}
