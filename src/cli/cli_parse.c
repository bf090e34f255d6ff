/* cli_parse.c - number parsing shared by the subcommands. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
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
