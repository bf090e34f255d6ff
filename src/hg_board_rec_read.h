/* hg_board_rec_read.h - a board record opened for reading: every column of
 * the board's record table (hg_board_rec_fields) needed and checked as the
 * type its pin has (an s32 count, a u32 word, a bit), so that a damaged
 * row is refused by whoever reads it: `hexaglide replay`, and identify's
 * readers (tools/hg_identify_base.py) through the Python binding. Host
 * only: it reads hg_record (strtod, snprintf). */
#ifndef HG_BOARD_REC_READ_H
#define HG_BOARD_REC_READ_H

#include "hg_board_rec.h"
#include "hg_record.h"

/* Need every column of table f[0..nf) in r (col[i] its index) and check
 * each as its type on every following row: 0, or HG_REC_ERR_COLUMN with
 * *e naming the first missing column. */
int hg_board_rec_bind(hg_record *r, const hg_board_rec_field *f, int nf, int *col, hg_record_error *e);

/* The same for the table of r's format, plant (registry index) and model
 * variant, for a reader that keeps no table of its own: 0, or an
 * HG_REC_ERR_* code with *e filled (HG_REC_ERR_HEADER: a plant, variant or
 * format this program has no table for). */
int hg_board_rec_bind_plant(hg_record *r, int plant, int variant, hg_record_error *e);

#endif
