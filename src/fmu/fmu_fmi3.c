/* fmu_fmi3.c - the FMI 3.0 co-simulation interface of the virtual
 * Hexaglide (build/hexaglide.fmu, docs/fmu.md): glue between the FMI
 * calls and the plant (fmu_plant.h). It keeps every variable's value by
 * value reference, hands them to the plant once per servo period and
 * reports what the plant reports through the logger callback.
 *
 * Communication step: the servo period `period` is the FMU's step; a
 * communication step of n whole periods runs n periods with the inputs
 * held; any other step is refused with fmi3Error. An importer's time
 * carries the rounding of its arithmetic: a time and a step's end are
 * taken within the rounding an importer adding its steps in double makes
 * (same_time: one rule for both).
 * Errors: a refused call returns fmi3Error after a message naming the
 * cause and the fix (category logStatusError), and changes nothing; a
 * fault of the machine is an output (fault, fault_code): the step that
 * latches it returns fmi3Warning with the core's message.
 * State: one malloc'd block without pointers per instance ([status]
 * [values] [plant], fmu_state.h): fmi3GetFMUState copies it,
 * fmi3SetFMUState copies it back; serialized with a header (magic and
 * format, token, layout, size, checksum), and a deserialized block's
 * content is checked before it is taken. No file-scope mutable state:
 * instances share nothing. */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fmi3Functions.h"
#include "hg_compiler.h"
#include "fmu_state.h"
#include "fmu_vars.h"

enum {
    MODE_INSTANTIATED = FMU_MODE_INSTANTIATED, MODE_INIT = FMU_MODE_INIT, MODE_STEP = FMU_MODE_STEP,
    MODE_TERMINATED = FMU_MODE_TERMINATED
};

#define INSTANCE_MAGIC 0x484758464d55494eull   /* "HGXFMUIN" */
#define STATE_MAGIC 0x484758464d555354ull      /* "HGXFMUST" */
#define SERIAL_PREFIX "HGXFMU"                 /* a serialized state opens with it and the format's 2 digits */
#define MAX_PERIODS_PER_STEP 1000000.0         /* longest communication step, in periods */
/* The time rule (same_time): an importer's time x against the FMU's ref
 * after n additions (t += h) may be off by half an ulp per addition (each
 * sum rounds once) plus TIME_SLACK_ULPS ulps (the period's decimal in
 * binary, t0 + k h, the FMU's own start + periods x period), the ulps of
 * the largest magnitude on the way from the start time t0 (|t0|, |k h|,
 * |x|: from a negative start the importer's time carries t0's rounding to
 * zero, where the ulp of x alone is tiny),
 * at most TIME_SLACK_MAX of a period (never taking a time for the next
 * period's). TIME_RESOLUTION: the FMU keeps its time where a double
 * resolves 1e-6 of a period (time_limit). */
#define TIME_SLACK_ULPS 256.0
#define TIME_SLACK_MAX 0.25
#define TIME_RESOLUTION 1e-6

/* The log categories of modelDescription.xml, by FMU_SAY_* level: errors, warnings, events. */
static const char *const log_categories[] = {"logStatusError", "logStatusWarning", "logEvents"};
#define LOG_CATEGORIES ((int)(sizeof log_categories / sizeof *log_categories))
#define LOG_ALL ((1u << LOG_CATEGORIES) - 1u)      /* log_on with every category on */
#define LOG_ERRORS (1u << 0)                        /* log_on's bit of logStatusError */
#define LOG_EVENTS (1u << 2)                        /* log_on's bit of logEvents */

typedef fmu_status status_t;
typedef fmu_serial_header serial_t;

struct saved;

/* One FMU instance. */
typedef struct {
    unsigned long long magic;
    struct saved *states;             /* its fmi3FMUStates not yet freed (fmi3FreeInstance frees them) */
    char *name;
    fmi3InstanceEnvironment env;
    fmi3LogMessageCallback log;
    unsigned log_on;                  /* the categories logged: bit i for log_categories[i] */
    unsigned nvars;
    size_t off_values, off_plant, blob_size;
    unsigned char *blob;              /* status_t, double values[nvars], the plant */
    char token[FMU_TOKEN_LEN];
} instance_t;

/* An fmi3FMUState: a copy of an instance's block, in the list of the instance that made it. */
typedef struct saved {
    unsigned long long magic;
    size_t size;
    void *owner;                      /* the instance_t whose list holds it */
    struct saved *prev, *next;
    unsigned char data[];
} saved_t;

/* x rounded up to a multiple of 16. */
static size_t align16(size_t x)
{
    return (x + 15u) & ~(size_t)15u;
}

/* The instance behind an FMI handle, or 0. */
static instance_t *inst_of(fmi3Instance instance)
{
    instance_t *s = instance;
    return s && s->magic == INSTANCE_MAGIC ? s : 0;
}

/* The instance's status, values and plant. */
static status_t *st(instance_t *s)
{
    return (status_t *)(void *)s->blob;
}
/* The instance's values, by value reference. */
static double *vals(instance_t *s)
{
    return (double *)(void *)(s->blob + s->off_values);
}
/* The instance's plant (fmu_plant.h). */
static void *plant(instance_t *s)
{
    return s->blob + s->off_plant;
}

/* Log one message (errors and warnings always, events with loggingOn). A '#' is written "##": in an FMI
 * message "#vr#" names a variable (FMI 3.0, 2.3.1), and no message of this FMU means one (an instance
 * name "arm#3#" is text). */
static void say(instance_t *s, int level, const char *fmt, ...) HG_PRINTF_LIKE(3, 4);
static void say(instance_t *s, int level, const char *fmt, ...)
{
    char text[768], out[2 * sizeof text];
    size_t i, j = 0;
    va_list ap;
    int category = level == FMU_SAY_ERROR ? 0 : level == FMU_SAY_WARNING ? 1 : 2;
    if (!s->log || !(s->log_on & 1u << category))
        return;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    for (i = 0; text[i]; i++) {
        if (text[i] == '#')
            out[j++] = '#';
        out[j++] = text[i];
    }
    out[j] = '\0';
    s->log(s->env, level == FMU_SAY_ERROR ? fmi3Error : level == FMU_SAY_WARNING ? fmi3Warning : fmi3OK,
           log_categories[category], out);
}

/* The plant's messages (fmu_say_fn), prefixed with the instance name. */
static void plant_say(void *env, int level, const char *text)
{
    instance_t *s = env;
    say(s, level, "%s: %s", s->name, text);
}

/* Name of a mode for messages. */
static const char *mode_name(int mode)
{
    return mode == MODE_INSTANTIATED ? "Instantiated" : mode == MODE_INIT ? "Initialization Mode"
         : mode == MODE_STEP ? "Step Mode" : "Terminated";
}

/* 1 if the instance is in one of modes, else 0 after an error message. */
static int allowed(instance_t *s, const char *fn, int modes, const char *when)
{
    if (st(s)->mode & modes)
        return 1;
    say(s, FMU_SAY_ERROR, "%s: %s: not allowed in %s; call it %s", s->name, fn, mode_name(st(s)->mode), when);
    return 0;
}

/* The simulation time: start time + periods x period. */
static double now(instance_t *s)
{
    return st(s)->start_time + st(s)->periods * st(s)->period_s;
}

/* The distance from |x| to the next double. */
static double ulp_of(double x)
{
    x = fabs(x);
    return isfinite(x) ? nextafter(x, INFINITY) - x : INFINITY;
}

/* How far an importer's time x may lie from the FMU's ref after n
 * additions from the start time t0 (the time rule above). */
static double time_slack(double x, double ref, double t0, double n, double period)
{
    double big = fmax(fmax(fabs(x), fabs(ref)), fmax(fabs(t0), fabs(ref - t0)));
    double slack = (0.5 * n + TIME_SLACK_ULPS) * ulp_of(big);
    return slack < TIME_SLACK_MAX * period ? slack : TIME_SLACK_MAX * period;
}

/* 1 if the importer's time x is the FMU's ref after n additions (the one rule of the time and a step's end). */
static int same_time(double x, double ref, double t0, double n, double period)
{
    return fabs(x - ref) <= time_slack(x, ref, t0, n, period);
}

/* The first power of two from which a double resolves time more coarsely
 * than TIME_RESOLUTION x period: the FMU's time stays below it. */
static double time_limit(double period)
{
    int e;
    frexp(TIME_RESOLUTION * period, &e);   /* 2^(e-1) <= resolution < 2^e */
    return ldexp(1.0, e + 52);             /* ulp(t) = 2^(e-1) for t in [2^(e+51), 2^(e+52)) */
}

/* The period parameter's value as the FMU's time step, or the default while it is refused. */
static double period_param(instance_t *s)
{
    char why[200];
    double p = vals(s)[fmu_var_vr(FMU_G_PERIOD, 0)];
    return fmu_plant_period_why(p, why, sizeof why) ? fmu_plant_period_default_s() : fmu_plant_period_in_force_s(p);
}

/* 0 if the FMU can keep time at start time t0 with the period, else -1 after a message. */
static int time_fits(instance_t *s, const char *fn, double t0, double period)
{
    char a[32], b[32], c[32];
    double limit = time_limit(period);
    if (fabs(t0) < limit)
        return 0;
    say(s, FMU_SAY_ERROR, "%s: %s: startTime %s s refused: from |t| = %s s (2^%d) on a double resolves time only to "
        "%.3g s, more than %g of the period %s s, so the FMU's time could not follow whole periods; start below "
        "%s s or set a longer period", s->name, fn, fmu_num(a, t0), fmu_num(b, limit), (int)log2(limit),
        ulp_of(limit), TIME_RESOLUTION, fmu_num(c, period), b);
    return -1;
}

/* The plant's outputs into the values. */
static void put_outputs(instance_t *s, const fmu_plant_outputs *o)
{
    double *v = vals(s);
    int k;
    for (k = 0; k < FMU_JOINTS; k++) {
        v[fmu_var_vr(FMU_G_COUNT, k)] = o->count[k];
        v[fmu_var_vr(FMU_G_POSITION, k)] = o->position[k];
        v[fmu_var_vr(FMU_G_INDEX, k)] = o->index[k];
        v[fmu_var_vr(FMU_G_LIMIT_MIN, k)] = o->limit_min[k];
        v[fmu_var_vr(FMU_G_LIMIT_MAX, k)] = o->limit_max[k];
        v[fmu_var_vr(FMU_G_HOME, k)] = o->home[k];
        v[fmu_var_vr(FMU_G_Z, k)] = o->z_m[k];
        v[fmu_var_vr(FMU_G_ZD, k)] = o->zd_mps[k];
        v[fmu_var_vr(FMU_G_CURRENT, k)] = o->current_a[k];
        v[fmu_var_vr(FMU_G_FORCE, k)] = o->force_n[k];
    }
    for (k = 0; k < 3; k++) {
        v[fmu_var_vr(FMU_G_HEAD_POS, k)] = o->pose[k];
        v[fmu_var_vr(FMU_G_HEAD_ROT, k)] = o->pose[k + 3];
    }
    v[fmu_var_vr(FMU_G_FAULT, 0)] = o->fault;
    v[fmu_var_vr(FMU_G_FAULT_CODE, 0)] = o->fault_code;
    v[fmu_var_vr(FMU_G_AMPS_ON, 0)] = o->amps_on;
    v[fmu_var_vr(FMU_G_TIME, 0)] = now(s);
}

/* A value as a long long, saturated (no undefined conversion of a huge or NaN double). */
static long long as_int(double x)
{
    return x >= -9e18 && x <= 9e18 ? (long long)x : x > 0 ? 9000000000000000000LL : -9000000000000000000LL;
}

/* The plant's setup from the variables' values v (the parameters point into v). */
static void setup_of(const double *v, fmu_plant_setup *setup)
{
    setup->model = as_int(v[fmu_var_vr(FMU_G_MODEL, 0)]);
    setup->integrator = as_int(v[fmu_var_vr(FMU_G_INTEGRATOR, 0)]);
    setup->substeps = as_int(v[fmu_var_vr(FMU_G_SUBSTEPS, 0)]);
    setup->period_s = v[fmu_var_vr(FMU_G_PERIOD, 0)];
    setup->enc_scale = v[fmu_var_vr(FMU_G_ENC_SCALE, 0)];
    setup->params = &v[fmu_var_vr(FMU_G_PARAM, 0)];
}

/* Build the board of the parameter values (if not built): 0, or -1 after the plant's messages. */
static int build(instance_t *s, const char *fn)
{
    const double *v = vals(s);
    fmu_plant_setup setup;
    fmu_plant_outputs o;
    if (st(s)->built)
        return 0;
    setup_of(v, &setup);
    if (fmu_plant_init(plant(s), &setup, plant_say, s)) {
        say(s, FMU_SAY_ERROR, "%s: %s: the parameters above are refused; set valid values (the FMU stays in %s)",
            s->name, fn, mode_name(st(s)->mode));
        return -1;
    }
    st(s)->period_s = fmu_plant_period_s(plant(s));
    st(s)->built = 1;
    fmu_plant_peek(plant(s), &o);
    put_outputs(s, &o);
    return 0;
}

/* Start values, nothing built, time 0: Instantiated. 0 or -1 (out of memory). */
static int restart(instance_t *s)
{
    memset(s->blob, 0, s->blob_size);
    st(s)->mode = MODE_INSTANTIATED;
    st(s)->stop_time = INFINITY;
    st(s)->period_s = fmu_plant_period_default_s();
    return fmu_vars_start(vals(s));
}

/* ---- creation and destruction ---- */

/* The FMI version of the headers ("3.0"). */
const char *fmi3GetVersion(void)
{
    return fmi3Version;
}

/* 1 if text has no character other than white space (FMI 3.0 refuses such an instanceName). */
static int blank(const char *text)
{
    while (*text && isspace((unsigned char)*text))
        text++;
    return !*text;
}

/* A new instance at the start values, Instantiated; 0 after a message when refused. */
fmi3Instance fmi3InstantiateCoSimulation(fmi3String instanceName, fmi3String instantiationToken,
                                         fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                         fmi3Boolean eventModeUsed, fmi3Boolean earlyReturnAllowed,
                                         const fmi3ValueReference requiredIntermediateVariables[],
                                         size_t nRequiredIntermediateVariables,
                                         fmi3InstanceEnvironment instanceEnvironment,
                                         fmi3LogMessageCallback logMessage,
                                         fmi3IntermediateUpdateCallback intermediateUpdate)
{
    instance_t tmp, *s;
    const char *why = 0;
    (void)resourcePath;
    (void)visible;
    (void)earlyReturnAllowed;            /* it never returns early */
    (void)requiredIntermediateVariables;
    (void)intermediateUpdate;
    memset(&tmp, 0, sizeof tmp);
    tmp.name = (char *)(instanceName ? instanceName : "hexaglide");
    tmp.env = instanceEnvironment;
    tmp.log = logMessage;
    if (fmu_vars_token(tmp.token))
        why = "out of memory";
    else if (!instanceName)
        why = "instanceName is NULL; give the instance a name";
    else if (blank(instanceName))
        why = "instanceName is empty or white space only; give the instance a name with at least one other "
              "character (FMI 3.0 requires it: messages name the instance by it)";
    else if (!instantiationToken || strcmp(instantiationToken, tmp.token) != 0)
        why = "the instantiation token is not this binary's: the modelDescription.xml belongs to another build "
              "of the FMU; rebuild build/hexaglide.fmu (make fmu) and use its modelDescription.xml";
    else if (eventModeUsed)
        why = "eventModeUsed: this FMU has no event mode (hasEventMode=\"false\"); instantiate it without";
    else if (nRequiredIntermediateVariables)
        why = "intermediate variables asked for: this FMU provides no intermediate update";
    if (why) {
        if (logMessage)
            logMessage(instanceEnvironment, fmi3Error, "logStatusError", why);
        return 0;
    }
    s = calloc(1, sizeof *s);
    if (s) {
        *s = tmp;
        s->name = malloc(strlen(instanceName) + 1);
        s->log_on = loggingOn ? LOG_ALL : LOG_ERRORS;  /* without loggingOn, errors only (docs/fmu.md) */
        s->nvars = fmu_var_count();
        s->off_values = align16(sizeof(status_t));
        s->off_plant = align16(s->off_values + s->nvars * sizeof(double));
        s->blob_size = s->off_plant + fmu_plant_size();
        s->blob = malloc(s->blob_size);
    }
    if (!s || !s->name || !s->blob || restart(s)) {
        if (logMessage)
            logMessage(instanceEnvironment, fmi3Error, "logStatusError", "out of memory");
        if (s) {
            free(s->name);
            free(s->blob);
        }
        free(s);
        return 0;
    }
    memcpy(s->name, instanceName, strlen(instanceName) + 1);
    s->magic = INSTANCE_MAGIC;
    return s;
}

/* Refused: co-simulation only. */
fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    (void)instanceName, (void)instantiationToken, (void)resourcePath, (void)visible, (void)loggingOn;
    if (logMessage)
        logMessage(instanceEnvironment, fmi3Error, "logStatusError",
                   "fmi3InstantiateModelExchange: this FMU is co-simulation only; use fmi3InstantiateCoSimulation");
    return 0;
}

/* Refused: co-simulation only. */
fmi3Instance fmi3InstantiateScheduledExecution(fmi3String instanceName, fmi3String instantiationToken,
                                               fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                               fmi3InstanceEnvironment instanceEnvironment,
                                               fmi3LogMessageCallback logMessage,
                                               fmi3ClockUpdateCallback clockUpdate,
                                               fmi3LockPreemptionCallback lockPreemption,
                                               fmi3UnlockPreemptionCallback unlockPreemption)
{
    (void)instanceName, (void)instantiationToken, (void)resourcePath, (void)visible, (void)loggingOn;
    (void)clockUpdate, (void)lockPreemption, (void)unlockPreemption;
    if (logMessage)
        logMessage(instanceEnvironment, fmi3Error, "logStatusError",
                   "fmi3InstantiateScheduledExecution: this FMU is co-simulation only; use "
                   "fmi3InstantiateCoSimulation");
    return 0;
}

/* Free the instance and every FMU state it made that is not yet freed (FMI 3.0: fmi3FreeInstance
 * frees all the memory the FMU's functions allocated). */
void fmi3FreeInstance(fmi3Instance instance)
{
    instance_t *s = inst_of(instance);
    saved_t *p, *next;
    if (!s)
        return;
    for (p = s->states; p; p = next) {   /* (the list goes with the instance: no unlinking) */
        next = p->next;
        p->magic = 0;
        free(p);
    }
    s->magic = 0;
    free(s->blob);
    free(s->name);
    free(s);
}

/* The index of log category name in log_categories, or -1. */
static int category_of(const char *name)
{
    int c;
    for (c = 0; c < LOG_CATEGORIES; c++)
        if (name && strcmp(name, log_categories[c]) == 0)
            return c;
    return -1;
}

/* Turn the listed categories (all when none is listed) on or off; every one must be known. */
fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
    instance_t *s = inst_of(instance);
    unsigned bits = nCategories ? 0u : LOG_ALL;
    size_t i;
    if (!s)
        return fmi3Error;
    if (nCategories && !categories) {
        say(s, FMU_SAY_ERROR, "%s: fmi3SetDebugLogging: categories is NULL with nCategories %zu", s->name,
            nCategories);
        return fmi3Error;
    }
    for (i = 0; i < nCategories; i++) {
        int c = category_of(categories[i]);
        if (c < 0) {
            say(s, FMU_SAY_ERROR, "%s: fmi3SetDebugLogging: unknown category '%s' (logStatusError, "
                "logStatusWarning, logEvents)", s->name, categories[i] ? categories[i] : "(NULL)");
            return fmi3Error;
        }
        bits |= 1u << c;
    }
    s->log_on = loggingOn ? s->log_on | bits : s->log_on & ~bits;
    return fmi3OK;
}

/* ---- the state machine ---- */

/* Instantiated -> Initialization Mode at startTime. */
fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined, fmi3Float64 tolerance,
                                       fmi3Float64 startTime, fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    instance_t *s = inst_of(instance);
    (void)toleranceDefined, (void)tolerance;
    if (!s || !allowed(s, "fmi3EnterInitializationMode", MODE_INSTANTIATED, "after instantiation or fmi3Reset"))
        return fmi3Error;
    if (!isfinite(startTime)) {
        say(s, FMU_SAY_ERROR, "%s: fmi3EnterInitializationMode: startTime %g is not a finite number of seconds",
            s->name, startTime);
        return fmi3Error;
    }
    if (stopTimeDefined && !(stopTime >= startTime)) {
        say(s, FMU_SAY_ERROR, "%s: fmi3EnterInitializationMode: stopTime %.17g s is %s startTime %.17g s; give a "
            "stopTime at or after startTime, or stopTimeDefined = false", s->name, stopTime,
            isnan(stopTime) ? "not a number, not after" : "before", startTime);
        return fmi3Error;
    }
    if (time_fits(s, "fmi3EnterInitializationMode", startTime, period_param(s)))
        return fmi3Error;
    st(s)->start_time = startTime;
    st(s)->stop_time = stopTimeDefined ? stopTime : INFINITY;
    st(s)->periods = 0;
    st(s)->steps = 0;
    vals(s)[fmu_var_vr(FMU_G_TIME, 0)] = startTime;
    st(s)->mode = MODE_INIT;
    return fmi3OK;
}

/* Build the machine of the parameters: Step Mode, or fmi3Error with the rules (stays). */
fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    instance_t *s = inst_of(instance);
    if (!s || !allowed(s, "fmi3ExitInitializationMode", MODE_INIT, "after fmi3EnterInitializationMode"))
        return fmi3Error;
    if (build(s, "fmi3ExitInitializationMode"))
        return fmi3Error;
    if (time_fits(s, "fmi3ExitInitializationMode", st(s)->start_time, st(s)->period_s))
        return fmi3Error;             /* the period set in Initialization Mode is too short for startTime */
    st(s)->mode = MODE_STEP;
    return fmi3OK;
}

/* Step Mode -> Terminated. */
fmi3Status fmi3Terminate(fmi3Instance instance)
{
    instance_t *s = inst_of(instance);
    if (!s || !allowed(s, "fmi3Terminate", MODE_STEP, "in Step Mode"))
        return fmi3Error;
    st(s)->mode = MODE_TERMINATED;
    return fmi3OK;
}

/* Back to Instantiated with the start values. */
fmi3Status fmi3Reset(fmi3Instance instance)
{
    instance_t *s = inst_of(instance);
    if (!s)
        return fmi3Error;
    if (restart(s)) {
        say(s, FMU_SAY_ERROR, "%s: fmi3Reset: out of memory", s->name);
        return fmi3Error;
    }
    return fmi3OK;
}

/* Run the whole servo periods of the step with the inputs held. */
fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize, fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation, fmi3Boolean *earlyReturn,
                      fmi3Float64 *lastSuccessfulTime)
{
    instance_t *s = inst_of(instance);
    fmu_plant_inputs in;
    fmu_plant_outputs o;
    double period, n, t, end, end_fmu, *v;
    char a[32], b[32], c[32];
    long left;
    int k, level = FMU_SAY_INFO, index[FMU_JOINTS] = {0};
    (void)noSetFMUStatePriorToCurrentPoint;
    if (!s || !allowed(s, "fmi3DoStep", MODE_STEP, "in Step Mode, after fmi3ExitInitializationMode"))
        return fmi3Error;
    if (!eventHandlingNeeded || !terminateSimulation || !earlyReturn || !lastSuccessfulTime) {
        say(s, FMU_SAY_ERROR, "%s: fmi3DoStep: an output argument is NULL", s->name);
        return fmi3Error;
    }
    period = st(s)->period_s;
    t = now(s);
    n = floor(communicationStepSize / period + 0.5);
    if (!isfinite(currentCommunicationPoint)) {
        say(s, FMU_SAY_ERROR, "%s: fmi3DoStep: currentCommunicationPoint %g is not a time (the FMU's is %.17g s); step "
            "on from where the last step ended", s->name, currentCommunicationPoint, t);
        return fmi3Error;
    }
    if (!same_time(currentCommunicationPoint, t, st(s)->start_time, st(s)->steps, period)) {
        say(s, FMU_SAY_ERROR, "%s: fmi3DoStep: currentCommunicationPoint %.17g s is not the FMU's time %.17g s (off "
            "by %.3g s, more than the %.3g s a time summed over %.0f steps in double may be off); step on from where "
            "the last step ended (or restore an FMU state)", s->name, currentCommunicationPoint, t,
            currentCommunicationPoint - t, time_slack(currentCommunicationPoint, t, st(s)->start_time, st(s)->steps, period),
            st(s)->steps);
        return fmi3Error;
    }
    /* the step's end as the importer's next time t + h, against the FMU's after n periods: the same rule */
    end = currentCommunicationPoint + communicationStepSize;
    end_fmu = st(s)->start_time + (st(s)->periods + n) * period;
    if (n >= 1 && n <= MAX_PERIODS_PER_STEP && !same_time(end, end_fmu, st(s)->start_time, st(s)->steps + 1, period) &&
        same_time(communicationStepSize, n * period, 0.0, 1, period)) {
        /* n periods to the step's own rounding, from a time within the rule: the importer's sums drifted */
        say(s, FMU_SAY_ERROR, "%s: fmi3DoStep: the step of %.17g s from %.17g s ends at %.17g s, %.3g s from the "
            "FMU's time after %.0f period%s, %.17g s: more than the %.3g s that %.0f sums in double may round by; "
            "the importer's time has drifted from the FMU's (keep it as startTime + k x step, not t += step)",
            s->name, communicationStepSize, currentCommunicationPoint, end, end - end_fmu, n, n == 1 ? "" : "s",
            end_fmu, time_slack(end, end_fmu, st(s)->start_time, st(s)->steps + 1, period), st(s)->steps + 1);
        return fmi3Error;
    }
    if (!(n >= 1 && n <= MAX_PERIODS_PER_STEP && same_time(end, end_fmu, st(s)->start_time, st(s)->steps + 1, period))) {
        char off[240] = "";
        if (n >= 1 && n <= MAX_PERIODS_PER_STEP)
            snprintf(off, sizeof off, " (from %.17g s it ends at %.17g s, %.3g s from the FMU's time after %.0f "
                     "period%s, %.17g s: more than the %.3g s the rounding of a double allows)",
                     currentCommunicationPoint, end, end - end_fmu, n, n == 1 ? "" : "s", end_fmu,
                     time_slack(end, end_fmu, st(s)->start_time, st(s)->steps + 1, period));
        say(s, FMU_SAY_ERROR, "%s: fmi3DoStep: communication step %.17g s is not a whole number (1 to %.0f) of servo "
            "periods of %s s%s: this FMU steps in whole periods; use a fixed communication step of %s s (the "
            "parameter period) or a multiple of it", s->name, communicationStepSize, MAX_PERIODS_PER_STEP,
            fmu_num(a, period), off, fmu_num(b, period));
        return fmi3Error;
    }
    if (!(fabs(end_fmu) < time_limit(period))) {
        say(s, FMU_SAY_ERROR, "%s: fmi3DoStep: the step would end at %.17g s: from |t| = %s s on a double resolves "
            "time only to %.3g s, more than %g of the period %s s, so the FMU's time stops short of it", s->name,
            end_fmu, fmu_num(a, time_limit(period)), ulp_of(time_limit(period)), TIME_RESOLUTION, fmu_num(c, period));
        return fmi3Error;
    }
    if (end_fmu > st(s)->stop_time && !same_time(end_fmu, st(s)->stop_time, st(s)->start_time, st(s)->steps + 1, period)) {
        say(s, FMU_SAY_ERROR, "%s: fmi3DoStep: the step from %.17g s to %.17g s would end past stopTime %.17g s "
            "(fmi3EnterInitializationMode's stopTimeDefined); the FMU computes nothing past it (FMI 3.0): stop "
            "there, or fmi3Reset and initialize with a later stopTime", s->name, t, end_fmu, st(s)->stop_time);
        return fmi3Error;
    }
    v = vals(s);
    for (k = 0; k < FMU_JOINTS; k++)
        in.dac_v[k] = v[fmu_var_vr(FMU_G_DAC, k)];
    in.estop = v[fmu_var_vr(FMU_G_ESTOP, 0)] != 0;
    in.reset = v[fmu_var_vr(FMU_G_RESET, 0)] != 0;
    in.amp_enable = v[fmu_var_vr(FMU_G_AMP_ENABLE, 0)] != 0;
    for (left = (long)n; left > 0; left--) {
        int l = fmu_plant_step(plant(s), &in, now(s), &o, plant_say, s);
        level = l > level ? l : level;
        st(s)->periods += 1;
        for (k = 0; k < FMU_JOINTS; k++)
            index[k] |= o.index[k];
    }
    for (k = 0; k < FMU_JOINTS; k++)
        o.index[k] = index[k];          /* a pulse in any period of the step */
    st(s)->steps += 1;
    put_outputs(s, &o);
    *eventHandlingNeeded = fmi3False;
    *terminateSimulation = fmi3False;
    *earlyReturn = fmi3False;
    *lastSuccessfulTime = now(s);
    return level == FMU_SAY_WARNING ? fmi3Warning : fmi3OK;
}

/* ---- getting and setting values ---- */

/* FMI name of a variable's type. */
static const char *fmi_type_name(fmu_type t)
{
    static const char *const names[] = {"Float64", "Int32", "UInt32", "Enumeration", "Boolean"};
    return names[t];
}

/* 1 if the call may access every vr (modes, types, causality, counts), else 0 after a message. */
static int check_access(instance_t *s, const char *fn, const fmi3ValueReference vr[], size_t nvr, const void *values,
                        size_t nvalues, int type, int set)
{
    size_t i;
    if (nvr && (!vr || !values)) {
        say(s, FMU_SAY_ERROR, "%s: %s: %s is NULL with %zu value references", s->name, fn, vr ? "values" : "vr", nvr);
        return 0;
    }
    if (nvalues != nvr) {
        say(s, FMU_SAY_ERROR, "%s: %s: %zu values for %zu value references; every variable here is a scalar",
            s->name, fn, nvalues, nvr);
        return 0;
    }
    for (i = 0; i < nvr; i++) {
        fmu_var v;
        if (fmu_var_get(vr[i], &v)) {
            say(s, FMU_SAY_ERROR, "%s: %s: value reference %u names no variable (0 to %u; modelDescription.xml)",
                s->name, fn, vr[i], s->nvars - 1);
            return 0;
        }
        if ((int)v.type != type) {
            say(s, FMU_SAY_ERROR, "%s: %s: %s (value reference %u) is a %s: use fmi3%s%s", s->name, fn, v.name,
                vr[i], fmi_type_name(v.type), set ? "Set" : "Get", v.type == FMU_ENUM ? "Int64" : fmi_type_name(v.type));
            return 0;
        }
        if (set && (v.causality == FMU_OUTPUT || v.causality == FMU_INDEPENDENT)) {
            say(s, FMU_SAY_ERROR, "%s: %s: %s is %s: it cannot be set", s->name, fn, v.name,
                v.causality == FMU_OUTPUT ? "an output" : "the independent variable");
            return 0;
        }
        if (set && v.causality == FMU_PARAMETER && !(st(s)->mode & (MODE_INSTANTIATED | MODE_INIT))) {
            say(s, FMU_SAY_ERROR, "%s: %s: parameter %s is fixed once initialized (%s now): set it before "
                "fmi3ExitInitializationMode, or call fmi3Reset first", s->name, fn, v.name, mode_name(st(s)->mode));
            return 0;
        }
        if (set && v.causality == FMU_INPUT && !(st(s)->mode & (MODE_INSTANTIATED | MODE_INIT | MODE_STEP))) {
            say(s, FMU_SAY_ERROR, "%s: %s: input %s cannot be set in %s", s->name, fn, v.name, mode_name(st(s)->mode));
            return 0;
        }
    }
    return 1;
}

/* Before a get: outputs of a board not built yet are computed (0, or -1 after the plant's messages). */
static int refresh(instance_t *s, const char *fn, const fmi3ValueReference vr[], size_t nvr)
{
    size_t i;
    for (i = 0; i < nvr; i++) {
        fmu_var v;
        fmu_var_get(vr[i], &v);
        if (v.causality == FMU_OUTPUT)
            return build(s, fn);
    }
    return 0;
}

/* 1 if variable vr takes x (fmu_var_refuse), else 0 after a message naming the rule and the value kept. */
static int value_ok(instance_t *s, const char *fn, fmi3ValueReference vr, double x)
{
    char why[400], a[32], b[32];
    fmu_var v;
    fmu_var_get(vr, &v);
    if (!fmu_var_refuse(&v, x, vals(s), why, sizeof why))
        return 1;
    say(s, FMU_SAY_ERROR, "%s: %s: parameter %s = %s%s%s refused: %s; it keeps %s%s%s", s->name, fn, v.name,
        fmu_num(a, x), v.unit ? " " : "", v.unit ? v.unit : "", why, fmu_num(b, vals(s)[vr]), v.unit ? " " : "",
        v.unit ? v.unit : "");
    return 0;
}

/* Store a set value (a Boolean as 0 or 1, whatever byte the importer's bool held; the period as the whole
 * nanoseconds it puts in force, so that fmi3Get returns the period stepped); a parameter makes the board be
 * built again. */
static void store(instance_t *s, fmi3ValueReference vr, double x)
{
    fmu_var v;
    fmu_var_get(vr, &v);
    if (v.causality == FMU_PARAMETER)
        st(s)->built = 0;
    if (v.type == FMU_BOOLEAN)
        x = (double)(x != 0.0);
    else if (v.group == FMU_G_PERIOD)
        x = fmu_plant_period_in_force_s(x);
    vals(s)[vr] = x;
}

/* fmi3Get<T> and fmi3Set<T> for a type with variables (T its FMI name, C its C type, F its fmu_type). */
#define GET_SET(T, C, F)                                                                                       \
    fmi3Status fmi3Get##T(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, C values[],       \
                          size_t nValues)                                                                       \
    {                                                                                                          \
        instance_t *s = inst_of(instance);                                                                     \
        size_t i;                                                                                              \
        if (!s || !check_access(s, "fmi3Get" #T, vr, nvr, values, nValues, F, 0) ||                            \
            refresh(s, "fmi3Get" #T, vr, nvr))                                                                 \
            return fmi3Error;                                                                                  \
        for (i = 0; i < nvr; i++)                                                                              \
            values[i] = (C)vals(s)[vr[i]];                                                                     \
        return fmi3OK;                                                                                         \
    }                                                                                                          \
    fmi3Status fmi3Set##T(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const C values[], \
                          size_t nValues)                                                                       \
    {                                                                                                          \
        instance_t *s = inst_of(instance);                                                                     \
        size_t i;                                                                                              \
        if (!s || !check_access(s, "fmi3Set" #T, vr, nvr, values, nValues, F, 1))                              \
            return fmi3Error;                                                                                  \
        for (i = 0; i < nvr; i++)     /* every value checked before any is stored */                           \
            if (!value_ok(s, "fmi3Set" #T, vr[i], (double)values[i]))                                          \
                return fmi3Error;                                                                              \
        for (i = 0; i < nvr; i++)                                                                              \
            store(s, vr[i], (double)values[i]);                                                                \
        return fmi3OK;                                                                                         \
    }

GET_SET(Float64, fmi3Float64, FMU_FLOAT64)
GET_SET(Int32, fmi3Int32, FMU_INT32)
GET_SET(UInt32, fmi3UInt32, FMU_UINT32)
GET_SET(Int64, fmi3Int64, FMU_ENUM)
GET_SET(Boolean, fmi3Boolean, FMU_BOOLEAN)
/* types this FMU has no variable of: only empty lists pass */
GET_SET(Float32, fmi3Float32, -1)
GET_SET(Int8, fmi3Int8, -1)
GET_SET(UInt8, fmi3UInt8, -1)
GET_SET(Int16, fmi3Int16, -1)
GET_SET(UInt16, fmi3UInt16, -1)
GET_SET(UInt64, fmi3UInt64, -1)

/* No String variables: only empty lists pass. */
fmi3Status fmi3GetString(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, fmi3String values[],
                         size_t nValues)
{
    instance_t *s = inst_of(instance);
    return s && check_access(s, "fmi3GetString", vr, nvr, values, nValues, -1, 0) ? fmi3OK : fmi3Error;
}

/* No String variables: only empty lists pass. */
fmi3Status fmi3SetString(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const fmi3String values[],
                         size_t nValues)
{
    instance_t *s = inst_of(instance);
    return s && check_access(s, "fmi3SetString", vr, nvr, values, nValues, -1, 1) ? fmi3OK : fmi3Error;
}

/* No Binary variables: only empty lists pass. */
fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, size_t valueSizes[],
                         fmi3Binary values[], size_t nValues)
{
    instance_t *s = inst_of(instance);
    (void)valueSizes;
    return s && check_access(s, "fmi3GetBinary", vr, nvr, values, nValues, -1, 0) ? fmi3OK : fmi3Error;
}

/* No Binary variables: only empty lists pass. */
fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const size_t valueSizes[],
                         const fmi3Binary values[], size_t nValues)
{
    instance_t *s = inst_of(instance);
    (void)valueSizes;
    return s && check_access(s, "fmi3SetBinary", vr, nvr, values, nValues, -1, 1) ? fmi3OK : fmi3Error;
}

/* ---- FMU state ---- */

/* The saved state behind an fmi3FMUState of this instance's size, or 0 after a message. */
static saved_t *saved_of(instance_t *s, const char *fn, fmi3FMUState state)
{
    saved_t *p = state;
    if (p && p->magic == STATE_MAGIC && p->size == s->blob_size)
        return p;
    say(s, FMU_SAY_ERROR, "%s: %s: the FMU state is %s; pass one fmi3GetFMUState or fmi3DeserializeFMUState of this "
        "FMU returned", s->name, fn, p ? "not one of this FMU's" : "NULL");
    return 0;
}

/* A new saved state of this instance's size, in its list, or 0 after a message. */
static saved_t *saved_new(instance_t *s, const char *fn)
{
    saved_t *p = malloc(sizeof *p + s->blob_size);
    if (!p) {
        say(s, FMU_SAY_ERROR, "%s: %s: out of memory", s->name, fn);
        return 0;
    }
    p->magic = STATE_MAGIC;
    p->size = s->blob_size;
    p->owner = s;
    p->prev = 0;
    p->next = s->states;
    if (s->states)
        s->states->prev = p;
    s->states = p;
    return p;
}

/* Take a saved state out of its instance's list and free it. */
static void saved_free(saved_t *p)
{
    instance_t *owner = p->owner;
    if (p->prev)
        p->prev->next = p->next;
    else
        owner->states = p->next;
    if (p->next)
        p->next->prev = p->prev;
    p->magic = 0;
    free(p);
}

/* Copy the instance's block into a new or the given state. */
fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    instance_t *s = inst_of(instance);
    saved_t *p;
    if (!s)
        return fmi3Error;
    if (!FMUState) {
        say(s, FMU_SAY_ERROR, "%s: fmi3GetFMUState: FMUState is NULL", s->name);
        return fmi3Error;
    }
    p = *FMUState ? saved_of(s, "fmi3GetFMUState", *FMUState) : saved_new(s, "fmi3GetFMUState");
    if (!p)
        return fmi3Error;
    memcpy(p->data, s->blob, s->blob_size);
    *FMUState = p;
    return fmi3OK;
}

/* Copy a state of this FMU back into the instance. */
fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{
    instance_t *s = inst_of(instance);
    saved_t *p = s ? saved_of(s, "fmi3SetFMUState", FMUState) : 0;
    if (!p)
        return fmi3Error;
    memcpy(s->blob, p->data, s->blob_size);
    return fmi3OK;
}

/* Free a state and clear the handle (a NULL pointer or handle: nothing to do). */
fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
    instance_t *s = inst_of(instance);
    saved_t *p;
    if (!s)
        return fmi3Error;
    if (!FMUState || !*FMUState)      /* FMI 3.0 (2.2.6.4): a NULL pointer is ignored */
        return fmi3OK;
    p = saved_of(s, "fmi3FreeFMUState", *FMUState);
    if (!p)
        return fmi3Error;
    saved_free(p);
    *FMUState = 0;
    return fmi3OK;
}

/* Header + block. */
fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState, size_t *size)
{
    instance_t *s = inst_of(instance);
    if (!s || !saved_of(s, "fmi3SerializedFMUStateSize", FMUState))
        return fmi3Error;
    if (!size) {
        say(s, FMU_SAY_ERROR, "%s: fmi3SerializedFMUStateSize: size is NULL", s->name);
        return fmi3Error;
    }
    *size = sizeof(serial_t) + s->blob_size;
    return fmi3OK;
}

/* The header of this instance's serialized states, checksum 0. */
static void header_of(const instance_t *s, serial_t *h)
{
    char magic[9];
    memset(h, 0, sizeof *h);
    snprintf(magic, sizeof magic, "%s%02d", SERIAL_PREFIX, FMU_SERIAL_FORMAT);
    memcpy(h->magic, magic, sizeof h->magic);
    memcpy(h->token, s->token, sizeof h->token);
    h->status_bytes = (uint32_t)sizeof(status_t);
    h->nvars = s->nvars;
    h->off_values = s->off_values;
    h->off_plant = s->off_plant;
    h->plant_bytes = fmu_plant_size();
    h->plant_layout = fmu_plant_layout();
    h->size = s->blob_size;
}

/* Header (magic and format, token, layout, size, checksum) + block. */
fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState, fmi3Byte serializedState[],
                                 size_t size)
{
    instance_t *s = inst_of(instance);
    saved_t *p = s ? saved_of(s, "fmi3SerializeFMUState", FMUState) : 0;
    serial_t h;
    if (!p)
        return fmi3Error;
    if (!serializedState || size != sizeof h + s->blob_size) {
        say(s, FMU_SAY_ERROR, "%s: fmi3SerializeFMUState: a buffer of %zu bytes%s; give one of the size "
            "fmi3SerializedFMUStateSize says (%zu)", s->name, size, serializedState ? "" : " (NULL)",
            sizeof h + s->blob_size);
        return fmi3Error;
    }
    header_of(s, &h);
    h.checksum = fmu_hash(p->data, s->blob_size);
    memcpy(serializedState, &h, sizeof h);
    memcpy(serializedState + sizeof h, p->data, s->blob_size);
    return fmi3OK;
}

/* 1 if x is a whole number in [0, 2^53]. */
static int is_count(double x)
{
    return x >= 0 && x <= 9007199254740992.0 && x == floor(x);
}

/* What is wrong with the content of a block of unknown origin (status,
 * values, plant) for instance s, into why; 0 when it can be a state of
 * this FMU. The values must pass their rules (fmu_var_refuse), a built
 * plant its check against the core's build of the values (fmu_plant_check). */
static int block_wrong(const instance_t *s, const unsigned char *blob, char *why, size_t len)
{
    const status_t *t = (const status_t *)(const void *)blob;
    const double *v = (const double *)(const void *)(blob + s->off_values);
    const void *pl = blob + s->off_plant;
    char rule[400];
    double limit;
    unsigned vr;
    if (!(t->mode == MODE_INSTANTIATED || t->mode == MODE_INIT || t->mode == MODE_STEP ||
          t->mode == MODE_TERMINATED) || (t->built != 0 && t->built != 1) ||
        ((t->mode & (MODE_STEP | MODE_TERMINATED)) && !t->built)) {
        snprintf(why, len, "in no mode of this FMU (mode %d, built %d)", t->mode, t->built);
        return -1;
    }
    /* before Step Mode the period may still change (fmi3ExitInitializationMode checks the start time against
     * the one in force, as fmi3EnterInitializationMode against the parameter's): the longest bounds it */
    limit = time_limit(t->mode & (MODE_STEP | MODE_TERMINATED) ? t->period_s : fmu_plant_period_max_s());
    if (!(isfinite(t->period_s) && t->period_s >= fmu_plant_period_min_s() &&
          t->period_s <= fmu_plant_period_max_s()) || !isfinite(t->start_time) || !(fabs(t->start_time) < limit) ||
        !is_count(t->periods) || !is_count(t->steps) || t->steps > t->periods ||
        (!(t->mode & (MODE_STEP | MODE_TERMINATED)) && (t->periods || t->steps)) ||
        !(fabs(t->start_time + t->periods * t->period_s) < limit) || !(t->stop_time >= t->start_time)) {
        snprintf(why, len, "not at a time of this FMU (start %.17g s, %.17g periods of %.17g s, %.17g steps, "
                 "stop %.17g s)", t->start_time, t->periods, t->period_s, t->steps, t->stop_time);
        return -1;
    }
    for (vr = 0; vr < s->nvars; vr++) {
        fmu_var var;
        double x = v[vr];
        fmu_var_get(vr, &var);
        if (fmu_var_refuse(&var, x, v, rule, sizeof rule)) {
            snprintf(why, len, "of a parameter value the FMU refuses: %s = %.17g %s", var.name, x, rule);
            return -1;
        }
        if ((var.type == FMU_BOOLEAN && x != 0 && x != 1) ||
            (var.type == FMU_INT32 && !(x >= -2147483648.0 && x <= 2147483647.0 && x == floor(x))) ||
            (var.causality == FMU_OUTPUT && !isfinite(x)) ||
            (var.causality == FMU_INDEPENDENT && x != t->start_time + t->periods * t->period_s)) {
            snprintf(why, len, "of a value no variable of its type holds: %s = %.17g", var.name, x);
            return -1;
        }
    }
    if (t->built) {
        fmu_plant_setup setup;
        char what[200];
        setup_of(v, &setup);
        if (fmu_plant_check(pl, &setup, what, sizeof what)) {
            snprintf(why, len, "not a machine of its parameters: %s", what);
            return -1;
        }
        if (t->period_s != fmu_plant_period_s(pl)) {
            snprintf(why, len, "at a time step (%.17g s) that is not its period's", t->period_s);
            return -1;
        }
    }
    return 0;
}

/* A state from serialized bytes of this build, checked. */
fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[], size_t size,
                                   fmi3FMUState *FMUState)
{
    instance_t *s = inst_of(instance);
    const char *why = 0;
    char content[600];
    unsigned char *blob = 0;
    serial_t h, mine;
    saved_t *p;
    if (!s)
        return fmi3Error;
    memset(&h, 0, sizeof h);
    header_of(s, &mine);
    if (size == 0)
        why = "empty (0 bytes): no state of this FMU";
    else if (!serializedState || !FMUState)
        why = "missing (serializedState or FMUState is NULL)";
    else if (size < sizeof h)
        why = "too short to be a state of this FMU";
    if (!why) {
        memcpy(&h, serializedState, sizeof h);
        if (memcmp(h.magic, SERIAL_PREFIX, strlen(SERIAL_PREFIX)) != 0)
            why = "not a serialized state of this FMU (no header)";
        else if (memcmp(h.magic, mine.magic, sizeof h.magic) != 0)
            why = "in another format (written by another version of the FMU): restore it with the FMU that saved it";
        else if (memcmp(h.token, s->token, sizeof h.token) != 0)
            why = "written by another build of the FMU (another instantiation token): restore it with the FMU "
                  "that saved it";
        else if (h.status_bytes != mine.status_bytes || h.nvars != mine.nvars || h.off_values != mine.off_values ||
                 h.off_plant != mine.off_plant || h.plant_bytes != mine.plant_bytes ||
                 h.plant_layout != mine.plant_layout)
            why = "of another layout (written by another build of the FMU's core): restore it with the FMU that "
                  "saved it";
        else if (h.size != s->blob_size || size != sizeof h + s->blob_size)
            why = "of the wrong size for this FMU";
        else if (h.checksum != fmu_hash(serializedState + sizeof h, s->blob_size))
            why = "damaged (checksum)";
    }
    if (!why) {                       /* the content, in an aligned copy */
        blob = malloc(s->blob_size);
        if (!blob)
            why = "not checked: out of memory";
        else {
            memcpy(blob, serializedState + sizeof h, s->blob_size);
            if (block_wrong(s, blob, content, sizeof content))
                why = content;
            else if (((const status_t *)(const void *)blob)->built)
                fmu_plant_forget(blob + s->off_plant);   /* its caches were not checked */
        }
    }
    if (why) {
        say(s, FMU_SAY_ERROR, "%s: fmi3DeserializeFMUState: the serialized state is %s", s->name, why);
        free(blob);
        return fmi3Error;
    }
    p = *FMUState ? saved_of(s, "fmi3DeserializeFMUState", *FMUState) : saved_new(s, "fmi3DeserializeFMUState");
    if (!p) {
        free(blob);
        return fmi3Error;
    }
    memcpy(p->data, blob, s->blob_size);
    free(blob);
    *FMUState = p;
    return fmi3OK;
}

/* ---- what this FMU does not have: fmi3Error with the reason ---- */

/* The message of an unsupported call; fmi3Error. */
static fmi3Status unsupported(fmi3Instance instance, const char *fn)
{
    instance_t *s = inst_of(instance);
    if (s)
        say(s, FMU_SAY_ERROR, "%s: %s: not supported: this FMU is co-simulation only, without event mode, clocks, "
            "configuration mode or derivatives (docs/fmu.md)", s->name, fn);
    return fmi3Error;
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterEventMode");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3EnterStepMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterStepMode");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterConfigurationMode");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3ExitConfigurationMode");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, fmi3Clock values[])
{
    (void)vr, (void)nvr, (void)values;
    return unsupported(instance, "fmi3GetClock");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, const fmi3Clock values[])
{
    (void)vr, (void)nvr, (void)values;
    return unsupported(instance, "fmi3SetClock");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance, fmi3ValueReference vr, size_t *n)
{
    (void)vr, (void)n;
    return unsupported(instance, "fmi3GetNumberOfVariableDependencies");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[], fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[], fmi3DependencyKind dependencyKinds[],
                                       size_t nDependencies)
{
    (void)dependent, (void)elementIndicesOfDependent, (void)independents, (void)elementIndicesOfIndependents;
    (void)dependencyKinds, (void)nDependencies;
    return unsupported(instance, "fmi3GetVariableDependencies");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,
                                        const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[],
                                        size_t nSeed, fmi3Float64 sensitivity[], size_t nSensitivity)
{
    (void)unknowns, (void)nUnknowns, (void)knowns, (void)nKnowns, (void)seed, (void)nSeed, (void)sensitivity;
    (void)nSensitivity;
    return unsupported(instance, "fmi3GetDirectionalDerivative");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,
                                    const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[],
                                    size_t nSeed, fmi3Float64 sensitivity[], size_t nSensitivity)
{
    (void)unknowns, (void)nUnknowns, (void)knowns, (void)nKnowns, (void)seed, (void)nSeed, (void)sensitivity;
    (void)nSensitivity;
    return unsupported(instance, "fmi3GetAdjointDerivative");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                  fmi3Float64 intervals[], fmi3IntervalQualifier qualifiers[])
{
    (void)vr, (void)nvr, (void)intervals, (void)qualifiers;
    return unsupported(instance, "fmi3GetIntervalDecimal");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetIntervalFraction(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                   fmi3UInt64 counters[], fmi3UInt64 resolutions[], fmi3IntervalQualifier qualifiers[])
{
    (void)vr, (void)nvr, (void)counters, (void)resolutions, (void)qualifiers;
    return unsupported(instance, "fmi3GetIntervalFraction");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetShiftDecimal(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr, fmi3Float64 shifts[])
{
    (void)vr, (void)nvr, (void)shifts;
    return unsupported(instance, "fmi3GetShiftDecimal");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetShiftFraction(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                fmi3UInt64 counters[], fmi3UInt64 resolutions[])
{
    (void)vr, (void)nvr, (void)counters, (void)resolutions;
    return unsupported(instance, "fmi3GetShiftFraction");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                  const fmi3Float64 intervals[])
{
    (void)vr, (void)nvr, (void)intervals;
    return unsupported(instance, "fmi3SetIntervalDecimal");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3SetIntervalFraction(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                   const fmi3UInt64 counters[], const fmi3UInt64 resolutions[])
{
    (void)vr, (void)nvr, (void)counters, (void)resolutions;
    return unsupported(instance, "fmi3SetIntervalFraction");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3SetShiftDecimal(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                               const fmi3Float64 shifts[])
{
    (void)vr, (void)nvr, (void)shifts;
    return unsupported(instance, "fmi3SetShiftDecimal");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3SetShiftFraction(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                const fmi3UInt64 counters[], const fmi3UInt64 resolutions[])
{
    (void)vr, (void)nvr, (void)counters, (void)resolutions;
    return unsupported(instance, "fmi3SetShiftFraction");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EvaluateDiscreteStates");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation, fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged, fmi3Boolean *nextEventTimeDefined,
                                    fmi3Float64 *nextEventTime)
{
    (void)discreteStatesNeedUpdate, (void)terminateSimulation, (void)nominalsOfContinuousStatesChanged;
    (void)valuesOfContinuousStatesChanged, (void)nextEventTimeDefined, (void)nextEventTime;
    return unsupported(instance, "fmi3UpdateDiscreteStates");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterContinuousTimeMode");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance, fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode, fmi3Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint, (void)enterEventMode, (void)terminateSimulation;
    return unsupported(instance, "fmi3CompletedIntegratorStep");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time)
{
    (void)time;
    return unsupported(instance, "fmi3SetTime");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    (void)continuousStates, (void)nContinuousStates;
    return unsupported(instance, "fmi3SetContinuousStates");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[],
                                             size_t nContinuousStates)
{
    (void)derivatives, (void)nContinuousStates;
    return unsupported(instance, "fmi3GetContinuousStateDerivatives");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[], size_t nEventIndicators)
{
    (void)eventIndicators, (void)nEventIndicators;
    return unsupported(instance, "fmi3GetEventIndicators");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[], size_t nContinuousStates)
{
    (void)continuousStates, (void)nContinuousStates;
    return unsupported(instance, "fmi3GetContinuousStates");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[],
                                             size_t nContinuousStates)
{
    (void)nominals, (void)nContinuousStates;
    return unsupported(instance, "fmi3GetNominalsOfContinuousStates");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t *nEventIndicators)
{
    (void)nEventIndicators;
    return unsupported(instance, "fmi3GetNumberOfEventIndicators");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t *nContinuousStates)
{
    (void)nContinuousStates;
    return unsupported(instance, "fmi3GetNumberOfContinuousStates");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance, const fmi3ValueReference vr[], size_t nvr,
                                    const fmi3Int32 orders[], fmi3Float64 values[], size_t nValues)
{
    (void)vr, (void)nvr, (void)orders, (void)values, (void)nValues;
    return unsupported(instance, "fmi3GetOutputDerivatives");
}

/* Not supported here: fmi3Error with the reason. */
fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{
    (void)clockReference, (void)activationTime;
    return unsupported(instance, "fmi3ActivateModelPartition");
}
