/* hg_record.h - reader of a record file: one LinuxCNC run of the virtual
 * board, one row per servo period (docs/replay.md, tools/hg_record.py).
 *
 * Format (text, lines end in '\n', "\r\n" accepted):
 *   # hexaglide-record 2            magic, line 1: the format (1, written by
 *                                   d20d9e5 and before, is read too; the
 *                                   columns of each: hg_board_rec.h)
 *   # key value                     metadata (model, period-ns, board, ...)
 *   sample,name1,name2,...          header: column names, comma-separated
 *   0,1.5,-3,...                    one row per servo period, sample 0, 1, 2...
 *   # key value                     footer: metadata known only at the end
 *                                   (the pid settings polled over the run)
 * Numbers are C/Python float syntax (decimal or hexadecimal, e.g. repr()
 * or %.17g output): they round-trip every double exactly. NaN, inf (except
 * in HG_REC_ANY columns: "nan", "inf", "-inf"),
 * missing or extra fields, gaps in the sample column, a line without its
 * newline (an interrupted recording) and binary data are errors.
 *
 * The reader works on the whole file in memory (no malloc, no stdio): the
 * caller keeps the buffer alive while the reader is used. Every error
 * names the line, the byte column and the field, says what is wrong and
 * what to do (hg_record_error.msg). Host code: not built into the
 * realtime modules (it uses strtod and snprintf). */
#ifndef HG_RECORD_H
#define HG_RECORD_H

#include <stddef.h>

#define HG_RECORD_MAGIC "# hexaglide-record 2"   /* what the recorder writes */
#define HG_RECORD_FORMAT_MAX 2                     /* the newest format read */
#define HG_RECORD_MAX_COLS 256        /* columns per row, sample included */
#define HG_RECORD_NAME_MAX 63         /* characters of a column name */
#define HG_RECORD_LINE_MAX 65536      /* bytes of one line, newline excluded */
#define HG_RECORD_MAX_META 256        /* "# key value" lines, header and footer */

/* What a column holds: checked on every row. */
typedef enum {
    HG_REC_F64 = 0,                   /* any finite double (the default) */
    HG_REC_S32 = 1,                   /* integer in [-2^31, 2^31) */
    HG_REC_U32 = 2,                   /* integer in [0, 2^32) */
    HG_REC_BIT = 3,                   /* 0 or 1 */
    HG_REC_ANY = 4                    /* a double, or nan, inf, -inf (raw inputs as HAL held them) */
} hg_record_kind;

/* Error codes (negative, distinct). */
enum {
    HG_REC_OK = 0,
    HG_REC_ERR_EMPTY = -1,            /* no bytes at all */
    HG_REC_ERR_MAGIC = -2,            /* line 1 is not HG_RECORD_MAGIC */
    HG_REC_ERR_BINARY = -3,           /* a NUL or other control byte */
    HG_REC_ERR_LONG_LINE = -4,        /* a line longer than HG_RECORD_LINE_MAX */
    HG_REC_ERR_TRUNCATED = -5,        /* the last line has no newline */
    HG_REC_ERR_HEADER = -6,           /* bad, duplicate or missing column name */
    HG_REC_ERR_FIELDS = -7,           /* too few or too many fields in a row */
    HG_REC_ERR_NUMBER = -8,           /* a field is not a finite number */
    HG_REC_ERR_KIND = -9,             /* not an integer in the column's range */
    HG_REC_ERR_SAMPLE = -10,          /* sample column not 0, 1, 2, ... */
    HG_REC_ERR_META = -11,            /* bad "# key value" line */
    HG_REC_ERR_COLUMN = -12           /* a column the caller needs is missing */
};

/* Where and why reading failed. */
typedef struct {
    int code;                         /* HG_REC_ERR_* */
    long line;                        /* 1-based line number, 0 if none */
    long column;                      /* 1-based byte column in that line, 0 if none */
    int field;                        /* 0-based field index, -1 if none */
    char msg[320];                    /* "line L, column C (name): what; what to do" */
} hg_record_error;

/* A "# key value" metadata line (pointers into the buffer). */
typedef struct {
    const char *key, *value;
    int key_len, value_len;
    long line;                        /* its line in the file */
} hg_record_meta;

/* The reader: buffer, header and position. */
typedef struct {
    const char *buf;                  /* the whole file (not owned) */
    int format;                       /* the magic line's format number (1 or 2) */
    size_t len, pos;                  /* its length, the next byte to read */
    long line;                        /* lines consumed so far */
    long rows;                        /* data rows read so far */
    int ncols;                        /* columns in the header, sample included */
    const char *name[HG_RECORD_MAX_COLS]; /* column names (pointers into buf) */
    int name_len[HG_RECORD_MAX_COLS];
    hg_record_kind kind[HG_RECORD_MAX_COLS];
    hg_record_meta meta[HG_RECORD_MAX_META];
    int nmeta;
} hg_record;

/* Start reading buf[0..len): magic, metadata, header and the footer's
 * metadata (the "# " lines after the last row; then hg_record_next stops
 * before them). 0, or an
 * HG_REC_ERR_* code with *e filled. Every column starts as HG_REC_F64,
 * except column 0 which must be called "sample" (HG_REC_U32). */
int hg_record_open(hg_record *r, const char *buf, size_t len, hg_record_error *e);

/* Index of the column called name, or -1. */
int hg_record_column(const hg_record *r, const char *name);

/* Index of column name, or -1 with *e filled (HG_REC_ERR_COLUMN: the file
 * lacks a column this replay needs). */
int hg_record_need(const hg_record *r, const char *name, hg_record_error *e);

/* Check column col as kind on every following row. */
void hg_record_set_kind(hg_record *r, int col, hg_record_kind kind);

/* Value of metadata key into out (NUL-terminated, at most size-1 bytes):
 * 1 if found, 0 if not. */
int hg_record_meta_get(const hg_record *r, const char *key, char *out, size_t size);

/* Read the next row into row[0..ncols): 1 on a row, 0 at the end of the
 * file, or an HG_REC_ERR_* code with *e filled. row[0] is the sample. */
int hg_record_next(hg_record *r, double *row, hg_record_error *e);

/* Short name of a code ("truncated", "not a number", ...). */
const char *hg_record_strerror(int code);

#endif
