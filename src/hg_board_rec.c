/* hg_board_rec.c - the record pin set of the virtual board (hg_board_rec.h). */
#include <stddef.h>
#include "hg_math.h"
#include "hg_string.h"
#include "hg_board_rec.h"

typedef char hg_board_rec_sizes[(HG_BOARD_DACS == 8 && HG_BOARD_ENCODERS == 8 && HG_BOARD_ADCS == 8 &&
                                 HG_CHANNELS_MAX == 8 && HG_BOARD_INPUTS <= 96) ? 1 : -1];

/* The table being built: f[0..max), n used; -1 in n once it overflowed. */
typedef struct {
    hg_board_rec_field *f;
    int n, max;
} builder;

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

/* A new entry called a + b (all else 0), or 0 when the table is full. */
static hg_board_rec_field *add(builder *t, const char *a, const char *b, int type, int side, unsigned long off)
{
    hg_board_rec_field *e;
    if (t->n < 0 || t->n >= t->max) {
        t->n = -1;
        return 0;
    }
    e = &t->f[t->n++];
    memset(e, 0, sizeof *e);
    join(e->name, a, b);
    e->type = (unsigned char)type;
    e->side = (unsigned char)side;
    e->offset = off;
    return e;
}

/* An input field. */
static void in1(builder *t, const char *name, int type, unsigned long off, int nonfinite)
{
    hg_board_rec_field *e = add(t, name, "", type, HG_BRS_IN, off);
    if (e)
        e->nonfinite = (unsigned char)nonfinite;
}

/* An output field. */
static void out1(builder *t, const char *name, int type, unsigned long off)
{
    add(t, name, "", type, HG_BRS_OUT, off);
}

/* name-CC (two digits, digits 2) or name-C (digits 1) for k = 0..count-1
 * of an array at off with elements of `size` bytes. */
static void array(builder *t, const char *name, int type, int side, unsigned long off, unsigned long size,
                  int count, int digits, int nonfinite)
{
    int k;
    for (k = 0; k < count; k++) {
        char suffix[5] = {'-', 0, 0, 0, 0};
        hg_board_rec_field *e;
        if (digits == 2) {
            suffix[1] = (char)('0' + k / 10);
            suffix[2] = (char)('0' + k % 10);
        } else {
            suffix[1] = (char)('0' + k);
        }
        e = add(t, name, suffix, type, side, off + (unsigned long)k * size);
        if (e)
            e->nonfinite = (unsigned char)nonfinite;
    }
}

/* A packed array of count elements of `bits` (the field's value >> shift). */
static void pack(builder *t, const char *name, int side, unsigned long off, int count, int bits, int elem,
                 int shift)
{
    hg_board_rec_field *e = add(t, name, "", HG_BRF_PACK, side, off);
    if (!e)
        return;
    e->pack_n = (unsigned char)count;
    e->pack_bits = (unsigned char)bits;
    e->pack_elem = (unsigned char)elem;
    e->pack_shift = (unsigned char)shift;
}

#define IN_OFF(f) offsetof(hg_board_inputs, f)
#define OUT_OFF(f) offsetof(hg_board_outputs, f)

/* The inputs every format records, in hg_board_inputs' order (nch: the plant's channels). */
static void inputs(builder *t, int nch)
{
    array(t, "in.dac-v", HG_BRF_F64, HG_BRS_IN, IN_OFF(dac_v), sizeof(double), HG_BOARD_DACS, 2, 1);
    in1(t, "in.dac-written", HG_BRF_BIT, IN_OFF(dac_written), 0);
    in1(t, "in.dac-stale", HG_BRF_BIT, IN_OFF(dac_stale), 0);
    in1(t, "in.dout-values", HG_BRF_U32, IN_OFF(dout_values), 0);
    in1(t, "in.dout-inverts", HG_BRF_U32, IN_OFF(dout_inverts), 0);
    in1(t, "in.estop-loop-out", HG_BRF_S32, IN_OFF(estop_loop_out), 0);
    in1(t, "in.estop-button", HG_BRF_BIT, IN_OFF(estop_button), 0);
    in1(t, "in.reset", HG_BRF_BIT, IN_OFF(reset), 0);
    in1(t, "in.watchdog-control", HG_BRF_U32, IN_OFF(watchdog_control), 0);
    in1(t, "in.watchdog-reset", HG_BRF_BIT, IN_OFF(watchdog_reset), 0);
    pack(t, "in.index-enable", HG_BRS_IN, IN_OFF(index_enable), HG_BOARD_ENCODERS, 1, sizeof(int), 0);
    pack(t, "in.enc-reset", HG_BRS_IN, IN_OFF(enc_reset), HG_BOARD_ENCODERS, 1, sizeof(int), 0);
    array(t, "in.enc-scale", HG_BRF_F64, HG_BRS_IN, IN_OFF(enc_scale), sizeof(double), HG_BOARD_ENCODERS, 2, 1);
    in1(t, "in.adc-read", HG_BRF_BIT, IN_OFF(adc_read), 0);
    array(t, "in.adc-gain", HG_BRF_F64, HG_BRS_IN, IN_OFF(adc_gain), sizeof(double), HG_BOARD_ADCS, 2, 1);
    array(t, "in.adc-offset", HG_BRF_F64, HG_BRS_IN, IN_OFF(adc_offset), sizeof(double), HG_BOARD_ADCS, 2, 1);
    in1(t, "in.adc-volts-per-amp", HG_BRF_F64, IN_OFF(adc_volts_per_amp), 1);
    pack(t, "in.amp-fail", HG_BRS_IN, IN_OFF(amp_fail), nch, 1, sizeof(int), 0);
    pack(t, "in.stuck", HG_BRS_IN, IN_OFF(stuck), nch, 3, sizeof(int), 0);
    pack(t, "in.tripped", HG_BRS_IN, IN_OFF(tripped), nch, 3, sizeof(int), 0);
    pack(t, "in.index-lost", HG_BRS_IN, IN_OFF(index_lost), nch, 1, sizeof(int), 0);
    array(t, "in.enc-glitch", HG_BRF_S32, HG_BRS_IN, IN_OFF(enc_glitch), sizeof(int), nch, 1, 0);
}

/* The plant's injections, one packed column each (nch: its channels). */
static void injections(builder *t, const hg_plant *p, int nch)
{
    int i;
    for (i = 0; i < p->ninjections; i++) {
        char name[HG_BOARD_REC_NAME];
        join(name, "in.", p->injections[i].hal_name);
        pack(t, name, HG_BRS_IN, IN_OFF(inject), nch, 1, sizeof(int), i);
    }
}

/* The outputs replay compares: the sensors, the state, the plant's own. */
static void outputs(builder *t, const hg_plant *p, int nch, int motor_pos)
{
    int i;
    array(t, "out.count", HG_BRF_S32, HG_BRS_OUT, OUT_OFF(count), sizeof(int), HG_BOARD_ENCODERS, 2, 0);
    pack(t, "out.index", HG_BRS_OUT, OUT_OFF(index), HG_BOARD_ENCODERS, 1, sizeof(int), 0);
    pack(t, "out.index-latched", HG_BRS_OUT, OUT_OFF(index_latched), HG_BOARD_ENCODERS, 1, sizeof(int), 0);
    pack(t, "out.in-word-0", HG_BRS_OUT, OUT_OFF(in[0]), 32, 1, 1, 0);
    pack(t, "out.in-word-1", HG_BRS_OUT, OUT_OFF(in[32]), 32, 1, 1, 0);
    pack(t, "out.in-word-2", HG_BRS_OUT, OUT_OFF(in[64]), HG_BOARD_INPUTS - 64, 1, 1, 0);
    out1(t, "out.dout-word", HG_BRF_U32, OUT_OFF(dout_word));
    out1(t, "out.estop-in", HG_BRF_BIT, OUT_OFF(estop_in));
    array(t, "out.z", HG_BRF_F64, HG_BRS_OUT, OUT_OFF(pos), sizeof(double), nch, 1, 0);
    array(t, "out.zd", HG_BRF_F64, HG_BRS_OUT, OUT_OFF(vel), sizeof(double), nch, 1, 0);
    if (motor_pos) {                  /* format 2: the drive train's encoder side, the tool */
        array(t, "out.motor-pos", HG_BRF_F64, HG_BRS_OUT, OUT_OFF(motor_pos), sizeof(double), nch, 1, 0);
        out1(t, "out.tool-error", HG_BRF_F64, OUT_OFF(tool_error));
    }
    array(t, "out.current", HG_BRF_F64, HG_BRS_OUT, OUT_OFF(current_a), sizeof(double), nch, 1, 0);
    for (i = 0; i < p->noutputs && i < HG_PLANT_EXTRA_MAX; i++) /* the plant's own, as recorded */
        if (p->outputs[i].rec_name && !p->outputs[i].is_u32)
            add(t, "out.", p->outputs[i].rec_name, HG_BRF_F64, HG_BRS_OUT,
                OUT_OFF(extra) + (unsigned long)i * sizeof(double));
    out1(t, "out.steps", HG_BRF_U32, OUT_OFF(steps));
    for (i = 0; i < p->noutputs && i < HG_PLANT_EXTRA_MAX; i++)
        if (p->outputs[i].rec_name && p->outputs[i].is_u32)
            add(t, "out.", p->outputs[i].rec_name, HG_BRF_U32, HG_BRS_OUT,
                OUT_OFF(extra) + (unsigned long)i * sizeof(double));
    out1(t, "out.fault", HG_BRF_BIT, OUT_OFF(fault));
    out1(t, "out.fault-code", HG_BRF_S32, OUT_OFF(fault_code));
    out1(t, "out.amps-on", HG_BRF_BIT, OUT_OFF(amps_on));
    out1(t, "out.events", HG_BRF_U32, OUT_OFF(events));
}

/* Number the NaN-capable entries and append the nonfinite words: the table's length or -1. */
static int finish(builder *t)
{
    static const char *const word[HG_BOARD_REC_NF_WORDS_MAX] = {
        "in.nonfinite-0", "in.nonfinite-1", "in.nonfinite-2", "in.nonfinite-3", "in.nonfinite-4",
    };
    int k, nf = 0, n = t->n, words;
    for (k = 0; k < n; k++)
        if (t->f[k].nonfinite)
            t->f[k].nf_index = (unsigned)nf++;
    words = (nf + 15) / 16;
    if (n < 0 || words > HG_BOARD_REC_NF_WORDS_MAX)
        return -1;
    for (k = 0; k < words; k++)
        add(t, word[k], "", HG_BRF_U32, HG_BRS_NFMASK, (unsigned long)k);
    return t->n;
}

/* Format 1's parameter columns (the Hexaglide's table at d20d9e5), in its order: frozen. */
static const char *const format1_params[] = {
    "l", "lb", "e", "lp", "cone_carriage", "cone_head", "d_bar", "tool_d", "g", "m_head", "head_com",
    "i_head_xx", "i_head_yy", "i_head_zz", "m_bar", "i_bar", "m_carriage", "lead", "j_rotor", "kt",
    "r_winding", "l_winding", "amp_mode", "ka", "i_max", "v_bus", "v_rated", "kp_vel", "ki_vel", "c_visc",
    "f_coulomb", "f_static", "v_stribeck", "stop_min", "stop_max", "k_stop", "c_stop", "limit_min",
    "limit_max", "home_switch", "counts_per_rev",
};

int hg_board_rec_fields(hg_board_rec_field *f, int max, int plant, int variant, int format)
{
    const hg_plant *p = hg_plant_at(plant);
    builder t;
    int k, nch;
    t.f = f;
    t.n = 0;
    t.max = max;
    if (!p || !hg_plant_nparams_at(plant, variant) || (format == 1 && plant != 0) || format < 1 || format > 2)
        return -1;
    nch = p->channels(variant);
    add(&t, "in.period-ns", "", HG_BRF_S32, HG_BRS_PERIOD, 0);
    if (format == 2)
        add(&t, "in.plant", "", HG_BRF_U32, HG_BRS_PLANT, 0);
    add(&t, "in.model", "", HG_BRF_U32, HG_BRS_MODEL, 0);
    inputs(&t, nch);
    injections(&t, p, nch);
    if (format == 2)                  /* the commands of the tool-path error */
        array(&t, "in.pos-cmd", HG_BRF_F64, HG_BRS_IN, IN_OFF(pos_cmd), sizeof(double), nch, 1, 1);
    in1(&t, "in.substeps", HG_BRF_U32, IN_OFF(params.substeps), 0);
    in1(&t, "in.integrator", HG_BRF_U32, IN_OFF(params.integrator), 0);
    outputs(&t, p, nch, format == 2);
    if (format == 1) {                /* every parameter of that day, every period */
        for (k = 0; k < (int)(sizeof format1_params / sizeof format1_params[0]); k++) {
            hg_param_info e0;
            hg_board_rec_field *e;
            int i = hg_plant_param_find(p, variant, format1_params[k]);
            if (i < 0)
                return -1;
            p->param(variant, i, &e0);
            e = add(&t, "in.param-", e0.hal_name, HG_BRF_F64, HG_BRS_PARAM, (unsigned long)i);
            if (e)
                e->nonfinite = 1;
        }
    } else {                          /* the fingerprint and the event slots */
        static const char *const slot_name[HG_BOARD_REC_SLOTS][3] = {
            {"in.pev-0-entry", "in.pev-0-value", "in.pev-0-age"},
            {"in.pev-1-entry", "in.pev-1-value", "in.pev-1-age"},
        };
        int s;
        add(&t, "in.params-fp", "", HG_BRF_U32, HG_BRS_PARAMS_FP, 0);
        for (s = 0; s < HG_BOARD_REC_SLOTS; s++) {
            add(&t, slot_name[s][0], "", HG_BRF_U32, HG_BRS_EVENT, 3ul * (unsigned long)s);
            add(&t, slot_name[s][1], "", HG_BRF_F64, HG_BRS_EVENT, 3ul * (unsigned long)s + 1ul);
            add(&t, slot_name[s][2], "", HG_BRF_U32, HG_BRS_EVENT, 3ul * (unsigned long)s + 2ul);
        }
    }
    return finish(&t);
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

/* The double of a 2-bit non-finite code (0 for code 0). */
static double nf_value(unsigned code)
{
    return code == 1u ? (double)NAN : code == 2u ? (double)INFINITY : code == 3u ? -(double)INFINITY : 0.0;
}

unsigned hg_board_rec_fingerprint(const hg_board_params *p, int n)
{
    unsigned h = 2166136261u;
    int i, k;
    for (i = 0; i < n + 2; i++) {     /* the plant's entries, substeps, integrator */
        double v = i < n ? p->plant.v[i] : i == n ? (double)p->substeps : (double)p->integrator;
        unsigned long long bits;
        memcpy(&bits, &v, sizeof bits);
        for (k = 0; k < 8; k++, bits >>= 8)
            h = (h ^ (unsigned)(bits & 0xffu)) * 16777619u;
    }
    return h ? h : 1u;
}

double hg_board_rec_entry(const hg_board_params *p, int n, unsigned e)
{
    return e < (unsigned)n && e < HG_PLANT_PARAMS_MAX ? p->plant.v[e] : 0.0;
}

void hg_board_rec_entry_set(hg_board_params *p, int n, unsigned e, double v)
{
    if (e < (unsigned)n && e < HG_PLANT_PARAMS_MAX)
        p->plant.v[e] = v;
}

void hg_board_rec_stream_start(hg_board_rec_stream *s, int plant, int variant)
{
    int k;
    if (hg_board_params_default(plant, variant, &s->told))
        memset(&s->told, 0, sizeof s->told);
    s->started = 0;
    s->lost = 0;
    s->period = 0;
    s->head = s->count = 0;
    for (k = 0; k < HG_BOARD_REC_SLOTS; k++)
        s->slot[k].entry = ~0u;
}

/* Queue entry e's value v, effective now. */
static void enqueue(hg_board_rec_stream *s, unsigned e, double v)
{
    hg_board_rec_event *ev;
    if (s->count == HG_BOARD_REC_QUEUE) {
        s->lost = 1;                  /* the replay finds it through the fingerprint */
        return;
    }
    ev = &s->q[(s->head + s->count) % HG_BOARD_REC_QUEUE];
    ev->entry = e;
    ev->value = v;
    ev->at = s->period;
    s->count++;
}

/* 1 if entry e of p differs bitwise from what s has told (a NaN equals itself). */
static int changed(const hg_board_rec_stream *s, const hg_board_params *p, int n, unsigned e)
{
    double v = hg_board_rec_entry(p, n, e), w = hg_board_rec_entry(&s->told, n, e);
    return memcmp(&v, &w, sizeof v) != 0; // NOLINT(bugprone-suspicious-memory-comparison): bitwise on purpose
}

void hg_board_rec_stream_step(hg_board_rec_stream *s, const hg_board_params *p, int n)
{
    unsigned e;
    int k, pass;
    if (s->started)
        s->period++;
    if (!s->started) {                 /* the whole block: those that differ from the defaults (where a replay
                                          starts) first, so that a record of a few periods still carries them */
        for (pass = 0; pass < 2; pass++)
            for (e = 0; e < (unsigned)n; e++)
                if (changed(s, p, n, e) == (pass == 0))
                    enqueue(s, e, hg_board_rec_entry(p, n, e));
        for (e = 0; e < (unsigned)n; e++)
            hg_board_rec_entry_set(&s->told, n, e, hg_board_rec_entry(p, n, e));
    } else {                           /* then what changed */
        for (e = 0; e < (unsigned)n; e++)
            if (changed(s, p, n, e)) {
                enqueue(s, e, hg_board_rec_entry(p, n, e));
                hg_board_rec_entry_set(&s->told, n, e, hg_board_rec_entry(p, n, e));
            }
    }
    s->started = 1;
    for (k = 0; k < HG_BOARD_REC_SLOTS; k++) {
        if (s->count == 0) {
            s->slot[k].entry = ~0u;
            continue;
        }
        s->slot[k] = s->q[s->head];
        s->head = (s->head + 1) % HG_BOARD_REC_QUEUE;
        s->count--;
    }
    s->fingerprint = hg_board_rec_fingerprint(p, n);
}

int hg_board_rec_event_of(double entry_word, double value, double age, unsigned long row,
                          hg_board_rec_event *ev)
{
    unsigned w = entry_word >= 0.0 && entry_word <= 4294967295.0 ? (unsigned)entry_word : 0u;
    unsigned long a = age >= 0.0 && age <= 4294967295.0 ? (unsigned long)age : 0ul;
    if ((w & 0xffffu) == 0u || a > row)
        return 0;
    ev->entry = (w & 0xffffu) - 1u;
    ev->value = (w >> 16) & 3u ? nf_value((w >> 16) & 3u) : value;
    ev->at = row - a;
    return 1;
}

/* Element k of a packed array at p. */
static unsigned elem_at(const hg_board_rec_field *f, const char *p, int k)
{
    unsigned u;
    if (f->pack_elem == 1)
        return ((const unsigned char *)p)[k];
    memcpy(&u, p + (size_t)k * f->pack_elem, sizeof u);
    return u >> f->pack_shift;
}

/* Slot part value of the stream (0 for an empty slot or no stream). */
static double event_part(const hg_board_rec_stream *s, unsigned long off)
{
    const hg_board_rec_event *ev;
    if (!s || off / 3 >= HG_BOARD_REC_SLOTS || s->slot[off / 3].entry == ~0u)
        return 0.0;
    ev = &s->slot[off / 3];
    switch (off % 3) {
    case 0: return (double)((ev->entry + 1u) | (nf_code(ev->value) << 16));
    case 1: return isfinite(ev->value) ? ev->value : 0.0;
    default: return (double)(s->period - ev->at);
    }
}

double hg_board_rec_get(const hg_board_rec_field *t, int n, int i, const hg_board_rec_ctx *c)
{
    const hg_board_rec_field *f = &t[i];
    const char *p;
    double d;
    int v, k;
    unsigned u;
    switch (f->side) {
    case HG_BRS_PERIOD:
        return (double)(c->period_ns > 2147483647L ? 2147483647L : c->period_ns < -2147483647L ? -2147483647L
                                                                                               : c->period_ns);
    case HG_BRS_MODEL:
        return (double)c->variant;
    case HG_BRS_PLANT:
        return (double)c->plant;
    case HG_BRS_PARAMS_FP:
        return c->stream ? (double)c->stream->fingerprint : 0.0;
    case HG_BRS_EVENT:
        return event_part(c->stream, f->offset);
    case HG_BRS_PARAM:
        d = f->offset < HG_PLANT_PARAMS_MAX ? c->in->params.plant.v[f->offset] : 0.0;
        return isfinite(d) ? d : 0.0;
    case HG_BRS_NFMASK: {
        unsigned word = 0;
        for (k = 0; k < n; k++) {
            unsigned slot = t[k].nf_index - 16u * (unsigned)f->offset;
            if (!t[k].nonfinite || slot >= 16u)
                continue;
            if (t[k].side == HG_BRS_PARAM)
                d = t[k].offset < HG_PLANT_PARAMS_MAX ? c->in->params.plant.v[t[k].offset] : 0.0;
            else if (t[k].side == HG_BRS_IN)
                memcpy(&d, (const char *)c->in + t[k].offset, sizeof d);
            else
                continue;
            word |= nf_code(d) << (2u * slot);
        }
        return (double)word;
    }
    default:
        break;
    }
    p = (f->side == HG_BRS_IN ? (const char *)c->in : (const char *)c->out) + f->offset;
    switch (f->type) {
    case HG_BRF_F64:
        memcpy(&d, p, sizeof d);
        return isfinite(d) ? d : 0.0;
    case HG_BRF_S32:
        memcpy(&v, p, sizeof v);
        return (double)v;
    case HG_BRF_U32:
        if (f->side == HG_BRS_OUT && f->offset >= OUT_OFF(extra) &&
            f->offset < OUT_OFF(extra) + sizeof c->out->extra) {   /* a plant's count, held as a double */
            memcpy(&d, p, sizeof d);
            return d >= 0.0 && d <= 4294967295.0 ? floor(d) : 0.0;
        }
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

/* Point of entry f in in: its field, or format 1's parameter. */
static char *field_of(const hg_board_rec_field *f, hg_board_inputs *in)
{
    if (f->side == HG_BRS_PARAM)
        return f->offset < HG_PLANT_PARAMS_MAX ? (char *)&in->params.plant.v[f->offset] : 0;
    return (char *)in + f->offset;
}

void hg_board_rec_set(const hg_board_rec_field *t, int n, int i, hg_board_inputs *in, double v)
{
    const hg_board_rec_field *f = &t[i];
    char *p;
    int iv, k;
    unsigned u;
    if (f->side == HG_BRS_NFMASK) {
        unsigned word = (v >= 0.0 && v <= 4294967295.0) ? (unsigned)v : 0u;
        for (k = 0; k < n; k++) {
            unsigned slot = t[k].nf_index - 16u * (unsigned)f->offset, code;
            double d;
            char *q;
            if (!t[k].nonfinite || (t[k].side != HG_BRS_IN && t[k].side != HG_BRS_PARAM) || slot >= 16u)
                continue;
            code = (word >> (2u * slot)) & 3u;
            q = field_of(&t[k], in);
            if (code == 0u || !q)
                continue;
            d = nf_value(code);
            memcpy(q, &d, sizeof d);
        }
        return;
    }
    if (f->side != HG_BRS_IN && f->side != HG_BRS_PARAM)
        return;
    p = field_of(f, in);
    if (!p)
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
            if (f->pack_elem == 1) {
                ((unsigned char *)p)[k] = (unsigned char)e;
            } else {                  /* only this field's bits of the element */
                unsigned old;
                memcpy(&old, p + (size_t)k * f->pack_elem, sizeof old);
                old = (old & ~(mask << f->pack_shift)) | (e << f->pack_shift);
                memcpy(p + (size_t)k * f->pack_elem, &old, sizeof old);
            }
        }
    }
    }
}
