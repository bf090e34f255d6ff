/* test_board_rec.c - the record pin set (src/hg_board_rec.c) and the record
 * reader (src/hg_record.c) without LinuxCNC:
 * - the table covers every byte of hg_board_inputs but padding before a
 *   double, in both formats (format 2's parameters through the event
 *   stream; a field added to the board's inputs without a column fails);
 * - names are unique, fit a HAL pin name, and the count fits sampler;
 * - packing round-trips;
 * - a run of random inputs (parameter changes one at a time and in bursts
 *   the slots must queue) written as record text ("%.17g") and read back,
 *   the parameters from the events read ahead, drives a second board to
 *   the same outputs and the same state, to the last bit (what `replay`
 *   relies on), with the fingerprint of every row matching;
 * - a stream whose queue overflowed is caught by the fingerprint. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hg_test.h"
#include "hg_board_rec.h"
#include "hg_board_rec_read.h"
#include "hg_record.h"
#include "hg_plant_hexaglide.h"

#define RUN_STEPS 400

static hg_board_rec_field f[HG_BOARD_REC_MAX];
static hg_board ba, bb;
static hg_board_rec_stream stream;
static char text[4 << 20];
static int nonfinite_pins;            /* pin values that were NaN/inf (must stay 0) */
static hg_board_rec_event events[RUN_STEPS * HG_BOARD_REC_SLOTS];

/* Field size in bytes in its struct. */
static size_t field_size(const hg_board_rec_field *e)
{
    if (e->type == HG_BRF_PACK)
        return (size_t)e->pack_n * e->pack_elem;
    return e->type == HG_BRF_F64 ? sizeof(double) : sizeof(int);
}

/* Entries of the Hexaglide's parameter table. */
static int nparams(void)
{
    int np;
    hg_params_table(&np);
    return np;
}

static void test_coverage(int n, int format)
{
    static unsigned char covered[sizeof(hg_board_inputs)];
    const size_t pv = offsetof(hg_board_inputs, params.plant.v);
    size_t i, uncovered = 0, bad_gap = 0;
    int k, j, dup = 0, too_long = 0, np = nparams();
    memset(covered, 0, sizeof covered);
    for (k = 0; k < n; k++) {
        if (f[k].side == HG_BRS_IN)
            for (i = 0; i < field_size(&f[k]); i++)
                covered[f[k].offset + i]++;
        if (f[k].side == HG_BRS_PARAM)   /* format 1: a parameter column */
            for (i = 0; i < sizeof(double); i++)
                covered[pv + f[k].offset * sizeof(double) + i]++;
    }
    if (format == 2)                  /* the event stream: every parameter of the plant */
        for (k = 0; k < np; k++)
            for (i = 0; i < sizeof(double); i++)
                covered[pv + (size_t)k * sizeof(double) + i]++;
    for (i = pv + (size_t)np * sizeof(double); i < pv + sizeof(hg_plant_params); i++)
        covered[i] = 1;               /* entries past the plant's table: no parameter */
    if (format == 1)                  /* parameters format 1 did not know: the plant's legacy values */
        for (k = 0; k < np; k++) {
            hg_param_info e;
            int j, in1 = 0;
            e = hg_params_table(0)[k];
            for (j = 0; j < n; j++)
                in1 |= f[j].side == HG_BRS_PARAM && f[j].offset == (unsigned long)k;
            if (!in1 && (strcmp(e.name, "k_axial") == 0 || strcmp(e.name, "c_axial") == 0 ||
                         strcmp(e.name, "backlash") == 0))
                for (i = 0; i < sizeof(double); i++)
                    covered[pv + (size_t)k * sizeof(double) + i] = 1;
        }
    {                                 /* the channels past the plant's (6): no input of this plant */
        static const size_t chan[] = {offsetof(hg_board_inputs, amp_fail), offsetof(hg_board_inputs, stuck),
                                      offsetof(hg_board_inputs, tripped), offsetof(hg_board_inputs, index_lost),
                                      offsetof(hg_board_inputs, enc_glitch), offsetof(hg_board_inputs, inject)};
        for (k = 0; k < (int)(sizeof chan / sizeof chan[0]); k++)
            for (i = 6 * sizeof(int); i < HG_CHANNELS_MAX * sizeof(int); i++)
                covered[chan[k] + i] = 1;
        /* the commands of the tool-path error: past the plant's channels; not in format 1 at all */
        for (i = format == 1 ? 0 : 6 * sizeof(double); i < HG_CHANNELS_MAX * sizeof(double); i++)
            covered[offsetof(hg_board_inputs, pos_cmd) + i] = 1;
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
          "format %d: the table covers every byte of hg_board_inputs (%zu bytes) once, but %zu bytes of padding",
          format, sizeof(hg_board_inputs), uncovered);
    for (k = 0; k < n; k++) {
        for (j = 0; j < k; j++)
            dup += strcmp(f[j].name, f[k].name) == 0;
        /* HAL_NAME_LEN 47: motenc-hexaglide.N.rec. is 23 characters */
        too_long += strlen(f[k].name) + 23 > 47;
    }
    CHECK(dup == 0 && too_long == 0, "format %d: %d column names, unique (%d twice), every pin name <= 47 "
          "characters (%d longer)", format, n, dup, too_long);
    CHECK(n + 6 <= 8 * 21, "format %d: %d columns and the recorder's 6 joint commands fit LinuxCNC's sampler "
          "(8 FIFOs of 21 pins, HAL_STREAM_MAX_PINS)", format, n);
}

/* The context of one period for hg_board_rec_get. */
static hg_board_rec_ctx ctx_of(const hg_board_inputs *in, const hg_board_outputs *o, const hg_board_rec_stream *s)
{
    hg_board_rec_ctx c;
    c.in = in;
    c.out = o;
    c.period_ns = 1000000;
    c.plant = 0;
    c.variant = HG_MODEL_REDUCED_CARTESIAN;
    c.stream = s;
    return c;
}

static void test_pack(int n)
{
    hg_board_inputs a, b;
    hg_board_outputs o;
    hg_board_rec_ctx c;
    int k, bad = 0;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    memset(&o, 0, sizeof o);
    a.stuck[0] = HG_SW_MIN;
    a.stuck[5] = HG_SW_MAX | HG_SW_HOME;
    a.index_enable[7] = 1;
    a.inject[3] = 1;                  /* bar 3 broken */
    a.enc_glitch[2] = -123456;
    a.dout_values = 0x80000081u;
    c = ctx_of(&a, &o, 0);
    for (k = 0; k < n; k++)
        if (f[k].side == HG_BRS_IN)
            hg_board_rec_set(f, n, k, &b, hg_board_rec_get(f, n, k, &c));
    bad = memcmp(a.stuck, b.stuck, sizeof a.stuck) || memcmp(a.index_enable, b.index_enable, sizeof a.index_enable) ||
          memcmp(a.inject, b.inject, sizeof a.inject) || b.enc_glitch[2] != -123456 ||
          b.dout_values != 0x80000081u;
    for (k = 0; k < n; k++)
        if (strcmp(f[k].name, "in.stuck") == 0)
            bad |= hg_board_rec_get(f, n, k, &c) != (double)(HG_SW_MIN | ((HG_SW_MAX | HG_SW_HOME) << 15));
    CHECK(!bad, "packed bit arrays (in.bar-broken from the injections' bit 0), s32 and u32 fields round-trip "
          "through their column values");
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
    *hg_test_pv(&in->params, "c_visc") = s == 130 ? (double)NAN : 5665.6; /* refused for one period */
    in->dac_written = 1;
    in->dout_values = s < 20 ? 0u : 0x80u; /* E-STOP loop closed after 20 periods */
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        in->index_enable[k] = hg_test_uniform(0, 1) < 0.1;
    in->enc_glitch[1] = s == 77 ? 5 : 0;
    in->stuck[3] = s > 200 ? HG_SW_HOME : 0u;
    if (s == 120)
        *hg_test_pv(&in->params, "m_head") = 7.5; /* a parameter change on the way */
    if (s == 150) {                   /* five at once: the two slots queue them */
        *hg_test_pv(&in->params, "m_carriage") = 3.0;
        *hg_test_pv(&in->params, "f_static") = 60.0;
        *hg_test_pv(&in->params, "f_coulomb") = 45.0;
        *hg_test_pv(&in->params, "i_head_zz") = 0.04;
        in->params.substeps = 2;
    }
    in->reset = s >= 300 && s < 305;
}

/* Append one record row of period s to text; returns the new length. */
static size_t write_row(size_t len, int n, int s, const hg_board_inputs *in, const hg_board_outputs *o)
{
    hg_board_rec_ctx c = ctx_of(in, o, &stream);
    int k;
    len += (size_t)snprintf(text + len, sizeof text - len, "%d", s);
    for (k = 0; k < n; k++) {
        double v = hg_board_rec_get(f, n, k, &c);
        if (!isfinite(v))
            nonfinite_pins++;
        len += (size_t)snprintf(text + len, sizeof text - len, ",%.17g", v);
    }
    len += (size_t)snprintf(text + len, sizeof text - len, "\n");
    return len;
}

/* Column of name in r, or -1. */
static int column(const hg_record *r, const char *name)
{
    return hg_record_column(r, name);
}

/* The events of the record text (a first pass, as replay reads ahead): count. */
static long read_events(size_t len)
{
    static hg_record r;
    static double row[HG_RECORD_MAX_COLS];
    hg_record_error e;
    int c[HG_BOARD_REC_SLOTS][3], s;
    long nev = 0;
    if (hg_record_open(&r, text, len, &e))
        return -1;
    for (s = 0; s < HG_BOARD_REC_SLOTS; s++) {
        char name[32];
        snprintf(name, sizeof name, "in.pev-%d-entry", s);
        c[s][0] = column(&r, name);
        snprintf(name, sizeof name, "in.pev-%d-value", s);
        c[s][1] = column(&r, name);
        snprintf(name, sizeof name, "in.pev-%d-age", s);
        c[s][2] = column(&r, name);
    }
    while (hg_record_next(&r, row, &e) == 1)
        for (s = 0; s < HG_BOARD_REC_SLOTS; s++)
            nev += hg_board_rec_event_of(row[c[s][0]], row[c[s][1]], row[c[s][2]], (unsigned long)row[0],
                                         &events[nev]);
    return nev;
}

/* Record RUN_STEPS (or steps) periods of inputs from `inputs` into text; its length. */
static size_t record_run(int n, int steps, void (*inputs)(hg_board_inputs *, int))
{
    hg_board_inputs in;
    hg_board_outputs o;
    size_t len;
    int k, s;
    hg_board_init(&ba, 0, HG_MODEL_REDUCED_CARTESIAN, 0);
    hg_board_inputs_default(&ba, &in);
    hg_board_rec_stream_start(&stream, 0, HG_MODEL_REDUCED_CARTESIAN);
    len = (size_t)snprintf(text, sizeof text, "%s\n# board 0\nsample", HG_RECORD_MAGIC);
    for (k = 0; k < n; k++)
        len += (size_t)snprintf(text + len, sizeof text - len, ",%s", f[k].name);
    len += (size_t)snprintf(text + len, sizeof text - len, "\n");
    for (s = 0; s < steps; s++) {
        inputs(&in, s);
        hg_board_step(&ba, &in, &o, 1000000);
        hg_board_rec_stream_step(&stream, &in.params, nparams());
        len = write_row(len, n, s, &in, &o);
    }
    return len;
}

/* Replay the record text on bb, parameters from the events read ahead:
 * rows read (or -1 - row of the first fingerprint mismatch), output fields that differ in *diff. */
static int replay(int n, size_t len, long nev, int *diff)
{
    static hg_record r;
    static double row[HG_RECORD_MAX_COLS];
    hg_board_inputs inb;
    hg_board_outputs ob;
    hg_record_error e;
    long next = 0;
    int k, rc, col[HG_BOARD_REC_MAX], rows = 0, colmiss = 0, fp = -1, np = nparams();
    *diff = 0;
    if (hg_record_open(&r, text, len, &e))
        return -1000000;
    for (k = 0; k < n; k++) {
        col[k] = hg_record_column(&r, f[k].name);
        colmiss += col[k] < 0;
        if (f[k].side == HG_BRS_PARAMS_FP)
            fp = col[k];
    }
    hg_board_init(&bb, 0, HG_MODEL_REDUCED_CARTESIAN, 0);
    hg_board_inputs_default(&bb, &inb);
    while (colmiss == 0 && (rc = hg_record_next(&r, row, &e)) == 1) {
        hg_board_rec_ctx c;
        for (k = 0; k < n; k++)
            hg_board_rec_set(f, n, k, &inb, row[col[k]]);
        for (; next < nev && events[next].at <= (unsigned long)row[0]; next++)
            hg_board_rec_entry_set(&inb.params, np, events[next].entry, events[next].value);
        if ((double)hg_board_rec_fingerprint(&inb.params, np) != row[fp])
            return -1 - rows;
        hg_board_step(&bb, &inb, &ob, (long)row[col[0]]);
        c = ctx_of(&inb, &ob, 0);
        for (k = 0; k < n; k++) {
            double a, b;
            if (f[k].side != HG_BRS_OUT)
                continue;
            a = row[col[k]];
            b = hg_board_rec_get(f, n, k, &c);
            *diff += memcmp(&a, &b, sizeof a) != 0;
        }
        rows++;
    }
    return colmiss ? -1000000 : rows;
}

static void test_round_trip(int n)
{
    size_t len = record_run(n, RUN_STEPS, random_inputs);
    long nev = read_events(len);
    int rows, diff;
    CHECK(nev == nparams() + 7, "the record carries %ld parameter events: the whole block at the start "
          "(%d), then every change (7: NaN c_visc and back, m_head, 4 at once)", nev, nparams());
    rows = replay(n, len, nev, &diff);
    CHECK(rows == RUN_STEPS, "read back %d of %d rows, every row's in.params-fp matching the parameters the "
          "events give", rows, RUN_STEPS);
    CHECK(nonfinite_pins == 0, "every record pin value is finite (NaN DAC, -inf DAC, inf scale, NaN parameter "
          "encoded in in.nonfinite-* or the event's entry word; %d were not)", nonfinite_pins);
    CHECK(diff == 0, "replayed outputs equal the recorded ones to the last bit (%d differ)", diff);
    CHECK(memcmp(bb.d.store, ba.d.store, hg_plant_hexaglide.state_bytes) == 0 &&
              memcmp(ba.enc, bb.enc, sizeof ba.enc) == 0 && ba.steps == bb.steps && ba.fault == bb.fault &&
              ba.wd.expired == bb.wd.expired,
          "the replayed board ends in the recorded board's state, bit for bit (steps %u)", bb.steps);
    CHECK(hg_hexaglide_model(&ba.m)->p.m_head_kg == 7.5 && hg_hexaglide_model(&bb.m)->p.m_head_kg == 7.5 &&
              hg_hexaglide_model(&bb.m)->p.f_static_n == 60.0 && bb.substeps == 2,
          "the parameter changes in the inputs (one alone, five at once) reached both boards");
}

/* Every parameter changes every period (more than the queue holds). */
static void storm_inputs(hg_board_inputs *in, int s)
{
    int k, np = nparams();
    in->dout_values = 0x80u;
    for (k = 0; k < np; k++)          /* a refused block: the board keeps its own; the stream sends all */
        in->params.plant.v[k] = 1.0 + s + 0.001 * k;
}

static void test_overflow(int n)
{
    size_t len = record_run(n, 40, storm_inputs);
    long nev = read_events(len);
    int diff, rows = replay(n, len, nev, &diff);
    CHECK(stream.lost && rows < 0 && rows > -40, "a queue that overflowed (every parameter changed in every one of "
          "40 periods: %ld events carried) is caught by the fingerprint at row %d, not replayed wrong",
          nev, -1 - rows);
}

/* A one-row record of table f[0..n) (every value 0, column `bad`'s `value`), without column `drop`. */
static size_t one_row(int n, int drop, int bad, const char *value)
{
    size_t len = (size_t)snprintf(text, sizeof text, "%s\n# board 0\nsample", HG_RECORD_MAGIC);
    int k;
    for (k = 0; k < n; k++)
        if (k != drop)
            len += (size_t)snprintf(text + len, sizeof text - len, ",%s", f[k].name);
    len += (size_t)snprintf(text + len, sizeof text - len, "\n0");
    for (k = 0; k < n; k++)
        if (k != drop)
            len += (size_t)snprintf(text + len, sizeof text - len, ",%s", k == bad ? value : "0");
    len += (size_t)snprintf(text + len, sizeof text - len, "\n");
    return len;
}

/* The first entry of table f[0..n) of type t, or -1. */
static int first_of(int n, int t)
{
    int k;
    for (k = 0; k < n && f[k].type != t; k++)
        ;
    return k < n ? k : -1;
}

/* hg_board_rec_bind_plant: every column needed and read as its pin's type (replay's and identify's readers). */
static void test_bind(int n)
{
    static hg_record r;
    static double row[HG_RECORD_MAX_COLS];
    static const struct { int type; const char *value, *says; } bad[] = {
        {HG_BRF_U32, "2.5", "not a u32 integer"}, {HG_BRF_U32, "-1", "not a u32 integer"},
        {HG_BRF_S32, "0.25", "not an s32 integer"}, {HG_BRF_BIT, "2", "not 0 or 1"}};
    hg_record_error e;
    int i, k, plain, bound;
    for (i = 0; i < (int)(sizeof bad / sizeof bad[0]); i++) {
        k = first_of(n, bad[i].type);
        plain = hg_record_open(&r, text, one_row(n, -1, k, bad[i].value), &e) == 0 &&
                hg_record_next(&r, row, &e) == 1;
        bound = hg_record_open(&r, text, one_row(n, -1, k, bad[i].value), &e) == 0 &&
                hg_board_rec_bind_plant(&r, 0, HG_MODEL_REDUCED_CARTESIAN, &e) == 0 &&
                hg_record_next(&r, row, &e) == HG_REC_ERR_KIND && strstr(e.msg, f[k].name) &&
                strstr(e.msg, bad[i].says);
        CHECK(k >= 0 && plain && bound, "%s = %s: read as a number unbound, refused bound (%s)",
              k >= 0 ? f[k].name : "?", bad[i].value, e.msg);
    }
    CHECK(hg_record_open(&r, text, one_row(n, -1, -1, "0"), &e) == 0 &&
              hg_board_rec_bind_plant(&r, 0, HG_MODEL_REDUCED_CARTESIAN, &e) == 0 && hg_record_next(&r, row, &e) == 1,
          "a row of zeros is read, bound");
    CHECK(hg_record_open(&r, text, one_row(n, n / 2, -1, "0"), &e) == 0 &&
              hg_board_rec_bind_plant(&r, 0, HG_MODEL_REDUCED_CARTESIAN, &e) == HG_REC_ERR_COLUMN &&
              strstr(e.msg, f[n / 2].name),
          "a record without %s: the bind names it (%s)", f[n / 2].name, e.msg);
    CHECK(hg_record_open(&r, text, one_row(n, -1, -1, "0"), &e) == 0 &&
              hg_board_rec_bind_plant(&r, 99, 0, &e) == HG_REC_ERR_HEADER && strstr(e.msg, "plant 99"),
          "an unknown plant: no table, said (%s)", e.msg);
}

int main(void)
{
    int n1, n = hg_board_rec_fields(f, HG_BOARD_REC_MAX, 0, HG_MODEL_REDUCED_CARTESIAN, 2);
    CHECK(n > 0, "the table has %d entries", n);
    if (n <= 0)
        return hg_test_exit();
    CHECK(hg_board_rec_fields(f, 10, 0, HG_MODEL_REDUCED_CARTESIAN, 2) == -1 && hg_board_rec_fields(f, HG_BOARD_REC_MAX, 0, HG_MODEL_REDUCED_CARTESIAN, 3) == -1 &&
              hg_board_rec_fields(f, HG_BOARD_REC_MAX, 99, 0, 2) == -1 &&
              hg_board_rec_fields(f, HG_BOARD_REC_MAX, 0, 99, 2) == -1,
          "a too small array, an unknown format, plant and model variant are refused");
    n1 = hg_board_rec_fields(f, HG_BOARD_REC_MAX, 0, HG_MODEL_REDUCED_CARTESIAN, 1);
    CHECK(n1 == 151, "format 1 has the 151 columns of d20d9e5's recorder (%d)", n1);
    test_coverage(n1, 1);
    n = hg_board_rec_fields(f, HG_BOARD_REC_MAX, 0, HG_MODEL_REDUCED_CARTESIAN, 2);
    test_coverage(n, 2);
    test_pack(n);
    test_round_trip(n);
    test_overflow(n);
    test_bind(n);
    return hg_test_exit();
}
