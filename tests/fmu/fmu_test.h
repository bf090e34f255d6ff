/* fmu_test.h - helpers of the C drivers of tests/fmu (fmu_api.c,
 * fmu_fuzz.c): TAP lines, a logger that keeps the FMU's messages, value
 * references by name. The drivers call the FMI 3.0 functions of the
 * FMU's own objects (src/fmu/fmu.mk links them). */
#ifndef FMU_TEST_H
#define FMU_TEST_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fmi3Functions.h"
#include "fmu_vars.h"

static int test_failures;

/* One TAP line; counts a failure. */
static inline void check(int cond, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static inline void check(int cond, const char *fmt, ...)
{
    va_list ap;
    printf(cond ? "ok - " : "not ok - ");
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
    if (!cond)
        test_failures++;
}

/* What an instance logged. */
typedef struct {
    int n[5];                         /* messages per fmi3Status */
    char last[1024];                  /* the last message */
    int quiet;                        /* don't print them */
} logbook;

/* The FMU's logger: counts and keeps the messages of one instance. */
static void log_cb(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message)
{
    logbook *b = env;
    if (status >= 0 && status < 5)
        b->n[status]++;
    snprintf(b->last, sizeof b->last, "%s", message);
    if (!b->quiet && status != fmi3OK)       /* logEvents are counted, not printed */
        printf("# [%s] %s\n", category, message);
}

/* A co-simulation instance with this build's token (0 on failure), loggingOn as given. */
static inline fmi3Instance instantiate_logging(const char *name, logbook *book, fmi3Boolean logging_on)
{
    char token[FMU_TOKEN_LEN];
    if (fmu_vars_token(token))
        return 0;
    return fmi3InstantiateCoSimulation(name, token, "", fmi3False, logging_on, fmi3False, fmi3False, 0, 0, book,
                                       log_cb, 0);
}

/* A co-simulation instance with loggingOn: every category logs (the tests read the messages). */
static inline fmi3Instance instantiate(const char *name, logbook *book)
{
    return instantiate_logging(name, book, fmi3True);
}

/* Value reference of the variable called name (exits when there is none: a test bug). */
static inline fmi3ValueReference vr_of(const char *name)
{
    unsigned vr, n = fmu_var_count();
    for (vr = 0; vr < n; vr++) {
        fmu_var v;
        fmu_var_get(vr, &v);
        if (!strcmp(v.name, name))
            return vr;
    }
    printf("not ok - no variable %s\n", name);
    exit(1);
}

/* Set one Float64 by name. */
static inline fmi3Status set_f64(fmi3Instance s, const char *name, double x)
{
    fmi3ValueReference vr = vr_of(name);
    return fmi3SetFloat64(s, &vr, 1, &x, 1);
}

/* Get one Float64 by name (NaN when refused). */
static inline double get_f64(fmi3Instance s, const char *name)
{
    fmi3ValueReference vr = vr_of(name);
    double x;
    return fmi3GetFloat64(s, &vr, 1, &x, 1) == fmi3OK ? x : 0.0 / 0.0;
}

#endif
