/* fmu_fuzz.c - random call sequences through the FMU's FMI 3.0 API:
 * random and hostile parameters and inputs (NaN, inf, huge, negative),
 * calls in the wrong order, wrong value references, types and counts,
 * random step sizes, state save/restore/serialize with damaged bytes and
 * forged ones (content changed, the checksum recomputed: what is taken
 * is stepped at once).
 * Properties: no crash (ASan + UBSan build too), every call returns
 * fmi3OK, fmi3Warning or fmi3Error, every fmi3Error comes with a logged
 * error message, a Warning only from a step, no output or time is ever
 * NaN or infinite.
 *   fmu_fuzz CALLS [SEED]      (run by tests/fmu/test_fmu_fuzz) */
#include <math.h>
#include <stdint.h>
#include "fmu_test.h"
#include "fmu_state.h"

/* xorshift64*: the fuzzer's only randomness (seeded: a failure can be rerun). */
static uint64_t next(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * 2685821657736338717ull;
}

/* Uniform in [0, 1). */
static double uniform(uint64_t *s)
{
    return (double)(next(s) >> 11) * (1.0 / 9007199254740992.0);
}

/* A value for a variable whose sane value is x: mostly sane, sometimes hostile. */
static double hostile(uint64_t *s, double x)
{
    static const double bad[] = {0.0, -0.0, 1e300, -1e300, 1e-300, 4.9e-324, -1, 1e9, 2147483648.0, -9.3e18};
    unsigned r = (unsigned)(next(s) % 100);
    if (r < 60)
        return x;
    if (r < 85)
        return x * (0.5 + 1.5 * uniform(s));
    if (r < 88)
        return NAN;
    if (r < 91)
        return next(s) & 1 ? INFINITY : -INFINITY;
    return bad[next(s) % (sizeof bad / sizeof bad[0])];
}

/* Counters of the run. */
typedef struct {
    long calls, errors, warnings, silent_errors, nonfinite, bad_status, steps_ok, forged, forged_taken;
} tally;

/* Account for one call's status: errors must have logged an error. */
static void account(tally *t, fmi3Status rc, const logbook *b, int errors_before, int may_warn)
{
    t->calls++;
    if (rc == fmi3Error) {
        t->errors++;
        if (b->n[fmi3Error] <= errors_before)
            t->silent_errors++;
    } else if (rc == fmi3Warning && may_warn) {
        t->warnings++;
    } else if (rc != fmi3OK) {
        t->bad_status++;
        printf("# status %d where OK%s was expected\n", rc, may_warn ? "/Warning" : "");
    }
}

/* Every output and the time must be finite (whenever the FMU answers): one get of them all. */
static void check_outputs(fmi3Instance s, tally *t)
{
    fmi3ValueReference vr[256];
    double x[256];
    unsigned i, n = fmu_var_count();
    size_t m = 0;
    for (i = 0; i < n && m < 256; i++) {
        fmu_var v;
        fmu_var_get(i, &v);
        if (v.type == FMU_FLOAT64 && (v.causality == FMU_OUTPUT || v.causality == FMU_INDEPENDENT))
            vr[m++] = i;
    }
    if (fmi3GetFloat64(s, vr, m, x, m) != fmi3OK)
        return;
    for (i = 0; i < m; i++)
        if (!isfinite(x[i])) {
            t->nonfinite++;
            printf("# value reference %u = %g\n", vr[i], x[i]);
        }
}

/* Start values of every variable (the sane values hostile() mostly keeps). */
static double *starts;

/* The start value of vr. */
static double vals_start(fmi3ValueReference vr)
{
    return starts[vr];
}

/* A random value reference: mostly real, sometimes past the end. */
static fmi3ValueReference random_vr(uint64_t *s)
{
    unsigned n = fmu_var_count();
    unsigned r = (unsigned)(next(s) % 20);
    return r == 0 ? (fmi3ValueReference)next(s) : r == 1 ? n + (unsigned)(next(s) % 5) : (unsigned)(next(s) % n);
}

/* One random call on instance s. */
static void one_call(fmi3Instance s, logbook *b, uint64_t *r, tally *t, fmi3FMUState *saved, double *period,
                     int forced_op)
{
    fmi3ValueReference vr = random_vr(r);
    fmi3Boolean ev, term, early;
    double last;
    int e = b->n[fmi3Error], may_warn = 0;
    fmi3Status rc = fmi3OK;
    unsigned op = forced_op >= 0 ? (unsigned)forced_op % 100 : (unsigned)(next(r) % 24);
    fmu_var v;
    int known = fmu_var_get(vr, &v) == 0;
    switch (op) {
    case 0: case 1: case 2: case 3: {         /* set a Float64 (parameter or input) */
        double x0 = known && v.type == FMU_FLOAT64 ? vals_start(vr) : 1.0;
        double x = forced_op >= 100 && next(r) % 8 ? x0 * (0.9 + 0.2 * uniform(r)) : hostile(r, x0);
        rc = fmi3SetFloat64(s, &vr, 1, &x, 1);
        if (known && v.group == FMU_G_PERIOD && rc == fmi3OK)
            *period = x;
        break;
    }
    case 4: {                                 /* set an enumeration, UInt32, Int32, Boolean */
        fmi3Int64 x = (fmi3Int64)(next(r) % 7) - 1;
        rc = fmi3SetInt64(s, &vr, 1, &x, 1);
        break;
    }
    case 5: {
        fmi3UInt32 x = (fmi3UInt32)(next(r) % 5 ? next(r) % 4 : next(r));
        rc = fmi3SetUInt32(s, &vr, 1, &x, 1);
        break;
    }
    case 6: {
        fmi3Boolean x = next(r) & 1;
        rc = fmi3SetBoolean(s, &vr, 1, &x, 1);
        break;
    }
    case 7: {                                 /* gets of any type, wrong counts */
        double x[2];
        rc = fmi3GetFloat64(s, &vr, 1, x, next(r) % 4 ? 1 : 2);
        break;
    }
    case 8: {
        fmi3Int32 x;
        rc = fmi3GetInt32(s, &vr, 1, &x, 1);
        break;
    }
    case 9: {
        fmi3Boolean x;
        rc = fmi3GetBoolean(s, &vr, 1, &x, 1);
        break;
    }
    case 10:
        rc = fmi3EnterInitializationMode(s, fmi3False, 0, next(r) % 8 ? 0.0 : hostile(r, 0.5), fmi3False, 0);
        break;
    case 11: case 12:
        rc = fmi3ExitInitializationMode(s);
        break;
    case 13: case 14: case 15: case 16: {     /* steps: mostly whole periods, sometimes not */
        double now = 0, p = *period, h = p * (double)(1 + next(r) % 3);
        fmi3ValueReference tvr = 0;
        fmi3GetFloat64(s, &tvr, 1, &now, 1);
        if (next(r) % 6 == 0)
            h = hostile(r, h * 1.37);
        if (next(r) % 10 == 0)
            now = hostile(r, now + 1);
        e = b->n[fmi3Error];
        rc = fmi3DoStep(s, now, h, fmi3True, &ev, &term, &early, &last);
        may_warn = 1;
        if (rc != fmi3Error)
            t->steps_ok++;
        break;
    }
    case 17:
        rc = next(r) % 4 ? fmi3OK : fmi3Terminate(s);
        break;
    case 18:
        rc = forced_op < 0 && next(r) % 4 ? fmi3OK : fmi3Reset(s);
        break;
    case 19:
        rc = fmi3GetFMUState(s, saved);
        break;
    case 20:
        if (*saved)
            rc = fmi3SetFMUState(s, *saved);
        break;
    case 21: {                                 /* serialize, damage sometimes, deserialize */
        size_t size = 0;
        fmi3Byte *bytes;
        if (!*saved)
            break;
        rc = fmi3SerializedFMUStateSize(s, *saved, &size);
        account(t, rc, b, e, 0);
        bytes = malloc(size ? size : 1);
        if (!bytes)
            break;
        e = b->n[fmi3Error];
        rc = fmi3SerializeFMUState(s, *saved, bytes, size);
        account(t, rc, b, e, 0);
        if (next(r) % 3 == 0 && size)
            bytes[next(r) % size] ^= (fmi3Byte)(1u << (next(r) % 8));
        else if (next(r) % 2 == 0 && size > sizeof(fmu_serial_header) + 8) {
            /* forged: 1..8 bytes of the block (mostly status, values and the board's first fields) made
               hostile, the checksum recomputed */
            fmu_serial_header h;
            size_t block = size - sizeof h, span = next(r) % 2 ? block : (block < 8192 ? block : 8192);
            size_t at = sizeof h + (size_t)(next(r) % (span - 8)), n = 1 + (size_t)(next(r) % 8), k;
            double x = hostile(r, 1.0);
            memcpy(&h, bytes, sizeof h);
            if (next(r) % 2)
                memcpy(bytes + at, &x, n);
            else
                for (k = 0; k < n; k++)
                    bytes[at + k] = (fmi3Byte)next(r);
            h.checksum = fmu_hash(bytes + sizeof h, block);
            memcpy(bytes, &h, sizeof h);
            e = b->n[fmi3Error];
            rc = fmi3DeserializeFMUState(s, bytes, size, saved);
            free(bytes);
            t->forged++;
            if (rc == fmi3OK) {         /* taken: it must run like any state */
                int i;
                t->forged_taken++;
                account(t, rc, b, e, 0);
                e = b->n[fmi3Error];
                rc = fmi3SetFMUState(s, *saved);
                account(t, rc, b, e, 0);
                for (i = 0; i < 3; i++) {
                    double now = 0, last;
                    fmi3ValueReference tvr = 0;
                    fmi3GetFloat64(s, &tvr, 1, &now, 1);
                    e = b->n[fmi3Error];
                    rc = fmi3DoStep(s, now, *period, fmi3True, &ev, &term, &early, &last);
                    account(t, rc, b, e, 1);
                    check_outputs(s, t);
                }
                e = b->n[fmi3Error];
                rc = fmi3OK;
            }
            break;
        }
        e = b->n[fmi3Error];
        rc = fmi3DeserializeFMUState(s, bytes, next(r) % 5 ? size : size / 2, saved);
        free(bytes);
        break;
    }
    case 22: {
        const fmi3String cats[] = {"logEvents", next(r) & 1 ? "logStatusError" : "bogus"};
        rc = fmi3SetDebugLogging(s, next(r) & 1, next(r) % 3, cats);
        if (rc == fmi3OK)             /* it may have turned logStatusError off: on again, errors must say why */
            fmi3SetDebugLogging(s, fmi3True, 1, (const fmi3String[]){"logStatusError"});
        break;
    }
    default:
        rc = next(r) & 1 ? fmi3EnterEventMode(s) : fmi3SetTime(s, 1.0);
        break;
    }
    account(t, rc, b, e, may_warn);
    check_outputs(s, t);
}

int main(int argc, char **argv)
{
    long calls = argc > 1 ? atol(argv[1]) : 20000, i = 0;
    uint64_t seed = argc > 2 ? strtoull(argv[2], 0, 0) : 0x9e3779b97f4a7c15ull, r = seed | 1;
    tally t = {0};
    int instances = 0;
    starts = malloc(fmu_var_count() * sizeof *starts);
    if (!starts || fmu_vars_start(starts)) {
        check(0, "start values");
        return 1;
    }
    while (i < calls) {
        logbook b = {0};
        fmi3Instance s = instantiate("fuzz", &b);
        fmi3FMUState saved = 0;
        double period = 0.001;
        long n = 50 + (long)(next(&r) % 400), j;
        b.quiet = getenv("FUZZ_VERBOSE") == 0;
        if (!s) {
            check(0, "instantiation");
            return 1;
        }
        instances++;
        for (j = 0; j < n && i < calls; j++, i++) {
            /* episodes of 40 calls: fmi3Reset, in most a few sets, Enter, Exit, then anything */
            int op = -1, at = (int)(j % 40);
            if (at == 0 && j)
                op = 18;
            else if (at < 5 && next(&r) % 4)
                op = 100 + (int)(next(&r) % 4);         /* a set, hostile only now and then */
            else if (at == 5 || at == 6)
                op = at == 5 ? 10 : 11;
            one_call(s, &b, &r, &t, &saved, &period, op);
        }
        if (saved)
            fmi3FreeFMUState(s, &saved);
        fmi3FreeInstance(s);
    }
    check(1, "fuzz: %ld calls on %d instances (seed 0x%llx), no crash: %ld refused, %ld warnings, %ld steps run",
          t.calls, instances, (unsigned long long)seed, t.errors, t.warnings, t.steps_ok);
    check(t.silent_errors == 0, "every fmi3Error came with a logged error message (%ld without)", t.silent_errors);
    check(t.bad_status == 0, "only fmi3OK and fmi3Error returned (fmi3Warning by fmi3DoStep alone): %ld others",
          t.bad_status);
    check(t.nonfinite == 0, "no output or time NaN or infinite after any call (%ld seen)", t.nonfinite);
    check(t.forged > 0, "forged serialized states (checksum recomputed): %ld, %ld of them taken (a change the "
          "content check cannot tell from a machine's state) and stepped without a crash", t.forged, t.forged_taken);
    check(t.errors > t.calls / 20 && t.steps_ok > t.calls / 20,
          "the sequences reach both sides: refusals and accepted steps are each over 5%% of the calls");
    free(starts);
    return test_failures ? 1 : 0;
}
