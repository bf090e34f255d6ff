/* hg_board_rec_read.c - a board record's columns needed and typed (hg_board_rec_read.h). */
#include <stdio.h>
#include "hg_board_rec_read.h"

/* The record reader's kind of a table type. */
static hg_record_kind kind_of(unsigned char type)
{
    return type == HG_BRF_F64 ? HG_REC_F64 : type == HG_BRF_S32 ? HG_REC_S32
           : type == HG_BRF_BIT ? HG_REC_BIT : HG_REC_U32;
}

int hg_board_rec_bind(hg_record *r, const hg_board_rec_field *f, int nf, int *col, hg_record_error *e)
{
    int i;
    for (i = 0; i < nf; i++) {
        col[i] = hg_record_need(r, f[i].name, e);
        if (col[i] < 0)
            return e->code;
        hg_record_set_kind(r, col[i], kind_of(f[i].type));
    }
    return 0;
}

int hg_board_rec_bind_plant(hg_record *r, int plant, int variant, hg_record_error *e)
{
    hg_board_rec_field f[HG_BOARD_REC_MAX];          /* host only: 11 kB on the stack */
    int col[HG_BOARD_REC_MAX];
    int nf = hg_board_rec_fields(f, HG_BOARD_REC_MAX, plant, variant, r->format);
    if (nf < 0) {
        e->code = HG_REC_ERR_HEADER;
        e->line = 0;
        e->column = 0;
        e->field = -1;
        snprintf(e->msg, sizeof e->msg, "no record table for plant %d, model variant %d, format %d: a record "
                 "of another version of the board; read it with that version", plant, variant, r->format);
        return e->code;
    }
    return hg_board_rec_bind(r, f, nf, col, e);
}
