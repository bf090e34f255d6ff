/* fmu_api.c - the FMU through its FMI 3.0 functions: state save and
 * restore (fmi3GetFMUState/SetFMUState, serialization) continue
 * bit-identically, two instances share nothing, a step of n periods is n
 * steps of one, fmi3Reset starts over, and every refused call returns
 * fmi3Error with a message and changes nothing. Run by tests/fmu/test_fmu_api. */
#include <math.h>
#include <stdint.h>
#include "fmu_test.h"

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

/* Instantiate, set enc_scale, initialize: the FMU in Step Mode. */
static fmi3Instance started(const char *name, logbook *b, double m_head)
{
    fmi3Instance s = instantiate(name, b);
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
    /* bad parameters: refused at fmi3ExitInitializationMode, the FMU stays in Initialization Mode */
    set_f64(s, "c_visc", -1);
    set_f64(s, "period", 0.02);
    fmi3EnterInitializationMode(s, 0, 0, 0.0, 0, 0);
    e = b.n[fmi3Error];
    refused(fmi3ExitInitializationMode(s), &b, e, "refused", "c_visc = -1 and period = 0.02 s");
    check(b.n[fmi3Error] - e >= 3, "one message per refused parameter and one for the call (%d messages)",
          b.n[fmi3Error] - e);
    set_f64(s, "c_visc", 5665.6);
    set_f64(s, "period", PERIOD);
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

int main(void)
{
    test_state();
    test_two_instances();
    test_multi_period();
    test_reset();
    test_refusals();
    test_before_init();
    return test_failures ? 1 : 0;
}
