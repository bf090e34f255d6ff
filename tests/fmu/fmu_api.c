/* fmu_api.c - the FMU through its FMI 3.0 functions: state save and
 * restore (fmi3GetFMUState/SetFMUState, serialization) continue
 * bit-identically, forged serialized states are refused, two instances
 * share nothing, a step of n periods is n steps of one, fmi3Reset starts
 * over, an importer keeping its time as t += h stays in step, parameters
 * outside their declared range are refused by fmi3Set, and every refused
 * call returns fmi3Error with a message and changes nothing. Run by
 * tests/fmu/test_fmu_api. */
#include <malloc.h>                /* mallinfo2: the heap in use (glibc) */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include "fmu_test.h"
#include "fmu_state.h"
#include "hg_board.h"             /* the board's fields, to forge states (a plant begins with its hg_board) */
#include "hg_model.h"             /* the Hexaglide's data (hg_data at the start of the board's plant data) */

#define PERIOD 0.001
#define MAX_OUT 256

/* Every output and the time, as doubles (bit patterns compared). */
static int outputs(fmi3Instance s, double *out)
{
    unsigned vr, n = fmu_var_count();
    int m = 0;
    for (vr = 0; vr < n; vr++) {
        fmu_var v;
        fmi3ValueReference r = vr;
        fmu_var_get(vr, &v);
        if (v.causality != FMU_OUTPUT && v.causality != FMU_INDEPENDENT)
            continue;
        if (v.type == FMU_FLOAT64) {
            fmi3GetFloat64(s, &r, 1, &out[m], 1);
        } else if (v.type == FMU_INT32) {
            fmi3Int32 x = 0;
            fmi3GetInt32(s, &r, 1, &x, 1);
            out[m] = x;
        } else {
            fmi3Boolean x = 0;
            fmi3GetBoolean(s, &r, 1, &x, 1);
            out[m] = x;
        }
        m++;
    }
    return m;
}

/* The DAC volts of period i (a deterministic, varied drive). */
static void volts_of(long i, int salt, double v[6])
{
    int k;
    for (k = 0; k < 6; k++)
        v[k] = 2.5 * sin(0.013 * (double)i * (k + 1) + salt + k) + (k == 2 ? 0.7 : 0.0);
}

/* Set the six DAC inputs. */
static void set_volts(fmi3Instance s, const double v[6])
{
    fmi3ValueReference vr[6];
    int k;
    for (k = 0; k < 6; k++)
        vr[k] = fmu_var_vr(FMU_G_DAC, k);
    fmi3SetFloat64(s, vr, 6, v, 6);
}

/* n steps from period `from` with drive salt; outputs after each into rec (n x MAX_OUT). Steps that fail count. */
static int run(fmi3Instance s, long from, long n, int salt, double *rec)
{
    fmi3Boolean ev, term, early;
    double last, v[6];
    long i;
    int bad = 0;
    for (i = 0; i < n; i++) {
        volts_of(from + i, salt, v);
        set_volts(s, v);
        if (fmi3DoStep(s, (double)(from + i) * PERIOD, PERIOD, fmi3True, &ev, &term, &early, &last) != fmi3OK)
            bad++;
        if (rec)
            outputs(s, rec + i * MAX_OUT);
    }
    return bad;
}

/* Instantiate (loggingOn as given), set enc_scale, initialize: the FMU in Step Mode. */
static fmi3Instance started_logging(const char *name, logbook *b, double m_head, fmi3Boolean logging_on)
{
    fmi3Instance s = instantiate_logging(name, b, logging_on);
    if (!s)
        return 0;
    set_f64(s, "enc_scale", 1000.0);
    if (m_head > 0)
        set_f64(s, "m_head", m_head);
    if (fmi3EnterInitializationMode(s, fmi3False, 0, 0.0, fmi3False, 0) != fmi3OK ||
        fmi3ExitInitializationMode(s) != fmi3OK) {
        fmi3FreeInstance(s);
        return 0;
    }
    return s;
}

/* started_logging with loggingOn. */
static fmi3Instance started(const char *name, logbook *b, double m_head)
{
    return started_logging(name, b, m_head, fmi3True);
}

/* 1 if the n x MAX_OUT records are bitwise equal over m columns. */
static int same(const double *a, const double *b, long n, int m)
{
    long i;
    for (i = 0; i < n; i++)
        if (memcmp(a + i * MAX_OUT, b + i * MAX_OUT, (size_t)m * sizeof *a) != 0) // NOLINT(bugprone-suspicious-memory-comparison): bitwise on purpose
            return 0;
    return 1;
}

/* Save at 200, run 300, restore, run 300 again; serialized into a fresh instance too. */
static void test_state(void)
{
    logbook b = {0}, b2 = {0};
    fmi3Instance s = started("state", &b, 0), s2;
    fmi3FMUState st = 0, st2 = 0, reused;
    fmi3Byte *bytes;
    size_t size = 0;
    double *r1 = calloc(300 * MAX_OUT, sizeof *r1), *r2 = calloc(300 * MAX_OUT, sizeof *r2);
    int m, bad, rc;
    if (!s || !r1 || !r2) {
        check(0, "state: instance and buffers");
        free(r1), free(r2), fmi3FreeInstance(s);
        return;
    }
    m = outputs(s, r1);
    bad = run(s, 0, 200, 0, 0);
    check(fmi3GetFMUState(s, &st) == fmi3OK && st, "fmi3GetFMUState after 200 periods");
    bad += run(s, 200, 300, 0, r1);
    check(fmi3SetFMUState(s, st) == fmi3OK, "fmi3SetFMUState back to period 200");
    bad += run(s, 200, 300, 0, r2);
    check(bad == 0 && same(r1, r2, 300, m), "restored state continues bit-identically: 300 periods x %d outputs", m);
    reused = st;
    check(fmi3GetFMUState(s, &reused) == fmi3OK && reused == st, "fmi3GetFMUState into an existing state reuses it");
    check(fmi3SetFMUState(s, st) == fmi3OK, "... and it holds the state at 500 periods");
    memset(r2, 0, 300 * MAX_OUT * sizeof *r2);
    run(s, 500, 1, 0, r2);
    rc = fmi3SerializedFMUStateSize(s, st, &size);
    check(rc == fmi3OK && size > 0, "serialized size %zu bytes", size);
    bytes = malloc(size ? size : 1);
    check(bytes && fmi3SerializeFMUState(s, st, bytes, size) == fmi3OK, "fmi3SerializeFMUState");
    s2 = instantiate("restored", &b2);
    check(s2 && fmi3DeserializeFMUState(s2, bytes, size, &st2) == fmi3OK && fmi3SetFMUState(s2, st2) == fmi3OK,
          "a fresh instance deserializes it and takes it (Instantiated -> the saved Step Mode)");
    memset(r1, 0, 300 * MAX_OUT * sizeof *r1);
    bad = run(s2, 500, 1, 0, r1);
    check(bad == 0 && same(r1, r2, 1, m), "the deserialized state continues bit-identically");
    /* damaged, truncated, foreign */
    if (bytes) {
        bytes[size - 1] ^= 1;
        check(fmi3DeserializeFMUState(s2, bytes, size, &st2) == fmi3Error && strstr(b2.last, "checksum"),
              "a damaged serialized state is refused (%s)", b2.last);
        check(fmi3DeserializeFMUState(s2, bytes, size - 1, &st2) == fmi3Error, "a truncated one is refused (%s)",
              b2.last);
        memset(bytes, 'x', size);
        check(fmi3DeserializeFMUState(s2, bytes, size, &st2) == fmi3Error, "bytes of no state are refused (%s)",
              b2.last);
        check(fmi3SetFMUState(s2, (fmi3FMUState)bytes) == fmi3Error, "a pointer to no FMU state is refused (%s)",
              b2.last);
    }
    check(fmi3FreeFMUState(s, &st) == fmi3OK && st == 0 && fmi3FreeFMUState(s2, &st2) == fmi3OK,
          "fmi3FreeFMUState frees and clears the handle");
    free(bytes);
    free(r1);
    free(r2);
    fmi3FreeInstance(s);
    fmi3FreeInstance(s2);
}

/* Two instances interleaved (other drive, other head mass) equal each run alone. */
static void test_two_instances(void)
{
    logbook ba = {0}, bb = {0};
    double *a1 = calloc(400 * MAX_OUT, sizeof *a1), *b1 = calloc(400 * MAX_OUT, sizeof *b1);
    double *a2 = calloc(400 * MAX_OUT, sizeof *a2), *b2 = calloc(400 * MAX_OUT, sizeof *b2);
    fmi3Instance a = started("a", &ba, 0), b = started("b", &bb, 9.5);
    long i;
    int m = 0, bad = 0;
    if (!a1 || !b1 || !a2 || !b2 || !a || !b) {
        check(0, "two instances: instances and buffers");
        free(a1), free(b1), free(a2), free(b2), fmi3FreeInstance(a), fmi3FreeInstance(b);
        return;
    }
    for (i = 0; i < 400; i++) {
        bad += run(a, i, 1, 0, a1 + i * MAX_OUT);
        bad += run(b, i, 1, 7, b1 + i * MAX_OUT);
    }
    fmi3FreeInstance(a);
    fmi3FreeInstance(b);
    a = started("a alone", &ba, 0);
    m = outputs(a, a2);
    bad += run(a, 0, 400, 0, a2);
    fmi3FreeInstance(a);
    b = started("b alone", &bb, 9.5);
    bad += run(b, 0, 400, 7, b2);
    fmi3FreeInstance(b);
    check(bad == 0 && same(a1, a2, 400, m) && same(b1, b2, 400, m),
          "two instances in one process, interleaved, each equal to its run alone (400 periods, %d outputs)", m);
    check(memcmp(a1 + 399 * MAX_OUT, b1 + 399 * MAX_OUT, (size_t)m * sizeof *a1) != 0, // NOLINT(bugprone-suspicious-memory-comparison): bitwise
          "... and they differ from each other (they are two machines)");
    free(a1), free(b1), free(a2), free(b2);
}

/* A state saved in Initialization Mode after a period change round-trips through serialization, whatever
 * the start time the change leaves (fmi3ExitInitializationMode is what refuses a start time the period in
 * force cannot keep: the deserializer refused it first, from 8e6 s with a 1 us period). */
static void refused(fmi3Status rc, logbook *b, int errors_before, const char *what, const char *desc);

static void test_state_init(void)
{
    logbook b = {0};
    fmi3Instance s = instantiate("state-init", &b);
    fmi3FMUState st = 0, st2 = 0;
    fmi3Byte *bytes = 0;
    size_t size = 0;
    int e;
    b.quiet = 1;
    check(fmi3EnterInitializationMode(s, 0, 0, 8e6, 0, 0) == fmi3OK && set_f64(s, "period", 1e-6) == fmi3OK,
          "from 8e6 s, period 1 us set in Initialization Mode");
    (void)get_f64(s, "z_0");                     /* an output read builds the machine with that period */
    check(fmi3GetFMUState(s, &st) == fmi3OK && fmi3SerializedFMUStateSize(s, st, &size) == fmi3OK &&
          (bytes = malloc(size)) && fmi3SerializeFMUState(s, st, bytes, size) == fmi3OK &&
          fmi3DeserializeFMUState(s, bytes, size, &st2) == fmi3OK && fmi3SetFMUState(s, st2) == fmi3OK,
          "its state serializes, deserializes and is set again (%s)", b.last);
    e = b.n[fmi3Error];
    refused(fmi3ExitInitializationMode(s), &b, e, "startTime", "fmi3ExitInitializationMode from 8e6 s at 1 us");
    fmi3FreeFMUState(s, &st);
    fmi3FreeFMUState(s, &st2);
    free(bytes);
    fmi3FreeInstance(s);
}

/* A step of 5 periods = 5 steps of 1 (inputs held); a pulse of index in any period shows. */
static void test_multi_period(void)
{
    logbook b = {0};
    fmi3Instance s = started("five", &b, 0), t = started("ones", &b, 0);
    fmi3Boolean ev, term, early;
    double last, v[6] = {3, -3, 2, -2, 1, -1}, r5[MAX_OUT], r1[MAX_OUT];
    int i, m, ok5, ok1 = 1;
    if (!s || !t) {
        check(0, "multi-period: instances");
        return;
    }
    set_volts(s, v);
    set_volts(t, v);
    ok5 = fmi3DoStep(s, 0.0, 5 * PERIOD, fmi3True, &ev, &term, &early, &last) == fmi3OK;
    for (i = 0; i < 5; i++)
        ok1 &= fmi3DoStep(t, i * PERIOD, PERIOD, fmi3True, &ev, &term, &early, &last) == fmi3OK;
    m = outputs(s, r5);
    outputs(t, r1);
    /* index_k: the single-period run shows only the last period's pulses; compare the rest */
    check(ok5 && ok1 && fabs(last - 5 * PERIOD) < 1e-15, "a step of 5 periods and 5 steps of 1 period both succeed");
    {
        int same_but_index = 1;
        unsigned vr, n = fmu_var_count(), col = 0;
        for (vr = 0; vr < n; vr++) {
            fmu_var var;
            fmu_var_get(vr, &var);
            if (var.causality != FMU_OUTPUT && var.causality != FMU_INDEPENDENT)
                continue;
            if (var.group != FMU_G_INDEX && memcmp(&r5[col], &r1[col], sizeof r5[col]) != 0) // NOLINT(bugprone-suspicious-memory-comparison): bitwise
                same_but_index = 0;
            col++;
        }
        check(same_but_index, "... with bit-identical outputs (%d of them)", m);
    }
    {
        fmi3ValueReference vr = fmu_var_vr(FMU_G_INDEX, 1);
        fmi3Boolean x5 = 0;
        fmi3GetBoolean(s, &vr, 1, &x5, 1);
        check(x5 == fmi3True, "index_1 of the 5-period step is TRUE: joint 1 at -3 V passes HOME's index in its "
              "first period (z = 0 lies on an index)");
    }
    fmi3FreeInstance(s);
    fmi3FreeInstance(t);
}

/* fmi3Reset: the second run equals the first. */
static void test_reset(void)
{
    logbook b = {0};
    fmi3Instance s = started("reset", &b, 0);
    double *r1 = calloc(100 * MAX_OUT, sizeof *r1), *r2 = calloc(100 * MAX_OUT, sizeof *r2);
    int m = 0, bad;
    if (!s || !r1 || !r2) {
        check(0, "reset: instance and buffers");
        free(r1), free(r2), fmi3FreeInstance(s);
        return;
    }
    m = outputs(s, r1);
    bad = run(s, 0, 100, 3, r1);
    check(fmi3Reset(s) == fmi3OK, "fmi3Reset");
    set_f64(s, "enc_scale", 1000.0);
    bad += fmi3EnterInitializationMode(s, fmi3False, 0, 0.0, fmi3False, 0) != fmi3OK;
    bad += fmi3ExitInitializationMode(s) != fmi3OK;
    bad += run(s, 0, 100, 3, r2);
    check(bad == 0 && same(r1, r2, 100, m), "after fmi3Reset the same inputs give the same 100 periods");
    free(r1), free(r2);
    fmi3FreeInstance(s);
}

/* One refused call: fmi3Error, a new error message naming `what`. */
static void refused(fmi3Status rc, logbook *b, int errors_before, const char *what, const char *desc)
{
    check(rc == fmi3Error && b->n[fmi3Error] > errors_before && (!what || strstr(b->last, what)),
          "refused with fmi3Error and a message: %s (%s)", desc, b->last);
}

/* Every way to misuse the API returns fmi3Error with a message; the instance goes on as before. */
static void test_refusals(void)
{
    logbook b = {0};
    char token[FMU_TOKEN_LEN];
    fmi3Boolean ev, term, early;
    double last, x = 1, t_before;
    fmi3ValueReference vr;
    fmi3Int32 i32;
    fmi3Instance s;
    int e;
    b.quiet = 1;
    fmu_vars_token(token);
    e = b.n[fmi3Error];
    check(fmi3InstantiateCoSimulation("x", "{not-this-one}", "", 0, 0, 0, 0, 0, 0, &b, log_cb, 0) == 0 &&
          b.n[fmi3Error] > e && strstr(b.last, "token"), "instantiation with another token refused (%s)", b.last);
    e = b.n[fmi3Error];
    check(fmi3InstantiateCoSimulation("x", token, "", 0, 0, fmi3True, 0, 0, 0, &b, log_cb, 0) == 0 &&
          b.n[fmi3Error] > e, "eventModeUsed refused (%s)", b.last);
    e = b.n[fmi3Error];
    check(fmi3InstantiateModelExchange("x", token, "", 0, 0, &b, log_cb) == 0 && b.n[fmi3Error] > e,
          "model exchange refused (%s)", b.last);
    s = instantiate("refusals", &b);
    if (!s) {
        check(0, "refusals: instance");
        return;
    }
    e = b.n[fmi3Error];
    refused(fmi3DoStep(s, 0, PERIOD, 1, &ev, &term, &early, &last), &b, e, "Step Mode", "fmi3DoStep before init");
    e = b.n[fmi3Error];
    refused(fmi3ExitInitializationMode(s), &b, e, 0, "fmi3ExitInitializationMode before Enter");
    vr = vr_of("z_0");
    e = b.n[fmi3Error];
    refused(fmi3SetFloat64(s, &vr, 1, &x, 1), &b, e, "output", "setting an output");
    e = b.n[fmi3Error];
    refused(fmi3GetInt32(s, &vr, 1, &i32, 1), &b, e, "Float64", "fmi3GetInt32 of a Float64");
    vr = 100000;
    e = b.n[fmi3Error];
    refused(fmi3GetFloat64(s, &vr, 1, &x, 1), &b, e, "names no variable", "value reference 100000");
    vr = vr_of("dac_0");
    e = b.n[fmi3Error];
    refused(fmi3SetFloat64(s, &vr, 1, &x, 2), &b, e, "scalar", "2 values for 1 value reference");
    e = b.n[fmi3Error];
    refused(fmi3SetFloat64(s, &vr, 1, 0, 1), &b, e, "NULL", "values NULL");
    e = b.n[fmi3Error];
    {
        const fmi3Float32 f = 1;
        refused(fmi3SetFloat32(s, &vr, 1, &f, 1), &b, e, "use fmi3SetFloat64", "fmi3SetFloat32 of a Float64");
    }
    check(fmi3GetFloat32(s, 0, 0, 0, 0) == fmi3OK, "an empty fmi3GetFloat32 is fine");
    /* parameters that break rules between them: refused at fmi3ExitInitializationMode, which stays in
       Initialization Mode */
    set_f64(s, "f_static", 10);
    set_f64(s, "i_bar", 0.1);
    fmi3EnterInitializationMode(s, 0, 0, 0.0, 0, 0);
    e = b.n[fmi3Error];
    refused(fmi3ExitInitializationMode(s), &b, e, "refused", "f_static = 10 N below f_coulomb and i_bar = 0.1 kg m^2");
    check(b.n[fmi3Error] - e >= 3, "one message per refused parameter and one for the call (%d messages)",
          b.n[fmi3Error] - e);
    set_f64(s, "f_static", 50);
    set_f64(s, "i_bar", 1.0435);
    check(fmi3ExitInitializationMode(s) == fmi3OK, "valid values set in Initialization Mode: fmi3ExitInitializationMode "
          "succeeds");
    vr = vr_of("m_head");
    x = 7;
    e = b.n[fmi3Error];
    refused(fmi3SetFloat64(s, &vr, 1, &x, 1), &b, e, "fixed", "a parameter in Step Mode");
    t_before = get_f64(s, "time");
    e = b.n[fmi3Error];
    refused(fmi3DoStep(s, 0, 1.5 * PERIOD, 1, &ev, &term, &early, &last), &b, e, "whole number",
            "a step of 1.5 periods");
    e = b.n[fmi3Error];
    refused(fmi3DoStep(s, 0.5, PERIOD, 1, &ev, &term, &early, &last), &b, e, "not the FMU's time",
            "a step from another time");
    e = b.n[fmi3Error];
    refused(fmi3DoStep(s, 0.0 / 0.0, PERIOD, 1, &ev, &term, &early, &last), &b, e, "is not a time",
            "a step from a NaN time");
    e = b.n[fmi3Error];
    refused(fmi3DoStep(s, 0, 0.0 / 0.0, 1, &ev, &term, &early, &last), &b, e, 0, "a NaN step");
    e = b.n[fmi3Error];
    refused(fmi3DoStep(s, 0, 1e300, 1, &ev, &term, &early, &last), &b, e, 0, "a step of 1e300 s");
    check(get_f64(s, "time") == t_before && fmi3DoStep(s, 0, PERIOD, 1, &ev, &term, &early, &last) == fmi3OK &&
          last == PERIOD, "after the refused steps the time is unchanged and a valid step runs");
    e = b.n[fmi3Error];
    refused(fmi3EnterEventMode(s), &b, e, "not supported", "fmi3EnterEventMode");
    e = b.n[fmi3Error];
    refused(fmi3EnterConfigurationMode(s), &b, e, "not supported", "fmi3EnterConfigurationMode");
    e = b.n[fmi3Error];
    refused(fmi3SetDebugLogging(s, 1, 1, (const fmi3String[]){"logEverything"}), &b, e, "unknown category",
            "an unknown log category");
    check(fmi3Terminate(s) == fmi3OK, "fmi3Terminate");
    e = b.n[fmi3Error];
    refused(fmi3DoStep(s, PERIOD, PERIOD, 1, &ev, &term, &early, &last), &b, e, "Terminated", "a step after Terminate");
    e = fmi3GetFloat64(s, &vr, 1, &x, 1);
    check(e == fmi3OK && x == 6.697, "values can be read when terminated, and the refused m_head = 7 left the "
          "default: m_head = %g kg", x);
    check(fmi3DoStep(0, 0, PERIOD, 1, &ev, &term, &early, &last) == fmi3Error, "a NULL instance: fmi3Error");
    fmi3FreeInstance(s);
    fmi3FreeInstance(0);
}

/* Outputs before initialization: the machine at HOME at rest. */
static void test_before_init(void)
{
    logbook b = {0};
    fmi3Instance s = instantiate("early", &b);
    double z = get_f64(s, "z_0"), hz = get_f64(s, "head_z");
    fmi3ValueReference vr = vr_of("amps_on");
    fmi3Boolean on = 0;
    fmi3GetBoolean(s, &vr, 1, &on, 1);
    check(z == 0.0 && hz == 0.0, "outputs read in Instantiated: z_0 = %g m, head_z = %g m (HOME)", z, hz);
    fmi3FreeInstance(s);
}

/* One step of h from t (its status). */
static fmi3Status step_at(fmi3Instance s, double t, double h)
{
    fmi3Boolean ev, term, early;
    double last;
    return fmi3DoStep(s, t, h, fmi3True, &ev, &term, &early, &last);
}

/* An importer keeping its time as t += h (sum 1), the usual master loop, or as t0 + k h (sum 0, as
 * docs/fmu.md advises): n steps of one period from t0. The machine strikes first (+-10 V), so that
 * the periods after are cheap (state frozen): the time is the same. The step refused first (-1:
 * none); *drift the importer's time less the FMU's at the end. */
static long drift_run(double t0, double period, long n, int sum, double *drift)
{
    logbook b = {0};
    fmi3Instance s = instantiate("drift", &b);
    double t = t0, v[6] = {10, -10, 10, -10, 10, -10};
    long i;
    b.quiet = 1;
    if (!s)
        return 0;
    if (period != PERIOD)
        set_f64(s, "period", period);
    if (fmi3EnterInitializationMode(s, fmi3False, 0, t0, fmi3False, 0) != fmi3OK ||
        fmi3ExitInitializationMode(s) != fmi3OK) {
        printf("# %s\n", b.last);
        fmi3FreeInstance(s);
        return 0;
    }
    set_volts(s, v);
    for (i = 0; i < n; i++) {
        if (step_at(s, t, period) == fmi3Error) {
            printf("# step %ld from %.17g s: %s\n", i, t, b.last);
            break;
        }
        t = sum ? t + period : t0 + (double)(i + 1) * period;
    }
    *drift = t - get_f64(s, "time");
    fmi3FreeInstance(s);
    return i < n ? i : -1;
}

/* The time rule: an importer adding its steps in double stays in step (1 ms from 0 and from 1e4, 1e5,
 * 1e6 s, 50 us); a step or a time off by more than rounding is refused at once; a start time at which
 * a double cannot resolve 1e-6 of a period is refused, naming the bound. */
static void test_time(void)
{
    static const struct {
        double t0, period;
        long n;
        int sum;
    } runs[] = {{0, 1e-3, 400000, 1}, {1e4, 1e-3, 20000, 1}, {1e5, 1e-3, 20000, 1}, {1e6, 1e-3, 20000, 1},
                {0, 5e-5, 400000, 1}, {-0.5, 1e-3, 2000, 1}, {-0.5, 1e-3, 2000, 0}, {-0.3, 1e-3, 600, 0},
                {-10, 1e-3, 20000, 1}, {-10, 1e-3, 20000, 0}};
    logbook b = {0};
    fmi3Instance s;
    double drift = 0, t;
    size_t k;
    int e;
    for (k = 0; k < sizeof runs / sizeof runs[0]; k++) {
        long at = drift_run(runs[k].t0, runs[k].period, runs[k].n, runs[k].sum, &drift);
        double t_end = runs[k].t0 + (double)runs[k].n * runs[k].period;
        double big = fmax(fabs(runs[k].t0), fabs(t_end)), ulp = nextafter(big, INFINITY) - big;
        check(at < 0, "an importer with %s: %ld steps of %g s from %g s%s all taken; its time ends %.3g s (%.2g periods) off the FMU's, within the %.3g s that %ld sums may "
              "round by (half an ulp each, + 256 ulps)", runs[k].sum ? "t += h" : "t0 + k h", runs[k].n,
              runs[k].period, runs[k].t0, runs[k].t0 < 0 ? " (through 0)" : "", drift, drift / runs[k].period, (0.5 * (double)runs[k].n + 256) * ulp,
              runs[k].n);
    }
    b.quiet = 1;
    s = started("sync", &b, 0);
    if (!s) {
        check(0, "time: instance");
        return;
    }
    e = b.n[fmi3Error];
    refused(step_at(s, 0, 0.0010000009), &b, e, "not a whole number", "a step of 1.0000009 ms (off by 9e-10 s) at "
            "the first step");
    check(step_at(s, 0, PERIOD) == fmi3OK && step_at(s, PERIOD, PERIOD) == fmi3OK, "steps of 1 ms from 0 run");
    t = 2 * PERIOD;
    e = b.n[fmi3Error];
    refused(step_at(s, t + PERIOD, PERIOD), &b, e, "not the FMU's time", "a step from one period ahead");
    e = b.n[fmi3Error];
    refused(step_at(s, t + 1e-9, PERIOD), &b, e, "not the FMU's time", "a step from 1 ns ahead");
    check(step_at(s, nextafter(nextafter(t, 1), 1), PERIOD) == fmi3OK, "a step from 2 ulps past the FMU's time runs "
          "(the rounding of an importer's sum)");
    fmi3FreeInstance(s);
    /* start times: the bound of 1 ms is 2^23 s (ulp 9.3e-10 s below, 1.9e-9 s from it) */
    s = instantiate("start", &b);
    e = b.n[fmi3Error];
    refused(fmi3EnterInitializationMode(s, 0, 0, 8388608.0, 0, 0), &b, e, "start below 8388608 s",
            "startTime 2^23 s at 1 ms");
    check(fmi3EnterInitializationMode(s, 0, 0, 8388607.0, 0, 0) == fmi3OK && fmi3ExitInitializationMode(s) == fmi3OK &&
          step_at(s, 8388607.0, PERIOD) == fmi3OK && step_at(s, 8388607.0 + PERIOD, PERIOD) == fmi3OK,
          "startTime 8388607 s at 1 ms: initialized and steps run");
    e = b.n[fmi3Error];
    refused(step_at(s, 8388607.0 + 2 * PERIOD, 998 * PERIOD), &b, e, "stops short", "a step ending at 2^23 s");
    fmi3FreeInstance(s);
    s = instantiate("start2", &b);
    fmi3EnterInitializationMode(s, 0, 0, 1e4, 0, 0);
    set_f64(s, "period", 1e-6);
    e = b.n[fmi3Error];
    refused(fmi3ExitInitializationMode(s), &b, e, "start below 8192 s", "startTime 1e4 s with a period of 1 us set "
            "in Initialization Mode");
    fmi3FreeInstance(s);
}

/* A period that is not whole nanoseconds is refused by fmi3Set, naming the nearest whole-ns values. */
static void test_period(void)
{
    static const struct {
        double p;
        const char *near;
    } bad[] = {{0.0010000004, "0.001 s (1000000 ns) and 0.001000001 s (1000001 ns)"},
               {2.5e-9, "2e-09 s (2 ns) and 3e-09 s (3 ns)"},
               {1.4e-9, "1e-09 s (1 ns) and 2e-09 s (2 ns)"},
               {0.0099999999, "0.009999999 s (9999999 ns) and 0.01 s (10000000 ns)"}};
    logbook b = {0};
    fmi3Instance s = instantiate("period", &b);
    size_t k;
    double t = 0;
    int i, e, ok = 1;
    b.quiet = 1;
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        e = b.n[fmi3Error];
        refused(set_f64(s, "period", bad[k].p), &b, e, bad[k].near, "a period of a fraction of a nanosecond");
    }
    check(get_f64(s, "period") == PERIOD, "... and the period stays %g s", get_f64(s, "period"));
    /* the declared range holds to the bit: 1 ns - 1e-6 ns was taken as 1 ns, 10 ms + 1 ulp as 10 ms */
    e = b.n[fmi3Error];
    refused(set_f64(s, "period", 9.99999e-10), &b, e, "must lie in [1e-09, 0.01] s", "a period below min");
    e = b.n[fmi3Error];
    refused(set_f64(s, "period", 0.010000000000000002), &b, e, "must lie in [1e-09, 0.01] s",
            "a period 1 ulp above max");
    check(set_f64(s, "period", 1e-9) == fmi3OK && set_f64(s, "period", 0.01) == fmi3OK &&
          set_f64(s, "period", 1.0000000000000002e-3) == fmi3OK, "1 ns, 10 ms and 1 ms + 1 ulp are whole ns: taken");
    /* a period within the rounding of whole ns is stored as them: fmi3Get returns the period stepped */
    check(get_f64(s, "period") == 1e6 / 1e9 && set_f64(s, "period", 0.0010000000000005) == fmi3OK &&
          get_f64(s, "period") == 1e6 / 1e9, "1 ms + 1 ulp and 1 ms + 5e-16 s read back as 1 ms (%.17g s)",
          get_f64(s, "period"));
    set_f64(s, "period", 0.00025);
    fmi3EnterInitializationMode(s, 0, 0, 0, 0, 0);
    fmi3ExitInitializationMode(s);
    for (i = 0; i < 8; i++, t += 0.00025)
        ok &= step_at(s, t, 0.00025) == fmi3OK;
    check(ok && get_f64(s, "time") == t, "period 0.25 ms, 8 steps of it: the FMU's time %.17g s is the importer's",
          get_f64(s, "time"));
    fmi3FreeInstance(s);
}

/* fmi3Set refuses what the description declares out of range (min, max, enumeration items) and NaN,
 * changes nothing; the rules between parameters stay at fmi3ExitInitializationMode. */
static void test_ranges(void)
{
    logbook b = {0};
    fmi3Instance s = instantiate("ranges", &b);
    fmi3ValueReference vr[2];
    fmi3UInt32 u;
    fmi3Int64 n;
    double x[2];
    int e;
    b.quiet = 1;
    vr[0] = vr_of("substeps");
    u = 0;
    e = b.n[fmi3Error];
    refused(fmi3SetUInt32(s, vr, 1, &u, 1), &b, e, "substeps = 0 refused: must be an integer in 1..64", "substeps 0");
    u = 65;
    e = b.n[fmi3Error];
    refused(fmi3SetUInt32(s, vr, 1, &u, 1), &b, e, "1..64", "substeps 65");
    u = 64;
    check(fmi3SetUInt32(s, vr, 1, &u, 1) == fmi3OK, "substeps 64 (its max) taken");
    /* enc_scale: the board's rule at fmi3Set (it was taken there and refused only at
       fmi3ExitInitializationMode); a negative scale is a direction, taken */
    {
        static const double scales[] = {1.0 / 0.0, 0.0, 1e-300};
        size_t k;
        for (k = 0; k < sizeof scales / sizeof scales[0]; k++) {
            e = b.n[fmi3Error];
            refused(set_f64(s, "enc_scale", scales[k]), &b, e, "finite and at least 1e-20 in magnitude",
                    "enc_scale inf, 0, 1e-300 at fmi3Set");
        }
        check(set_f64(s, "enc_scale", -1000) == fmi3OK && get_f64(s, "enc_scale") == -1000,
              "enc_scale -1000 taken");
        set_f64(s, "enc_scale", 1000);
    }
    vr[0] = vr_of("model");
    n = 7;
    e = b.n[fmi3Error];
    refused(fmi3SetInt64(s, vr, 1, &n, 1), &b, e, "fused-cartesian", "model 7 (no item)");
    vr[0] = vr_of("integrator");
    n = -1;
    e = b.n[fmi3Error];
    refused(fmi3SetInt64(s, vr, 1, &n, 1), &b, e, "rk4", "integrator -1 (no item)");
    e = b.n[fmi3Error];
    refused(set_f64(s, "period", 0.02), &b, e, "servo period", "period 0.02 s (max 0.01)");
    e = b.n[fmi3Error];
    refused(set_f64(s, "period", 0), &b, e, "servo period", "period 0 (min 1e-9)");
    e = b.n[fmi3Error];
    refused(set_f64(s, "period", NAN), &b, e, "not a number", "period NaN");
    e = b.n[fmi3Error];
    refused(set_f64(s, "l", NAN), &b, e, "parameter l = nan m refused: is not a number", "l NaN");
    e = b.n[fmi3Error];
    refused(set_f64(s, "amp_mode", 0.5), &b, e, "parameter amp_mode = 0.5 refused: must be 0 (torque mode) or 1",
            "amp_mode 0.5 (no unit printed)");
    e = b.n[fmi3Error];
    refused(set_f64(s, "c_visc", -1), &b, e, "c_visc = -1 N s/m refused: must be finite and >= 0", "c_visc -1 (min 0)");
    e = b.n[fmi3Error];
    refused(set_f64(s, "k_stop", INFINITY), &b, e, "below 1e9", "k_stop inf (max 1e9)");
    e = b.n[fmi3Error];
    refused(set_f64(s, "cone_head", 2), &b, e, "between 1 and 90 deg", "cone_head 2 rad (max pi/2)");
    vr[0] = vr_of("m_head");
    vr[1] = vr_of("m_bar");
    x[0] = 9;
    x[1] = 0;
    e = b.n[fmi3Error];
    refused(fmi3SetFloat64(s, vr, 2, x, 2), &b, e, "m_bar = 0 kg", "m_head 9 and m_bar 0 in one call");
    check(get_f64(s, "m_head") == 6.697 && get_f64(s, "c_visc") == 5665.6 && get_f64(s, "amp_mode") == 0 &&
          get_f64(s, "l") == 1, "... and nothing changed: m_head %g kg (the call's valid value not stored either)",
          get_f64(s, "m_head"));
    check(set_f64(s, "amp_mode", 1) == fmi3OK && set_f64(s, "c_visc", 0) == fmi3OK && set_f64(s, "dac_0", NAN) ==
          fmi3OK, "amp_mode 1, c_visc 0 (its min) and an input dac_0 NaN (0 V) are taken");
    set_f64(s, "amp_mode", 0);
    set_f64(s, "c_visc", 5665.6);
    check(set_f64(s, "l", 0) == fmi3OK && set_f64(s, "f_static", 10) == fmi3OK, "l 0 (its declared min; the core "
          "wants l > 0) and f_static 10 N (below f_coulomb: a rule between two) pass fmi3Set");
    fmi3EnterInitializationMode(s, 0, 0, 0, 0, 0);
    e = b.n[fmi3Error];
    refused(fmi3ExitInitializationMode(s), &b, e, "refused", "... and fmi3ExitInitializationMode refuses them with the "
            "core's rules");
    fmi3FreeInstance(s);
}

/* A serialized state: the instance stepped 50 periods, serialized into *bytes (returned size). */
static size_t serialized(fmi3Instance s, fmi3Byte **bytes)
{
    fmi3FMUState st = 0;
    size_t size = 0;
    run(s, 0, 50, 5, 0);
    fmi3GetFMUState(s, &st);
    fmi3SerializedFMUStateSize(s, st, &size);
    *bytes = malloc(size);
    if (*bytes)
        fmi3SerializeFMUState(s, st, *bytes, size);
    fmi3FreeFMUState(s, &st);
    return *bytes ? size : 0;
}

/* Write n bytes of x at offset off of the block, and the checksum again (a forger's state). */
static void forge(fmi3Byte *bytes, size_t off, const void *x, size_t n)
{
    fmu_serial_header h;
    memcpy(&h, bytes, sizeof h);
    memcpy(bytes + sizeof h + off, x, n);
    h.checksum = fmu_hash(bytes + sizeof h, (size_t)h.size);
    memcpy(bytes, &h, sizeof h);
}

/* Forged serialized states (the checksum recomputed) are refused with a message, the handle and the
 * instance unchanged and stepping on; a state whose input holds NaN volts is fine. */
static void test_forged(void)
{
    enum { STATUS, VALUE, BOARD, HEADER };
    static const int huge = 1000000;
    static const unsigned many = 4000000000u;
    static const long long llmax = 9223372036854775807LL;
    static const double nan = NAN, minus1 = -1, seven = 7, one = 1, half = 0.5;
    static const int ninety_nine = 99, zero = 0;
    static const char format01[2] = {'0', '1'};
    const struct {
        const char *what;
        int where;
        size_t off;
        const void *x;
        size_t n;
        const char *key;
    } cases[] = {
        {"the board's plant index 1000000", BOARD, offsetof(hg_board, plant), &huge, sizeof huge, "plant index"},
        {"the board's variant 1000000", BOARD, offsetof(hg_board, variant), &huge, sizeof huge, "parametrization"},
        {"a NaN count of periods", STATUS, offsetof(fmu_status, periods), &nan, sizeof nan, "not at a time"},
        {"a NaN stopTime", STATUS, offsetof(fmu_status, stop_time), &nan, sizeof nan, "not at a time"},
        {"more steps than periods", STATUS, offsetof(fmu_status, steps), &seven, 0, "not at a time"},
        {"mode 99", STATUS, offsetof(fmu_status, mode), &ninety_nine, sizeof(int), "no mode"},
        {"Step Mode with no machine built", STATUS, offsetof(fmu_status, built), &zero, sizeof zero, "no mode"},
        {"the sensors' channels 1000000", BOARD, offsetof(hg_board, sense.channels), &huge, sizeof huge, "sensors"},
        {"4e9 substeps run", BOARD, offsetof(hg_board, substeps_run), &many, sizeof many, "substeps"},
        {"a byte of the model", BOARD, offsetof(hg_board, m) + 811, &ninety_nine, 1, "model"},
        {"an encoder at revolution 2^63 - 1", BOARD, offsetof(hg_board, enc[0].revolution), &llmax, sizeof llmax,
         "encoders"},
        {"a fault latch of 99", BOARD, offsetof(hg_board, fault), &ninety_nine, sizeof(int), "latches"},
        {"the head's kept sin A 0.5", BOARD, offsetof(hg_board, d) + offsetof(hg_data, trig_sc), &half, sizeof half,
         "sin and cos"},
        {"a NaN velocity-loop integrator (amplifier 0 silent ever after)", BOARD,
         offsetof(hg_board, d) + offsetof(hg_data, vloop_int_m), &nan, sizeof nan, "not finite"},
        {"m_head = -1 (out of range)", VALUE, 0, &minus1, sizeof minus1, "m_head"},
        {"m_head = 7 (not the machine's 6.697)", VALUE, 0, &seven, sizeof seven, "model"},
        {"z_0 = NaN (an output)", VALUE, 1, &nan, sizeof nan, "z_0"},
        {"format 01 in the header", HEADER, 6, format01, 2, "another format"},
        {"another board layout in the header", HEADER, offsetof(fmu_serial_header, plant_layout), &one, 1,
         "another layout"},
    };
    logbook b = {0}, b2 = {0};
    fmi3Instance s = started("forger", &b, 0), s2 = instantiate("victim", &b2);
    fmi3Byte *bytes = 0, *copy = 0;
    fmi3FMUState keep = 0, handle;
    fmu_serial_header h;
    size_t size, k;
    int e, survived = 1;
    b2.quiet = 1;
    size = s ? serialized(s, &bytes) : 0;
    copy = size ? malloc(size) : 0;
    if (!copy || !s2 || fmi3DeserializeFMUState(s2, bytes, size, &keep) != fmi3OK) {
        check(0, "forged states: instances and a state");
        free(copy), free(bytes), fmi3FreeInstance(s), fmi3FreeInstance(s2);
        return;
    }
    memcpy(&h, bytes, sizeof h);
    for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        size_t off = cases[k].off;
        memcpy(copy, bytes, size);
        if (cases[k].where == VALUE)
            off = (size_t)h.off_values + sizeof(double) * vr_of(off ? "z_0" : "m_head");
        else if (cases[k].where == BOARD)
            off += (size_t)h.off_plant;
        if (cases[k].where == HEADER) {
            memcpy(copy + off, cases[k].x, cases[k].n);
        } else if (cases[k].n == 0) {  /* steps: periods + 1 */
            double periods;
            memcpy(&periods, copy + sizeof h + offsetof(fmu_status, periods), sizeof periods);
            periods += 1;
            forge(copy, off, &periods, sizeof periods);
        } else {
            forge(copy, off, cases[k].x, cases[k].n);
        }
        handle = keep;
        e = b2.n[fmi3Error];
        check(fmi3DeserializeFMUState(s2, copy, size, &handle) == fmi3Error && b2.n[fmi3Error] > e &&
              strstr(b2.last, cases[k].key) && handle == keep, "a forged state, %s, is refused: %s", cases[k].what,
              b2.last);
        survived &= fmi3SetFMUState(s2, keep) == fmi3OK && run(s2, 50, 2, 5, 0) == 0;
    }
    check(survived, "... and after each the instance takes the genuine state and steps on");
    memcpy(copy, bytes, size);
    forge(copy, (size_t)h.off_values + sizeof(double) * vr_of("dac_0"), &nan, sizeof nan);
    check(fmi3DeserializeFMUState(s2, copy, size, &keep) == fmi3OK && fmi3SetFMUState(s2, keep) == fmi3OK &&
          step_at(s2, get_f64(s2, "time"), PERIOD) != fmi3Error, "a state whose input dac_0 holds NaN (0 V) is taken "
          "and steps (%s)", b2.last);
    fmi3FreeFMUState(s2, &keep);
    free(copy), free(bytes);
    fmi3FreeInstance(s);
    fmi3FreeInstance(s2);
}

/* Drive instance s at +-10 V alternating from its time t0 until it faults (at most n periods): the
 * periods stepped before the fault (n when none) and its message in why. */
static long until_fault(fmi3Instance s, logbook *b, double t0, long n, char *why, size_t len)
{
    static const double v[6] = {10, -10, 10, -10, 10, -10};
    long i;
    set_volts(s, v);
    for (i = 0; i < n; i++)
        if (step_at(s, t0 + (double)i * PERIOD, PERIOD) != fmi3OK)
            break;
    snprintf(why, len, "%s", b->last);
    return i;
}

/* A serialized state whose guard memo (scratch the check cannot see) was forged to clear every
 * limit is taken with its caches emptied: driven at +-10 V it faults where the genuine state's
 * machine does, with the same message (the head joint's cone), instead of passing through. */
static void test_forged_memo(void)
{
    logbook b = {0}, b2 = {0}, b3 = {0};
    fmi3Instance s = started("memo", &b, 0), s2 = instantiate("forged", &b2), s3 = instantiate("genuine", &b3);
    fmi3Byte *bytes = 0;
    fmi3FMUState st = 0, st3 = 0;
    fmu_serial_header h;
    hg_guard_memo memo;
    char why2[1024], why3[1024];
    size_t size;
    long n2, n3;
    int k, p;
    b.quiet = b2.quiet = b3.quiet = 1;
    size = s ? serialized(s, &bytes) : 0;
    if (!size || !s2 || !s3 || fmi3DeserializeFMUState(s3, bytes, size, &st3) != fmi3OK ||
        fmi3SetFMUState(s3, st3) != fmi3OK) {
        check(0, "forged memo: instances and a state");
        free(bytes), fmi3FreeInstance(s), fmi3FreeInstance(s2), fmi3FreeInstance(s3);
        return;
    }
    memset(&memo, 0, sizeof memo);    /* references that clear every cone and pair of any state */
    memo.valid = memo.cones_valid = 1;
    for (k = 0; k < 6; k++) {
        memo.cone_carriage[k] = memo.cone_head[k] = -1e9;
        memo.bar_len[k] = 1e9;
    }
    for (p = 0; p < HG_GUARD_PAIRS; p++)
        memo.dist[p] = 1e9;
    memo.dist_min = 1e9;
    memcpy(&h, bytes, sizeof h);
    forge(bytes, (size_t)h.off_plant + offsetof(hg_board, d) + offsetof(hg_data, work.guard), &memo, sizeof memo);
    check(fmi3DeserializeFMUState(s2, bytes, size, &st) == fmi3OK && fmi3SetFMUState(s2, st) == fmi3OK,
          "a state with a forged guard memo passes the check (the memo is scratch: %s)", b2.last);
    n3 = until_fault(s3, &b3, get_f64(s3, "time"), 3000, why3, sizeof why3);
    n2 = until_fault(s2, &b2, get_f64(s2, "time"), 3000, why2, sizeof why2);
    check(n3 < 3000 && strstr(why3, "cone") && n2 == n3 && strchr(why2, ':') && strchr(why3, ':') &&
              strcmp(strchr(why2, ':'), strchr(why3, ':')) == 0,    /* the same message after the instance's name */
          "... and its machine faults where the genuine state's does: period %ld as %ld (%.160s)", n2, n3, why2);
    fmi3FreeFMUState(s2, &st);
    fmi3FreeFMUState(s3, &st3);
    free(bytes);
    fmi3FreeInstance(s);
    fmi3FreeInstance(s2);
    fmi3FreeInstance(s3);
}

/* A fault's message names the period by the FMU's time (startTime 5 s), not the board's clock. */
static void test_fault_time(void)
{
    logbook b = {0};
    fmi3Instance s = instantiate("fault", &b);
    double v[6] = {10, -10, 10, -10, 10, -10}, t = 5.0;
    char want[80];
    long i;
    b.quiet = 1;
    fmi3EnterInitializationMode(s, 0, 0, 5.0, 0, 0);
    fmi3ExitInitializationMode(s);
    set_volts(s, v);
    for (i = 0; i < 2000; i++, t = 5.0 + (double)i * PERIOD)
        if (step_at(s, t, PERIOD) != fmi3OK)
            break;
    snprintf(want, sizeof want, "the period from t = %.6f s to %.6f s failed", t, t + PERIOD);
    check(i < 2000 && strstr(b.last, want) && !strstr(b.last, "board time"), "with startTime 5 s the fault of the "
          "step from %.6f s is reported at the FMU's time: %.90s", t, b.last);
    fmi3FreeInstance(s);
}

/* An enc_scale that is not the encoder's (10000 counts a turn over the 10 mm lead: 1000 per mm, 25400
 * per inch) is said once as a warning; the scale in force stays, as the board keeps it. */
static void test_enc_scale_odd(void)
{
    logbook b = {0};
    fmi3Instance s = instantiate("scale", &b);
    int w;
    if (!s) {
        check(0, "enc_scale odd: an instance");
        return;
    }
    set_f64(s, "enc_scale", 800.0);
    fmi3EnterInitializationMode(s, 0, 0, 0.0, 0, 0);
    fmi3ExitInitializationMode(s);
    w = b.n[fmi3Warning];
    check(step_at(s, 0.0, PERIOD) == fmi3Warning && b.n[fmi3Warning] == w + 1 &&
              strstr(b.last, "enc_scale = 800 (channel 0) is not the encoder's 1000 counts per mm (25400 per inch): "
                             "counts / scale read the travel 1.25 times as long"),
          "enc_scale 800: a warning at the first step: %s", b.last);
    check(step_at(s, PERIOD, PERIOD) == fmi3OK && b.n[fmi3Warning] == w + 1 && get_f64(s, "enc_scale") == 800.0,
          "... once: the next step is fmi3OK, the scale kept");
    fmi3FreeInstance(s);
}

/* What FMI 3.0 asks of the instantiation and of fmi3EnterInitializationMode's stopTime (2.3: "the FMU has to
 * return fmi3Error" past it), and a message for every fmi3Error. */
static void test_fmi_rules(void)
{
    logbook b = {0};
    char token[FMU_TOKEN_LEN];
    fmi3FMUState st = 0, st2 = 0;
    fmi3Instance s;
    fmi3Byte *bytes = 0;
    size_t size = 0;
    double t = 0, t_stop = 0.0105;
    long n = 0;
    int e;
    b.quiet = 1;
    fmu_vars_token(token);
    e = b.n[fmi3Error];
    s = fmi3InstantiateCoSimulation("", token, "", 0, 0, 0, 0, 0, 0, &b, log_cb, 0);
    check(!s && b.n[fmi3Error] > e && strstr(b.last, "instanceName"), "an empty instanceName is refused (%s)", b.last);
    fmi3FreeInstance(s);
    e = b.n[fmi3Error];
    s = fmi3InstantiateCoSimulation(" \t", token, "", 0, 0, 0, 0, 0, 0, &b, log_cb, 0);
    check(!s && b.n[fmi3Error] > e && strstr(b.last, "instanceName"), "a white-space instanceName is refused (%s)",
          b.last);
    fmi3FreeInstance(s);
    s = fmi3InstantiateCoSimulation("no logger", token, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
    check(s && step_at(s, 0, PERIOD) == fmi3Error, "no logger and no resourcePath: instantiated, and a refused "
          "call is only refused");
    fmi3FreeInstance(s);
    s = instantiate("rules", &b);
    if (!s) {
        check(0, "rules: instance");
        return;
    }
    e = b.n[fmi3Error];
    check(fmi3FreeFMUState(s, 0) == fmi3OK && fmi3FreeFMUState(s, &st) == fmi3OK && b.n[fmi3Error] == e,
          "fmi3FreeFMUState of a NULL pointer or a NULL state is ignored (FMI 3.0 2.2.6.4), no error");
    e = b.n[fmi3Error];
    refused(fmi3EnterInitializationMode(s, 0, 0, 1.0, fmi3True, 0.5), &b, e, "stopTime", "stopTime before startTime");
    e = b.n[fmi3Error];
    refused(fmi3EnterInitializationMode(s, 0, 0, 0.0, fmi3True, NAN), &b, e, "stopTime", "a NaN stopTime");
    check(fmi3EnterInitializationMode(s, 0, 0, 0.0, fmi3True, t_stop) == fmi3OK &&
          fmi3ExitInitializationMode(s) == fmi3OK, "initialized with stopTime %g s", t_stop);
    while (n < 20 && step_at(s, t, PERIOD) == fmi3OK)
        t += PERIOD, n++;
    check(n == 10 && get_f64(s, "time") == 10 * PERIOD && strstr(b.last, "stopTime"), "stepping by 1 ms: the 10 "
          "steps to 0.01 s run, the one past stopTime 0.0105 s is refused, the time stays (%s)", b.last);
    /* the stop time is part of the FMU state: restored, serialized and deserialized into another instance */
    fmi3GetFMUState(s, &st);
    fmi3Reset(s);
    fmi3SetFMUState(s, st);
    fmi3SerializedFMUStateSize(s, st, &size);
    bytes = malloc(size);
    e = b.n[fmi3Error];
    check(step_at(s, t, PERIOD) == fmi3Error && b.n[fmi3Error] > e && strstr(b.last, "stopTime"), "restored after "
          "fmi3Reset, the state keeps its stopTime");
    check(bytes && fmi3SerializeFMUState(s, st, bytes, size) == fmi3OK, "serialized");
    fmi3FreeInstance(s);              /* (frees st: a state is its instance's) */
    st = 0;
    s = instantiate("rules 2", &b);
    e = b.n[fmi3Error];
    check(s && bytes && fmi3DeserializeFMUState(s, bytes, size, &st2) == fmi3OK && fmi3SetFMUState(s, st2) == fmi3OK &&
          step_at(s, t, PERIOD) == fmi3Error && b.n[fmi3Error] > e && strstr(b.last, "stopTime"),
          "serialized and taken by another instance, the state keeps its stopTime");
    fmi3FreeFMUState(s, &st2);
    fmi3Reset(s);
    t = 0, n = 0;
    if (fmi3EnterInitializationMode(s, 0, 0, 0.0, fmi3True, 0.003) == fmi3OK && fmi3ExitInitializationMode(s) == fmi3OK)
        while (n < 5 && step_at(s, t, PERIOD) == fmi3OK)
            t += PERIOD, n++;
    check(n == 3, "stopTime 0.003 s reached by t += 0.001 s (t = %.17g s): 3 steps run", t);
    free(bytes);
    fmi3FreeInstance(s);
}

/* fmi3FreeInstance frees the FMU states the instance made and the importer did not free (FMI 3.0 2.3.1: it
 * frees all the memory the FMU's functions allocated): the heap in use returns to what it was before the
 * instance (glibc's count; under ASan, LeakSanitizer checks it at exit). */
static void test_free_instance_frees_states(void)
{
    logbook b = {0};
    fmi3FMUState a = 0, c = 0, d = 0;
    fmi3Byte *bytes = 0;
    size_t size = 0, before, after;
    fmi3Instance s;
    b.quiet = 1;
    before = mallinfo2().uordblks;
    s = started("free states", &b, 0);
    if (!s) {
        check(0, "free states: instance");
        return;
    }
    fmi3GetFMUState(s, &a);
    fmi3GetFMUState(s, &c);
    fmi3SerializedFMUStateSize(s, a, &size);
    bytes = malloc(size);
    check(bytes && fmi3SerializeFMUState(s, a, bytes, size) == fmi3OK &&
          fmi3DeserializeFMUState(s, bytes, size, &d) == fmi3OK && fmi3FreeFMUState(s, &c) == fmi3OK && !c,
          "three states made (two got, one deserialized), one freed by the importer");
    free(bytes);
    fmi3FreeInstance(s);
    after = mallinfo2().uordblks;
    check(after == before, "fmi3FreeInstance frees the two states left: %zu bytes in use before the instance, %zu "
          "after it", before, after);
}

/* No output depends on an input at the same communication point (modelDescription.xml's dependencies=""):
 * setting every input changes no output until the next step. */
static void test_no_feedthrough(void)
{
    logbook b = {0};
    fmi3Instance s = started("feedthrough", &b, 0);
    static const double tens[6] = {10, -10, 10, -10, 10, -10};
    static double before[MAX_OUT], after[MAX_OUT];
    fmi3ValueReference vr[3] = {vr_of("estop"), vr_of("reset"), vr_of("amp_enable")};
    const fmi3Boolean flip[3] = {fmi3True, fmi3True, fmi3False};
    int m;
    if (!s || run(s, 0, 20, 1, 0)) {
        check(0, "feedthrough: instance and 20 steps");
        fmi3FreeInstance(s);
        return;
    }
    m = outputs(s, before);
    set_volts(s, tens);
    fmi3SetBoolean(s, vr, 3, flip, 3);
    outputs(s, after);
    check(memcmp(before, after, (size_t)m * sizeof *before) == 0, "every input set (+-10 V, estop, reset, "  // NOLINT(bugprone-suspicious-memory-comparison): bitwise on purpose
          "amp_enable off): no output changes before the next step (no direct feedthrough)");
    fmi3FreeInstance(s);
}

/* A '#' in a message is written "##" (FMI 3.0 2.3.1: "#vr#" names a variable; a literal # is "##"): an
 * instance named "arm#3#" is not read as variable 3 (substeps). */
static void test_log_hash(void)
{
    logbook b = {0};
    fmi3Instance s = instantiate("arm#3#", &b);
    fmi3Boolean ev, term, early;
    double last;
    b.quiet = 1;
    if (!s) {
        check(0, "hash: instance");
        return;
    }
    check(fmi3DoStep(s, 0.0, PERIOD, fmi3True, &ev, &term, &early, &last) == fmi3Error &&
              strncmp(b.last, "arm##3##: ", 10) == 0 && !strstr(b.last + 10, "#"),
          "a message of instance \"arm#3#\" names it \"arm##3##\" and has no other # (%s)", b.last);
    fmi3FreeInstance(s);
}

/* fmi3SetDebugLogging turns each listed category on or off, all of them when none is listed: the FMU logs only
 * in categories that are on (FMI 3.0 2.3). A reset's rising edge is a logEvents message. */
static void test_log_categories(void)
{
    logbook b = {0};
    fmi3Instance s = started_logging("categories", &b, 0, fmi3False);
    fmi3ValueReference vr = vr_of("reset");
    fmi3Boolean on = fmi3True, off = fmi3False;
    int n_ok, n_err;
    b.quiet = 1;
    if (!s) {
        check(0, "categories: instance");
        return;
    }
    check(fmi3SetDebugLogging(s, fmi3True, 1, (const fmi3String[]){"logStatusError"}) == fmi3OK, "logStatusError on");
    n_ok = b.n[fmi3OK];
    fmi3SetBoolean(s, &vr, 1, &on, 1);
    step_at(s, 0, PERIOD);
    check(b.n[fmi3OK] == n_ok, "... turns no other category on: the reset's event is not logged (%d messages)",
          b.n[fmi3OK] - n_ok);
    fmi3SetBoolean(s, &vr, 1, &off, 1);
    step_at(s, PERIOD, PERIOD);
    check(fmi3SetDebugLogging(s, fmi3True, 1, (const fmi3String[]){"logEvents"}) == fmi3OK, "logEvents on");
    n_ok = b.n[fmi3OK];
    fmi3SetBoolean(s, &vr, 1, &on, 1);
    step_at(s, 2 * PERIOD, PERIOD);
    check(b.n[fmi3OK] > n_ok, "... the reset's event is logged (%s)", b.last);
    check(fmi3SetDebugLogging(s, fmi3False, 1, (const fmi3String[]){"logStatusError"}) == fmi3OK, "logStatusError off");
    n_err = b.n[fmi3Error];
    check(step_at(s, 0.5, PERIOD) == fmi3Error && b.n[fmi3Error] == n_err, "... a refused step returns fmi3Error "
          "and logs nothing");
    check(fmi3SetDebugLogging(s, fmi3True, 0, 0) == fmi3OK && step_at(s, 0.5, PERIOD) == fmi3Error &&
          b.n[fmi3Error] == n_err + 1, "all categories on (none listed): the refused step is logged");
    check(fmi3SetDebugLogging(s, fmi3False, 0, 0) == fmi3OK, "all categories off");
    n_ok = b.n[fmi3OK], n_err = b.n[fmi3Error];
    fmi3SetBoolean(s, &vr, 1, &off, 1);
    step_at(s, 3 * PERIOD, PERIOD);
    fmi3SetBoolean(s, &vr, 1, &on, 1);
    step_at(s, 4 * PERIOD, PERIOD);
    check(step_at(s, 0.5, PERIOD) == fmi3Error && b.n[fmi3Error] == n_err && b.n[fmi3OK] == n_ok,
          "... nothing is logged: neither the reset's event nor the refused step");
    fmi3FreeInstance(s);
}

/* Without loggingOn the FMU calls logMessage for errors only (FMI 3.0 2.3.1): a machine fault returns
 * fmi3Warning with no message, a refused step fmi3Error with one. */
static void test_logging_off(void)
{
    static const double v[6] = {10, -10, 10, -10, 10, -10};
    logbook b = {0};
    fmi3Instance s = started_logging("quiet", &b, 0, fmi3False);
    fmi3Status rc = fmi3OK;
    long n;
    b.quiet = 1;
    if (!s) {
        check(0, "logging off: instance");
        return;
    }
    set_volts(s, v);
    for (n = 0; n < 2000 && rc == fmi3OK; n++)
        rc = step_at(s, (double)n * PERIOD, PERIOD);
    check(rc == fmi3Warning && b.n[fmi3Warning] == 0 && b.n[fmi3OK] == 0 && b.n[fmi3Error] == 0,
          "loggingOn false: the machine faults in period %ld at +-10 V, the step returns fmi3Warning (%d) and "
          "nothing is logged (%d warnings, %d other messages)", n, (int)rc, b.n[fmi3Warning], b.n[fmi3OK]);
    check(step_at(s, 0.5, PERIOD) == fmi3Error && b.n[fmi3Error] == 1, "... a refused step still logs its error "
          "(%s)", b.last);
    fmi3FreeInstance(s);
}

int main(void)
{
    test_state();
    test_state_init();
    test_two_instances();
    test_multi_period();
    test_reset();
    test_refusals();
    test_before_init();
    test_time();
    test_period();
    test_ranges();
    test_forged();
    test_forged_memo();
    test_fault_time();
    test_enc_scale_odd();
    test_fmi_rules();
    test_no_feedthrough();
    test_log_categories();
    test_log_hash();
    test_logging_off();
    test_free_instance_frees_states();
    return test_failures ? 1 : 0;
}
