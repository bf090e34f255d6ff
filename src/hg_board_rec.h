/* hg_board_rec.h - the record pin set of the virtual board: every field of
 * hg_board_inputs (what hg_board_step consumes), the step's period, plant
 * and model variant, and the outputs replay compares, each with its
 * column name, type and place. One table, three users: the HAL glue
 * exports one pin motenc-hexaglide.<board>.rec.<name> per entry and
 * writes it from the very structs it passed to hg_board_step;
 * tools/hg_record.py records those pins; `hexaglide replay` maps the
 * columns back into hg_board_inputs. A field added to the board's inputs
 * without an entry here is caught by tests/unit/test_board_rec.c.
 *
 * Column names: "in.<field>" (inputs), "out.<field>" (outputs), with the
 * channel as a two-digit (DAC, encoder, ADC: all 8) or one-digit (the
 * plant's channels) suffix ("in.dac-v-03", "out.z-5"); the plant's own
 * outputs "out.<rec_name>" and injections "in.<hal name>". Bit arrays are
 * packed into one u32 (element k at bits [k*bits, (k+1)*bits)). Every pin
 * is finite: an input that HAL may hold as NaN or +-inf (DAC products,
 * scales, gains, parameters) shows 0 on its pin, and its state is in the
 * words "in.nonfinite-W": 2 bits per such field (bits 2j, 2j+1 of word W
 * for the field of nf_index 16W+j): 0 finite, 1 NaN, 2 +inf, 3 -inf. The
 * mask entries come last in the table, so setting the fields in table
 * order restores the non-finite values after the finite ones.
 *
 * Two formats (the record file's magic line says which):
 *   1 (commit d20d9e5 and before; the Hexaglide only): every model
 *     parameter is a column "in.param-<HAL name>", every period.
 *   2 (today): the parameters travel as events, so that a plant with
 *     hundreds of them fits sampler's 8 FIFOs of 21 pins: each period
 *     carries the fingerprint of the whole parameter block
 *     ("in.params-fp") and HG_BOARD_REC_SLOTS event slots
 *     ("in.pev-S-entry": 0 empty, else the entry + 1, the value's
 *     non-finite code in bits 16..17; "in.pev-S-value"; "in.pev-S-age":
 *     periods since the value took effect). The stream
 *     (hg_board_rec_stream) sends the plant's whole block from the period
 *     it starts (the entries that differ from the defaults first), then
 *     every entry that changes, in order (substeps and
 *     integrator stay columns, as in format 1); a replay reads
 *     ahead, applies each value at the period it took effect and checks
 *     the fingerprint of every period ("in.plant" names the plant).
 *
 * Pure C, no stdio, no malloc: the realtime glue uses it. */
#ifndef HG_BOARD_REC_H
#define HG_BOARD_REC_H

#include "hg_board.h"

#define HG_BOARD_REC_MAX 200          /* entries; sampler records 8 FIFOs x 21 pins at most,
                                         and the recorder adds the joint commands */
#define HG_BOARD_REC_NAME 32          /* bytes of a name, NUL included */
#define HG_BOARD_REC_NF_WORDS_MAX 5   /* in.nonfinite-0..4: up to 80 fields that may be NaN/inf */
#define HG_BOARD_REC_SLOTS 2          /* parameter event slots per period (format 2) */
#define HG_BOARD_REC_QUEUE 512        /* parameter events waiting for a slot */
#define HG_BOARD_REC_FORMAT 2         /* the format the glue records */

typedef enum {
    HG_BRF_F64 = 0,                   /* double (HAL float) */
    HG_BRF_S32 = 1,                   /* int (HAL s32) */
    HG_BRF_U32 = 2,                   /* unsigned (HAL u32) */
    HG_BRF_BIT = 3,                   /* int 0/1 (HAL bit) */
    HG_BRF_PACK = 4                   /* int or unsigned array packed into a HAL u32 */
} hg_board_rec_type;

typedef enum {
    HG_BRS_IN = 0,                    /* field of hg_board_inputs */
    HG_BRS_OUT = 1,                   /* field of hg_board_outputs */
    HG_BRS_PERIOD = 2,                /* hg_board_step's period_ns */
    HG_BRS_MODEL = 3,                 /* the board's model variant */
    HG_BRS_NFMASK = 4,                /* in.nonfinite-W: offset is W */
    HG_BRS_PARAM = 5,                 /* format 1: parameter column, offset is the table entry */
    HG_BRS_PLANT = 6,                 /* format 2: the plant's registry index */
    HG_BRS_PARAMS_FP = 7,             /* format 2: fingerprint of the parameter block */
    HG_BRS_EVENT = 8                  /* format 2: event slot offset / 3, part offset % 3
                                         (0 entry, 1 value, 2 age) */
} hg_board_rec_side;

/* One record column. */
typedef struct {
    char name[HG_BOARD_REC_NAME];     /* column name, e.g. "in.dac-v-00" */
    unsigned char type;               /* hg_board_rec_type */
    unsigned char side;               /* hg_board_rec_side */
    unsigned char nonfinite;          /* 1: HAL may hold NaN/inf here (encoded in in.nonfinite-*) */
    unsigned char pack_n;             /* PACK: elements */
    unsigned char pack_bits;          /* PACK: bits per element */
    unsigned char pack_elem;          /* PACK: bytes per element (sizeof int) */
    unsigned char pack_shift;         /* PACK: an element is (value >> pack_shift) of the field */
    unsigned long offset;             /* in the side's struct (or as the side says) */
    unsigned nf_index;                /* nonfinite: its 2-bit slot in the in.nonfinite-* words */
} hg_board_rec_field;

/* Fill f[0..max) with the table of `format` (1 or 2) for the plant at
 * registry index `plant` with model variant `variant` (its channels;
 * format 1: the Hexaglide only); returns the number of entries, or -1 if
 * max is too small or the plant, variant or format is unknown. */
int hg_board_rec_fields(hg_board_rec_field *f, int max, int plant, int variant, int format);

/* One parameter event (format 2). */
typedef struct {
    unsigned entry;                   /* the plant's table entry */
    double value;
    unsigned long at;                 /* the stream period it took effect in */
} hg_board_rec_event;

/* The sender of the parameter events (format 2): what it has told, what waits. */
typedef struct {
    int started;
    int lost;                         /* 1: the queue overflowed; events were lost since */
    unsigned long period;             /* periods since the stream started */
    hg_board_params told;             /* the block as the events so far tell it */
    hg_board_rec_event q[HG_BOARD_REC_QUEUE];
    int head, count;
    hg_board_rec_event slot[HG_BOARD_REC_SLOTS]; /* this period's (entry ~0u: empty) */
    unsigned fingerprint;             /* of this period's block */
} hg_board_rec_stream;

/* Fingerprint of the first n plant entries, substeps and integrator of p
 * (FNV-1a over the bits, never 0). */
unsigned hg_board_rec_fingerprint(const hg_board_params *p, int n);

/* The value of the plant's entry e (of n) in p (0 past them). */
double hg_board_rec_entry(const hg_board_params *p, int n, unsigned e);

/* Set the plant's entry e (of n) of p to v (none past them). */
void hg_board_rec_entry_set(hg_board_params *p, int n, unsigned e, double v);

/* Start the stream of a board of plant and variant (nothing told yet: the
 * first period queues the whole block, the entries that differ from the
 * plant's defaults first: a replay starts from the defaults, so a record
 * shorter than the block's periods still carries every value that matters). */
void hg_board_rec_stream_start(hg_board_rec_stream *s, int plant, int variant);

/* One recorded period with input block p (n plant entries): queue what
 * changed (everything, in the first period), fill this period's slots. */
void hg_board_rec_stream_step(hg_board_rec_stream *s, const hg_board_params *p, int n);

/* Everything a column's value comes from in one period. */
typedef struct {
    const hg_board_inputs *in;        /* the structs hg_board_step got and gave */
    const hg_board_outputs *out;
    long period_ns;                   /* its other arguments */
    int plant, variant;
    const hg_board_rec_stream *stream; /* format 2's parameter events (may be 0: slots empty) */
} hg_board_rec_ctx;

/* Value (always finite) of entry i of table t[0..n) in one period. Exact:
 * every int and packed word fits a double; a NaN/inf input reads 0 and is
 * described by the in.nonfinite-* entries. */
double hg_board_rec_get(const hg_board_rec_field *t, int n, int i, const hg_board_rec_ctx *c);

/* Store v (from a record) into the input of entry i of table t[0..n)
 * (inputs and format 1's parameters only; others are ignored). Integer
 * types take the integer v holds; an in.nonfinite-* word sets the fields
 * it marks to NaN/+-inf, so set every entry in table order. */
void hg_board_rec_set(const hg_board_rec_field *t, int n, int i, hg_board_inputs *in, double v);

/* The event of slot part values (entry word, value, age) recorded in a
 * row of stream period `row`: 1 and *ev filled, or 0 for an empty slot. */
int hg_board_rec_event_of(double entry_word, double value, double age, unsigned long row,
                          hg_board_rec_event *ev);

#endif
