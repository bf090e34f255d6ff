/* hg_board_rec.h - the record pin set of the virtual board: every field of
 * hg_board_inputs (what hg_board_step consumes), the step's period and
 * model, and the outputs replay compares, each with its column name, type
 * and place. One table, three users: the HAL glue exports one pin
 * motenc-hexaglide.<board>.rec.<name> per entry and writes it from the
 * very structs it passed to hg_board_step; tools/hg_record.py records
 * those pins; `hexaglide replay` maps the columns back into
 * hg_board_inputs. A field added to the board's inputs without an entry
 * here is caught by tests/unit/test_board_rec.c.
 *
 * Column names: "in.<field>" (inputs), "out.<field>" (outputs), with the
 * channel or joint as a two-digit / one-digit suffix ("in.dac-v-03",
 * "out.z-5"); parameters "in.param-<HAL name>" in SI units. Bit arrays are
 * packed into one u32 (element k at bits [k*bits, (k+1)*bits)).
 * Every pin is finite: an input that HAL may hold as NaN or +-inf (DAC
 * products, scales, gains, parameters) shows 0 on its pin, and its state
 * is in the words "in.nonfinite-W": 2 bits per such field (bits 2j, 2j+1
 * of word W for the field of nf_index 16W+j): 0 finite, 1 NaN, 2 +inf,
 * 3 -inf. The mask entries come last in the table, so setting the fields
 * in table order restores the non-finite values after the finite ones.
 *
 * Pure C, no stdio, no malloc: the realtime glue uses it. */
#ifndef HG_BOARD_REC_H
#define HG_BOARD_REC_H

#include "hg_board.h"

#define HG_BOARD_REC_MAX 160          /* entries; sampler records 8 FIFOs x 21 pins at most,
                                         and the recorder adds the 6 joint commands */
#define HG_BOARD_REC_NAME 32          /* bytes of a name, NUL included */
#define HG_BOARD_REC_NF_WORDS 5       /* in.nonfinite-0..4: up to 80 fields that may be NaN/inf */

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
    HG_BRS_MODEL = 3,                 /* hg_model_kind the board runs */
    HG_BRS_NFMASK = 4                 /* in.nonfinite-W: offset is W */
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
    unsigned long offset;             /* in the side's struct (0 for PERIOD, MODEL; W for NFMASK) */
    unsigned nf_index;                /* nonfinite: its 2-bit slot in the in.nonfinite-* words */
} hg_board_rec_field;

/* Fill f[0..max) with the table (fixed part, then one entry per model
 * parameter of hg_params_table); returns the number of entries, or -1 if
 * max is too small. */
int hg_board_rec_fields(hg_board_rec_field *f, int max);

/* Value (always finite) of entry i of table t[0..n) in one period: in/out
 * the structs hg_board_step got and gave, period_ns and model its other
 * arguments. Exact: every int and packed word fits a double; a NaN/inf
 * input reads 0 and is described by the in.nonfinite-* entries. */
double hg_board_rec_get(const hg_board_rec_field *t, int n, int i, const hg_board_inputs *in,
                        const hg_board_outputs *out, long period_ns, int model);

/* Store v (from a record) into the input of entry i of table t[0..n)
 * (inputs only; others are ignored). Integer types take the integer v
 * holds; an in.nonfinite-* word sets the fields it marks to NaN/+-inf, so
 * set every entry in table order. */
void hg_board_rec_set(const hg_board_rec_field *t, int n, int i, hg_board_inputs *in, double v);

#endif
