/* test_board_rec.c - the record pin set (src/hg_board_rec.c) and the record
 * reader (src/hg_record.c) without LinuxCNC:
 * - the table covers every byte of hg_board_inputs but padding before a
 *   double (a field added to the board's inputs without a column fails);
 * - names are unique, fit a HAL pin name, and the count fits sampler;
 * - packing round-trips;
 * - a run of random inputs written as record text ("%.17g", "nan") and read
 *   back drives a second board to the same outputs and the same state, to
 *   the last bit (what `replay` relies on). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hg_test.h"
#include "hg_board_rec.h"
#include "hg_record.h"

#define RUN_STEPS 400

static hg_board_rec_field f[HG_BOARD_REC_MAX];
static hg_board ba, bb;
static char text[4 << 20];
static int nonfinite_pins;            /* pin values that were NaN/inf (must stay 0) */

/* Field size in bytes in its struct. */
static size_t field_size(const hg_board_rec_field *e)
{
    if (e->type == HG_BRF_PACK)
        return (size_t)e->pack_n * e->pack_elem;
    return e->type == HG_BRF_F64 ? sizeof(double) : sizeof(int);
}

static void test_coverage(int n)
{
    static unsigned char covered[sizeof(hg_board_inputs)];
    size_t i, uncovered = 0, bad_gap = 0;
    int k, j, dup = 0, too_long = 0;
    for (k = 0; k < n; k++) {
        if (f[k].side != HG_BRS_IN)
            continue;
        for (i = 0; i < field_size(&f[k]); i++)
            covered[f[k].offset + i]++;
    }
    for (i = 0; i < sizeof covered; i++) {
        size_t a = i;
        if (covered[i] > 1)
            bad_gap++;                /* two columns on one byte */
        if (covered[i])
            continue;
        while (i < sizeof covered && !covered[i])
            i++;
        uncovered += i - a;
        /* padding: fewer than 8 bytes, up to an 8-aligned offset (a double) */
        if (i - a >= 8 || (i % 8) != 0)
            bad_gap++;
        i--;
    }
    CHECK(bad_gap == 0 && uncovered < 16,
          "the table covers every byte of hg_board_inputs (%zu bytes) once, but %zu bytes of padding",
          sizeof(hg_board_inputs), uncovered);
    for (k = 0; k < n; k++) {
        for (j = 0; j < k; j++)
            dup += strcmp(f[j].name, f[k].name) == 0;
        /* HAL_NAME_LEN 47: motenc-hexaglide.N.rec. is 23 characters */
        too_long += strlen(f[k].name) + 23 > 47;
    }
    CHECK(dup == 0 && too_long == 0, "%d column names, unique (%d twice), every pin name <= 47 characters (%d longer)",
          n, dup, too_long);
    CHECK(n + 6 <= 8 * 21, "%d columns and the recorder's 6 joint commands fit LinuxCNC's sampler "
          "(8 FIFOs of 21 pins, HAL_STREAM_MAX_PINS)", n);
}

static void test_pack(int n)
{
    hg_board_inputs a, b;
    hg_board_outputs o;
    int k, bad = 0;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    memset(&o, 0, sizeof o);
    a.stuck[0] = HG_SW_MIN;
    a.stuck[5] = HG_SW_MAX | HG_SW_HOME;
    a.index_enable[7] = 1;
    a.bar_broken[3] = 1;
    a.enc_glitch[2] = -123456;
    a.dout_values = 0x80000081u;
    for (k = 0; k < n; k++)
        if (f[k].side == HG_BRS_IN)
            hg_board_rec_set(f, n, k, &b, hg_board_rec_get(f, n, k, &a, &o, 1000000, 2));
    bad = memcmp(a.stuck, b.stuck, sizeof a.stuck) || memcmp(a.index_enable, b.index_enable, sizeof a.index_enable) ||
          memcmp(a.bar_broken, b.bar_broken, sizeof a.bar_broken) || b.enc_glitch[2] != -123456 ||
          b.dout_values != 0x80000081u;
    for (k = 0; k < n; k++)
        if (strcmp(f[k].name, "in.stuck") == 0)
            bad |= hg_board_rec_get(f, n, k, &a, &o, 0, 0) != (double)(HG_SW_MIN | ((HG_SW_MAX | HG_SW_HOME) << 15));
    CHECK(!bad, "packed bit arrays, s32 and u32 fields round-trip through their column values");
}

/* Random inputs of period s on top of the defaults. */
static void random_inputs(hg_board_inputs *in, int s)
{
    int k;
    for (k = 0; k < HG_BOARD_DACS; k++)
        in->dac_v[k] = hg_test_uniform(-3.0, 3.0);
    if (s == 50)
        in->dac_v[2] = (double)NAN;  /* a NaN product: 0 V; pin 0, state in in.nonfinite-* */
    if (s == 60)
        in->dac_v[4] = -(double)INFINITY; /* clamps to -10 V */
    in->enc_scale[6] = (s >= 90 && s < 95) ? (double)INFINITY : 1.0; /* refused, set to 1.0 */
    in->params.model.c_visc_ns_per_m = s == 130 ? (double)NAN : 5665.6; /* refused for one period */
    in->dac_written = 1;
    in->dout_values = s < 20 ? 0u : 0x80u; /* E-STOP loop closed after 20 periods */
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        in->index_enable[k] = hg_test_uniform(0, 1) < 0.1;
    in->enc_glitch[1] = s == 77 ? 5 : 0;
    in->stuck[3] = s > 200 ? HG_SW_HOME : 0u;
    if (s == 120)
        in->params.model.m_head_kg = 7.5; /* a parameter change on the way */
    in->reset = s >= 300 && s < 305;
}

/* Append one record row of period s to text; returns the new length. */
static size_t write_row(size_t len, int n, int s, const hg_board_inputs *in, const hg_board_outputs *o)
{
    int k;
    len += (size_t)snprintf(text + len, sizeof text - len, "%d", s);
    for (k = 0; k < n; k++) {
        double v = hg_board_rec_get(f, n, k, in, o, 1000000, 2);
        if (!isfinite(v))
            nonfinite_pins++;
        len += (size_t)snprintf(text + len, sizeof text - len, ",%.17g", v);
    }
    len += (size_t)snprintf(text + len, sizeof text - len, "\n");
    return len;
}

static void test_round_trip(int n)
{
    static hg_record r;
    static double row[HG_RECORD_MAX_COLS];
    hg_board_inputs in, inb;
    hg_board_outputs o, ob;
    hg_record_error e;
    size_t len;
    int k, s, rc, col[HG_BOARD_REC_MAX], diff = 0, rows = 0, colmiss = 0;
    hg_board_init(&ba, HG_MODEL_REDUCED_CARTESIAN, 0);
    hg_board_inputs_default(&ba, &in);
    len = (size_t)snprintf(text, sizeof text, "%s\n# board 0\nsample", HG_RECORD_MAGIC);
    for (k = 0; k < n; k++)
        len += (size_t)snprintf(text + len, sizeof text - len, ",%s", f[k].name);
    len += (size_t)snprintf(text + len, sizeof text - len, "\n");
    for (s = 0; s < RUN_STEPS; s++) {
        random_inputs(&in, s);
        hg_board_step(&ba, &in, &o, 1000000);
        len = write_row(len, n, s, &in, &o);
    }
    rc = hg_record_open(&r, text, len, &e);
    CHECK(rc == 0, "the written record opens (%s)", rc ? e.msg : "ok");
    for (k = 0; k < n; k++) {
        col[k] = hg_record_column(&r, f[k].name);
        colmiss += col[k] < 0;
    }
    hg_board_init(&bb, HG_MODEL_REDUCED_CARTESIAN, 0);
    hg_board_inputs_default(&bb, &inb);
    while (colmiss == 0 && (rc = hg_record_next(&r, row, &e)) == 1) {
        for (k = 0; k < n; k++)
            hg_board_rec_set(f, n, k, &inb, row[col[k]]);
        hg_board_step(&bb, &inb, &ob, (long)row[col[0]]);
        for (k = 0; k < n; k++) {
            double a, b;
            if (f[k].side != HG_BRS_OUT)
                continue;
            a = row[col[k]];
            b = hg_board_rec_get(f, n, k, &inb, &ob, 0, 0);
            diff += memcmp(&a, &b, sizeof a) != 0;
        }
        rows++;
    }
    CHECK(rc == 0 && rows == RUN_STEPS && colmiss == 0, "read back %d of %d rows (%s)", rows, RUN_STEPS,
          rc < 0 ? e.msg : "to the end");
    CHECK(nonfinite_pins == 0, "every record pin value is finite (NaN DAC, -inf DAC, inf scale, NaN parameter "
          "encoded in in.nonfinite-*; %d were not)", nonfinite_pins);
    CHECK(diff == 0, "replayed outputs equal the recorded ones to the last bit (%d differ)", diff);
    CHECK(memcmp(&ba.d, &bb.d, sizeof ba.d) == 0 && memcmp(ba.enc, bb.enc, sizeof ba.enc) == 0 &&
              ba.steps == bb.steps && ba.fault == bb.fault && ba.wd.expired == bb.wd.expired,
          "the replayed board ends in the recorded board's state, bit for bit (steps %u)", bb.steps);
    CHECK(ba.m.p.m_head_kg == 7.5 && bb.m.p.m_head_kg == 7.5, "the parameter change in the inputs reached both boards");
}

int main(void)
{
    int n = hg_board_rec_fields(f, HG_BOARD_REC_MAX);
    CHECK(n > 0, "the table has %d entries", n);
    if (n <= 0)
        return hg_test_exit();
    CHECK(hg_board_rec_fields(f, 10) == -1, "a too small array is refused");
    n = hg_board_rec_fields(f, HG_BOARD_REC_MAX);
    test_coverage(n);
    test_pack(n);
    test_round_trip(n);
    return hg_test_exit();
}
