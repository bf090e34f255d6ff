/* cli_parse.c - number parsing shared by the subcommands. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"

int cli_parse_double(const char *text, const char *what, double *out)
{
    char *end = 0;
    double v;
    errno = 0;
    v = strtod(text, &end);
    if (end == text || *end != '\0') {
        fprintf(stderr, "hexaglide: %s: '%s' is not a number\n", what, text);
        return -1;
    }
    if (!isfinite(v) || (errno == ERANGE && fabs(v) > 1.0)) { /* overflow; underflow to a denormal or 0 is a number */
        fprintf(stderr, "hexaglide: %s: '%s' is not a finite number\n", what, text);
        return -1;
    }
    *out = v;
    return 0;
}

int cli_parse_set(const char *cmd, const char *text, hg_params *p)
{
    char name[64];
    const char *eq = strchr(text, '=');
    double v;
    if (!eq || eq == text || (size_t)(eq - text) >= sizeof name) {
        fprintf(stderr, "hexaglide %s: --set: expected name=value, got '%s'\n", cmd, text);
        return -1;
    }
    memcpy(name, text, (size_t)(eq - text));
    name[eq - text] = '\0';
    if (!hg_params_field(p, name)) {
        fprintf(stderr, "hexaglide %s: --set: unknown parameter '%s' (hexaglide sim --list-params "
                "lists them)\n", cmd, name);
        return -1;
    }
    if (cli_parse_double(eq + 1, name, &v))
        return -1;
    if (hg_params_set(p, name, v)) {
        fprintf(stderr, "hexaglide %s: --set: cannot set '%s' to '%s'\n", cmd, name, eq + 1);
        return -1;
    }
    return 0;
}
