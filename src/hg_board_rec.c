/* hg_board_rec.c - the record pin set of the virtual board (hg_board_rec.h). */
#include <stddef.h>
#include "hg_math.h"
#include "hg_string.h"
#include "hg_board_rec.h"

/* Table macros: n is a string literal pasted to a suffix, f a member
 * designator for offsetof; neither can take parentheses. */
/* NOLINTBEGIN(bugprone-macro-parentheses) */
#define IN(n, t, f, nf) { n, t, HG_BRS_IN, nf, 0, 0, 0, offsetof(hg_board_inputs, f), 0 }
#define OUT(n, t, f) { n, t, HG_BRS_OUT, 0, 0, 0, 0, offsetof(hg_board_outputs, f), 0 }
#define INPACK(n, f, cnt, bits) \
    { n, HG_BRF_PACK, HG_BRS_IN, 0, cnt, bits, sizeof(int), offsetof(hg_board_inputs, f), 0 }
#define OUTPACK(n, f, cnt, bits, elem) \
    { n, HG_BRF_PACK, HG_BRS_OUT, 0, cnt, bits, elem, offsetof(hg_board_outputs, f), 0 }
#define IN8(n, t, f, nf) IN(n "-00", t, f[0], nf), IN(n "-01", t, f[1], nf), IN(n "-02", t, f[2], nf), \
    IN(n "-03", t, f[3], nf), IN(n "-04", t, f[4], nf), IN(n "-05", t, f[5], nf), \
    IN(n "-06", t, f[6], nf), IN(n "-07", t, f[7], nf)
#define IN6(n, t, f, nf) IN(n "-0", t, f[0], nf), IN(n "-1", t, f[1], nf), IN(n "-2", t, f[2], nf), \
    IN(n "-3", t, f[3], nf), IN(n "-4", t, f[4], nf), IN(n "-5", t, f[5], nf)
#define OUT8(n, t, f) OUT(n "-00", t, f[0]), OUT(n "-01", t, f[1]), OUT(n "-02", t, f[2]), \
    OUT(n "-03", t, f[3]), OUT(n "-04", t, f[4]), OUT(n "-05", t, f[5]), OUT(n "-06", t, f[6]), \
    OUT(n "-07", t, f[7])
#define OUT6(n, t, f) OUT(n "-0", t, f[0]), OUT(n "-1", t, f[1]), OUT(n "-2", t, f[2]), \
    OUT(n "-3", t, f[3]), OUT(n "-4", t, f[4]), OUT(n "-5", t, f[5])
/* NOLINTEND(bugprone-macro-parentheses) */

typedef char hg_board_rec_8_channels[(HG_BOARD_DACS == 8 && HG_BOARD_ENCODERS == 8 &&
                                      HG_BOARD_ADCS == 8 && HG_BOARD_JOINTS == 6 &&
                                      HG_BOARD_INPUTS <= 96) ? 1 : -1];

/* Every field of hg_board_inputs, in its order, then the outputs compared
 * (the state and what the sensors show; the drive volts and the simulated
 * time follow from the inputs and the step count, and stay off the pin
 * budget of sampler's 8 FIFOs of 21 pins). */
static const hg_board_rec_field fixed[] = {
    {"in.period-ns", HG_BRF_S32, HG_BRS_PERIOD, 0, 0, 0, 0, 0, 0},
    {"in.model", HG_BRF_U32, HG_BRS_MODEL, 0, 0, 0, 0, 0, 0},
    IN8("in.dac-v", HG_BRF_F64, dac_v, 1),
    IN("in.dac-written", HG_BRF_BIT, dac_written, 0),
    IN("in.dac-stale", HG_BRF_BIT, dac_stale, 0),
    IN("in.dout-values", HG_BRF_U32, dout_values, 0),
    IN("in.dout-inverts", HG_BRF_U32, dout_inverts, 0),
    IN("in.estop-loop-out", HG_BRF_S32, estop_loop_out, 0),
    IN("in.estop-button", HG_BRF_BIT, estop_button, 0),
    IN("in.reset", HG_BRF_BIT, reset, 0),
    IN("in.watchdog-control", HG_BRF_U32, watchdog_control, 0),
    IN("in.watchdog-reset", HG_BRF_BIT, watchdog_reset, 0),
    INPACK("in.index-enable", index_enable, HG_BOARD_ENCODERS, 1),
    INPACK("in.enc-reset", enc_reset, HG_BOARD_ENCODERS, 1),
    IN8("in.enc-scale", HG_BRF_F64, enc_scale, 1),
    IN("in.adc-read", HG_BRF_BIT, adc_read, 0),
    IN8("in.adc-gain", HG_BRF_F64, adc_gain, 1),
    IN8("in.adc-offset", HG_BRF_F64, adc_offset, 1),
    IN("in.adc-volts-per-amp", HG_BRF_F64, adc_volts_per_amp, 1),
    INPACK("in.amp-fail", amp_fail, HG_BOARD_JOINTS, 1),
    INPACK("in.stuck", stuck, HG_BOARD_JOINTS, 3),
    INPACK("in.tripped", tripped, HG_BOARD_JOINTS, 3),
    INPACK("in.index-lost", index_lost, HG_BOARD_JOINTS, 1),
    IN6("in.enc-glitch", HG_BRF_S32, enc_glitch, 0),
    INPACK("in.bar-broken", bar_broken, HG_BOARD_JOINTS, 1),
    IN("in.substeps", HG_BRF_U32, params.substeps, 0),
    IN("in.integrator", HG_BRF_U32, params.integrator, 0),
    /* outputs compared by replay */
    OUT8("out.count", HG_BRF_S32, count),
    OUTPACK("out.index", index, HG_BOARD_ENCODERS, 1, sizeof(int)),
    OUTPACK("out.index-latched", index_latched, HG_BOARD_ENCODERS, 1, sizeof(int)),
    OUTPACK("out.in-word-0", in[0], 32, 1, 1),
    OUTPACK("out.in-word-1", in[32], 32, 1, 1),
    OUTPACK("out.in-word-2", in[64], HG_BOARD_INPUTS - 64, 1, 1),
    OUT("out.dout-word", HG_BRF_U32, dout_word),
    OUT("out.estop-in", HG_BRF_BIT, estop_in),
    OUT6("out.z", HG_BRF_F64, z_m),
    OUT6("out.zd", HG_BRF_F64, zd_mps),
    OUT6("out.current", HG_BRF_F64, current_a),
    OUT("out.pose-x", HG_BRF_F64, pose[0]),
    OUT("out.pose-y", HG_BRF_F64, pose[1]),
    OUT("out.pose-z", HG_BRF_F64, pose[2]),
    OUT("out.pose-a", HG_BRF_F64, pose[3]),
    OUT("out.pose-b", HG_BRF_F64, pose[4]),
    OUT("out.pose-c", HG_BRF_F64, pose[5]),
    OUT("out.steps", HG_BRF_U32, steps),
    OUT("out.bars-broken", HG_BRF_U32, bars_broken),
    OUT("out.fault", HG_BRF_BIT, fault),
    OUT("out.fault-code", HG_BRF_S32, fault_code),
    OUT("out.amps-on", HG_BRF_BIT, amps_on),
    OUT("out.events", HG_BRF_U32, events),
};

static const char *const mask_name[HG_BOARD_REC_NF_WORDS] = {
    "in.nonfinite-0", "in.nonfinite-1", "in.nonfinite-2", "in.nonfinite-3", "in.nonfinite-4",
};

/* dst = a then b, truncated to HG_BOARD_REC_NAME - 1 characters. */
static void join(char *dst, const char *a, const char *b)
{
    int k = 0;
    while (*a && k < HG_BOARD_REC_NAME - 1)
        dst[k++] = *a++;
    while (*b && k < HG_BOARD_REC_NAME - 1)
        dst[k++] = *b++;
    dst[k] = '\0';
}

int hg_board_rec_fields(hg_board_rec_field *f, int max)
{
    int n = (int)(sizeof fixed / sizeof fixed[0]), np = 0, k, nf = 0;
    const hg_param_info *t = hg_params_table(&np);
    if (n + np + HG_BOARD_REC_NF_WORDS > max)
        return -1;
    memcpy(f, fixed, sizeof fixed);
    for (k = 0; k < np; k++) {
        hg_board_rec_field *e = &f[n + k];
        memset(e, 0, sizeof *e);
        join(e->name, "in.param-", t[k].hal_name);
        e->type = HG_BRF_F64;
        e->side = HG_BRS_IN;
        e->nonfinite = 1;
        e->offset = offsetof(hg_board_inputs, params.model) + t[k].offset;
    }
    n += np;
    for (k = 0; k < n; k++)
        if (f[k].nonfinite)
            f[k].nf_index = (unsigned)nf++;
    if (nf > 16 * HG_BOARD_REC_NF_WORDS)
        return -1;
    for (k = 0; k < HG_BOARD_REC_NF_WORDS; k++) {
        hg_board_rec_field *e = &f[n + k];
        memset(e, 0, sizeof *e);
        join(e->name, mask_name[k], "");
        e->type = HG_BRF_U32;
        e->side = HG_BRS_NFMASK;
        e->offset = (unsigned long)k;
    }
    return n + HG_BOARD_REC_NF_WORDS;
}

/* 2-bit state of a double: 0 finite, 1 NaN, 2 +inf, 3 -inf. */
static unsigned nf_code(double d)
{
    if (isfinite(d))
        return 0u;
    if (d != d)
        return 1u;
    return d > 0 ? 2u : 3u;
}

/* Element k of a packed array at p. */
static unsigned elem_at(const hg_board_rec_field *f, const char *p, int k)
{
    if (f->pack_elem == 1)
        return ((const unsigned char *)p)[k];
    {
        unsigned u;
        memcpy(&u, p + (size_t)k * f->pack_elem, sizeof u);
        return u;
    }
}

double hg_board_rec_get(const hg_board_rec_field *t, int n, int i, const hg_board_inputs *in,
                        const hg_board_outputs *out, long period_ns, int model)
{
    const hg_board_rec_field *f = &t[i];
    const char *p;
    double d;
    int v, k;
    unsigned u;
    if (f->side == HG_BRS_PERIOD)
        return (double)(period_ns > 2147483647L ? 2147483647L : period_ns < -2147483647L ? -2147483647L
                                                                                          : period_ns);
    if (f->side == HG_BRS_MODEL)
        return (double)model;
    if (f->side == HG_BRS_NFMASK) {
        unsigned word = 0;
        for (k = 0; k < n; k++) {
            unsigned slot = t[k].nf_index - 16u * (unsigned)f->offset;
            if (!t[k].nonfinite || t[k].side != HG_BRS_IN || slot >= 16u)
                continue;
            memcpy(&d, (const char *)in + t[k].offset, sizeof d);
            word |= nf_code(d) << (2u * slot);
        }
        return (double)word;
    }
    p = (f->side == HG_BRS_IN ? (const char *)in : (const char *)out) + f->offset;
    switch (f->type) {
    case HG_BRF_F64:
        memcpy(&d, p, sizeof d);
        return isfinite(d) ? d : 0.0;
    case HG_BRF_S32:
        memcpy(&v, p, sizeof v);
        return (double)v;
    case HG_BRF_U32:
        memcpy(&u, p, sizeof u);
        return (double)u;
    case HG_BRF_BIT:
        memcpy(&v, p, sizeof v);
        return v ? 1.0 : 0.0;
    default: {
        unsigned word = 0, mask = (1u << f->pack_bits) - 1u;
        for (k = 0; k < f->pack_n && k < 32; k++)
            word |= (elem_at(f, p, k) & mask) << (k * f->pack_bits);
        return (double)word;
    }
    }
}

void hg_board_rec_set(const hg_board_rec_field *t, int n, int i, hg_board_inputs *in, double v)
{
    const hg_board_rec_field *f = &t[i];
    char *p = (char *)in + f->offset;
    int iv, k;
    unsigned u;
    if (f->side == HG_BRS_NFMASK) {
        unsigned word = (v >= 0.0 && v <= 4294967295.0) ? (unsigned)v : 0u;
        for (k = 0; k < n; k++) {
            unsigned slot = t[k].nf_index - 16u * (unsigned)f->offset, code;
            double d;
            if (!t[k].nonfinite || t[k].side != HG_BRS_IN || slot >= 16u)
                continue;
            code = (word >> (2u * slot)) & 3u;
            if (code == 0u)
                continue;
            d = code == 1u ? (double)NAN : code == 2u ? (double)INFINITY : -(double)INFINITY;
            memcpy((char *)in + t[k].offset, &d, sizeof d);
        }
        return;
    }
    if (f->side != HG_BRS_IN)
        return;
    switch (f->type) {
    case HG_BRF_F64:
        memcpy(p, &v, sizeof v);
        break;
    case HG_BRF_S32:
    case HG_BRF_BIT:
        iv = (v >= -2147483648.0 && v <= 2147483647.0) ? (int)v : 0;
        memcpy(p, &iv, sizeof iv);
        break;
    case HG_BRF_U32:
        u = (v >= 0.0 && v <= 4294967295.0) ? (unsigned)v : 0u;
        memcpy(p, &u, sizeof u);
        break;
    default: {
        unsigned word = (v >= 0.0 && v <= 4294967295.0) ? (unsigned)v : 0u;
        unsigned mask = (1u << f->pack_bits) - 1u;
        for (k = 0; k < f->pack_n && k < 32; k++) {
            unsigned e = (word >> (k * f->pack_bits)) & mask;
            if (f->pack_elem == 1)
                ((unsigned char *)p)[k] = (unsigned char)e;
            else
                memcpy(p + (size_t)k * f->pack_elem, &e, sizeof e);
        }
    }
    }
}
