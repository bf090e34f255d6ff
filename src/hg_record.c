/* hg_record.c - reader of a record file (format in hg_record.h). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include "hg_math.h"
#include "hg_string.h"
#include "hg_record.h"
#include "hg_text.h"

#define NUMBER_MAX 64                 /* longest number field: %.17g and hex floats need < 30 */

/* Printable excerpt of s[0..n) (at most 24 bytes, others as '?'). */
static void excerpt(char *out, size_t size, const char *s, size_t n)
{
    size_t i, k = 0;
    for (i = 0; i < n && k + 4 < size && i < 24; i++)
        out[k++] = (s[i] >= 0x20 && s[i] < 0x7f) ? s[i] : '?';
    if (i < n && k + 4 < size) {
        out[k++] = '.';
        out[k++] = '.';
        out[k++] = '.';
    }
    out[k] = '\0';
}

/* Fill *e: code, position and "line L, column C (field): text". */
static int fail(const hg_record *r, hg_record_error *e, int code, long line, long column,
                int field, const char *text)
{
    char where[160];
    int n;
    if (!e)
        return code;
    e->code = code;
    e->line = line;
    e->column = column;
    e->field = field;
    n = line > 0 ? snprintf(where, sizeof where, "line %ld", line) : snprintf(where, sizeof where, "file");
    if (column > 0 && n > 0 && (size_t)n < sizeof where)
        n += snprintf(where + n, sizeof where - (size_t)n, ", column %ld", column);
    if (field >= 0 && r && field < r->ncols && n > 0 && (size_t)n < sizeof where)
        snprintf(where + n, sizeof where - (size_t)n, " (field %d, %.*s)", field + 1,
                 r->name_len[field], r->name[field]);
    snprintf(e->msg, sizeof e->msg, "%s: %s", where, text);
    return code;
}

/* The next line of the buffer into *s, *n (newline and a '\r' before it
 * excluded): 1, 0 at the end, or an error code. */
static int next_line(hg_record *r, const char **s, size_t *n, hg_record_error *e)
{
    size_t left = r->len - r->pos, scan = left < HG_RECORD_LINE_MAX + 2 ? left : HG_RECORD_LINE_MAX + 2;
    const char *p = r->buf + r->pos;
    const char *nl;
    size_t i, k;
    char text[200];
    if (left == 0)
        return 0;
    nl = memchr(p, '\n', scan);
    r->line++;
    if (!nl) {
        if (left > HG_RECORD_LINE_MAX && memchr(p, '\r', scan))
            return fail(r, e, HG_REC_ERR_LONG_LINE, r->line, 0, -1,
                        "no line ends in a newline, but in a carriage return (CR) alone, as an old Mac "
                        "editor saves: a record's lines end in LF; convert it (tr '\\r' '\\n')");
        if (left > HG_RECORD_LINE_MAX)
            return fail(r, e, HG_REC_ERR_LONG_LINE, r->line, 0, -1,
                        "line longer than 65536 bytes: this is not a record file (rows are a few kB); "
                        "check the file name");
        for (i = 0; i < left; i++)
            if (p[i] == '\0' || ((unsigned char)p[i] < 0x20 && p[i] != '\t' && p[i] != '\r'))
                break;
        if (i < left) {
            snprintf(text, sizeof text, "binary byte 0x%02x: not a text record file; give the file "
                     "tools/hg_record.py wrote", (unsigned char)p[i]);
            return fail(r, e, HG_REC_ERR_BINARY, r->line, (long)i + 1, -1, text);
        }
        return fail(r, e, HG_REC_ERR_TRUNCATED, r->line, (long)left + 1, -1,
                    "the last line has no newline: the recording stopped in the middle of a row; "
                    "delete that line (sed -i '$d' FILE) or record again");
    }
    k = (size_t)(nl - p);
    if (k > HG_RECORD_LINE_MAX)
        return fail(r, e, HG_REC_ERR_LONG_LINE, r->line, 0, -1,
                    "line longer than 65536 bytes: this is not a record file (rows are a few kB); "
                    "check the file name");
    r->pos += k + 1;
    if (k > 0 && p[k - 1] == '\r')
        k--;
    for (i = 0; i < k; i++)
        if (p[i] == '\0' || p[i] == '\r' || ((unsigned char)p[i] < 0x20 && p[i] != '\t') ||
            (unsigned char)p[i] == 0x7f) {
            snprintf(text, sizeof text, "binary byte 0x%02x: not a text record file; give the file "
                     "tools/hg_record.py wrote", (unsigned char)p[i]);
            return fail(r, e, HG_REC_ERR_BINARY, r->line, (long)i + 1, -1, text);
        }
    *s = p;
    *n = k;
    return 1;
}

/* 1 if c may appear in a column name or a metadata key. */
static int name_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c == '-' || c == '_' || c == '.';
}

/* One "# key value" line into r->meta. */
static int parse_meta(hg_record *r, const char *s, size_t n, hg_record_error *e)
{
    size_t i = 2, k0;
    int k;
    hg_record_meta *m;
    if (n < 3 || s[1] != ' ' || !name_char(s[2]))
        return fail(r, e, HG_REC_ERR_META, r->line, 2, -1,
                    "a metadata line is '# key value'; fix or delete this line");
    if (r->nmeta == HG_RECORD_MAX_META)
        return fail(r, e, HG_REC_ERR_META, r->line, 1, -1,
                    "more than 256 metadata lines: not a record file tools/hg_record.py wrote");
    k0 = i;
    while (i < n && name_char(s[i]))
        i++;
    if (i < n && s[i] != ' ')
        return fail(r, e, HG_REC_ERR_META, r->line, (long)i + 1, -1,
                    "a metadata key is letters, digits, '-', '_' or '.', then one space; fix or delete this line");
    for (k = 0; k < r->nmeta; k++)    /* a key once: a second value would be read or ignored silently */
        if ((size_t)r->meta[k].key_len == i - k0 && memcmp(r->meta[k].key, s + k0, i - k0) == 0) {
            char text[240];
            snprintf(text, sizeof text, "the metadata key '%.*s' is given twice (lines %ld and %ld): a record "
                     "holds each once; the file was edited or two were joined: keep the right one",
                     (int)(i - k0 < 64 ? i - k0 : 64), s + k0, r->meta[k].line, r->line);
            return fail(r, e, HG_REC_ERR_META, r->line, (long)k0 + 1, -1, text);
        }
    m = &r->meta[r->nmeta++];
    m->key = s + k0;
    m->key_len = (int)(i - k0);
    m->value = i < n ? s + i + 1 : s + n;
    m->value_len = i < n ? (int)(n - i - 1) : 0;
    m->line = r->line;
    return 0;
}

/* The header line: column names. */
static int parse_header(hg_record *r, const char *s, size_t n, hg_record_error *e)
{
    size_t i = 0;
    char text[200], ex[40];
    r->ncols = 0;
    while (1) {
        size_t k0 = i;
        int c;
        while (i < n && s[i] != ',')
            i++;
        if (r->ncols == HG_RECORD_MAX_COLS)
            return fail(r, e, HG_REC_ERR_HEADER, r->line, (long)k0 + 1, -1,
                        "more than 256 columns: not a record file tools/hg_record.py wrote");
        if (i == k0 || i - k0 > HG_RECORD_NAME_MAX) {
            snprintf(text, sizeof text, "column %d has %s name: the header line names every column "
                     "(sample,name,...); restore the header line", r->ncols + 1,
                     i == k0 ? "an empty" : "a too long");
            return fail(r, e, HG_REC_ERR_HEADER, r->line, (long)k0 + 1, -1, text);
        }
        for (c = 0; c < (int)(i - k0); c++)
            if (!name_char(s[k0 + (size_t)c])) {
                excerpt(ex, sizeof ex, s + k0, i - k0);
                snprintf(text, sizeof text, "column name '%s' has a character other than letters, "
                         "digits, '-', '_', '.': this is not the header line; restore it", ex);
                return fail(r, e, HG_REC_ERR_HEADER, r->line, (long)k0 + 1 + c, -1, text);
            }
        for (c = 0; c < r->ncols; c++)
            if (r->name_len[c] == (int)(i - k0) && memcmp(r->name[c], s + k0, i - k0) == 0) {
                excerpt(ex, sizeof ex, s + k0, i - k0);
                snprintf(text, sizeof text, "column '%s' appears twice (columns %d and %d); "
                         "delete one of them", ex, c + 1, r->ncols + 1);
                return fail(r, e, HG_REC_ERR_HEADER, r->line, (long)k0 + 1, -1, text);
            }
        r->name[r->ncols] = s + k0;
        r->name_len[r->ncols] = (int)(i - k0);
        r->kind[r->ncols] = HG_REC_F64;
        r->ncols++;
        if (i == n)
            break;
        i++;
    }
    if (r->name_len[0] != 6 || memcmp(r->name[0], "sample", 6) != 0)
        return fail(r, e, HG_REC_ERR_HEADER, r->line, 1, -1,
                    "the first column must be 'sample' (the servo period number); restore the header line");
    r->kind[0] = HG_REC_U32;
    return 0;
}

/* The footer: the "# key value" lines after the last row (what the recorder
 * knew only at the end), into r->meta; the rows then end where it starts.
 * Blank lines at the very end (an editor's) carry nothing and are dropped. */
static int parse_footer(hg_record *r, hg_record_error *e)
{
    size_t start, end = r->len, i;
    long line = r->line, save_pos = (long)r->pos, save_line = r->line;
    const char *s = 0;
    size_t n = 0;
    int rc;
    if (end == r->pos || r->buf[end - 1] != '\n')
        return 0;                     /* no footer; a cut last line is reported with the rows */
    while (end - r->pos >= 2 && (r->buf[end - 2] == '\n' ||
                                 (r->buf[end - 2] == '\r' && end - r->pos >= 3 && r->buf[end - 3] == '\n')))
        end -= r->buf[end - 2] == '\n' ? 1 : 2;   /* a trailing "\n" or "\r\n" line */
    r->len = end;
    start = end;
    while (start > r->pos) {          /* back over the trailing '#' lines */
        size_t b = start - 1;         /* the '\n' ending the line before `start` */
        while (b > r->pos && r->buf[b - 1] != '\n')
            b--;
        if (r->buf[b] != '#')
            break;
        start = b;
    }
    if (start == end)
        return 0;
    for (i = r->pos; i < start; i++)  /* its line number */
        if (r->buf[i] == '\n')
            line++;
    r->pos = start;
    r->line = line;
    while ((rc = next_line(r, &s, &n, e)) == 1) {
        rc = parse_meta(r, s, n, e);
        if (rc)
            return rc;
    }
    if (rc < 0)
        return rc;
    r->pos = (size_t)save_pos;
    r->line = save_line;
    r->len = start;
    return 0;
}

int hg_record_open(hg_record *r, const char *buf, size_t len, hg_record_error *e)
{
    const char *s = 0;
    size_t n = 0;
    int rc;
    memset(r, 0, sizeof *r);
    r->buf = buf;
    r->len = buf ? len : 0;
    if (e) {
        e->code = 0;
        e->msg[0] = '\0';
    }
    if (r->len == 0)
        return fail(r, e, HG_REC_ERR_EMPTY, 0, 0, -1,
                    "the file is empty: the recorder wrote nothing; check that tools/hg_record.py ran "
                    "(docs/replay.md)");
    rc = next_line(r, &s, &n, e);
    if (rc < 0)
        return rc;
    if (n >= 3 && memcmp(s, "\xef\xbb\xbf", 3) == 0)
        return fail(r, e, HG_REC_ERR_MAGIC, 1, 1, -1,
                    "the file starts with a UTF-8 byte-order mark (an editor added it before the magic line): "
                    "remove it (sed -i '1s/^\\xEF\\xBB\\xBF//' FILE)");
    /* "# hexaglide-record N", N one of the formats this reader knows */
    if (n != sizeof HG_RECORD_MAGIC - 1 || memcmp(s, HG_RECORD_MAGIC, n - 1) != 0 || s[n - 1] < '1' ||
        s[n - 1] > '0' + HG_RECORD_FORMAT_MAX)
        return fail(r, e, HG_REC_ERR_MAGIC, 1, 1, -1,
                    "line 1 is not '" HG_RECORD_MAGIC "' (or an earlier format): not a record file, or "
                    "one of a newer recorder (make one with tools/hg_record.py, docs/replay.md)");
    r->format = s[n - 1] - '0';
    while (1) {
        rc = next_line(r, &s, &n, e);
        if (rc < 0)
            return rc;
        if (rc == 0)
            return fail(r, e, HG_REC_ERR_HEADER, r->line + 1, 0, -1,
                        "no header line (sample,name,...) after the metadata: the file was cut short; "
                        "record again");
        if (n > 0 && s[0] == '#') {
            rc = parse_meta(r, s, n, e);
            if (rc)
                return rc;
            continue;
        }
        rc = parse_header(r, s, n, e);
        return rc ? rc : parse_footer(r, e);
    }
}

int hg_record_column(const hg_record *r, const char *name)
{
    size_t n = strlen(name);
    int c;
    for (c = 0; c < r->ncols; c++)
        if ((size_t)r->name_len[c] == n && memcmp(r->name[c], name, n) == 0)
            return c;
    return -1;
}

int hg_record_need(const hg_record *r, const char *name, hg_record_error *e)
{
    char text[200];
    int c = hg_record_column(r, name);
    if (c >= 0)
        return c;
    snprintf(text, sizeof text, "no column '%.63s': the recording lacks a pin this replay needs; "
             "record with tools/hg_record.py from the same version of the board", name);
    fail(r, e, HG_REC_ERR_COLUMN, r->line, 0, -1, text);
    return -1;
}

void hg_record_set_kind(hg_record *r, int col, hg_record_kind kind)
{
    if (col > 0 && col < r->ncols && col < HG_RECORD_MAX_COLS)
        r->kind[col] = kind;
}

int hg_record_meta_get(const hg_record *r, const char *key, char *out, size_t size)
{
    size_t n = strlen(key);
    int i;
    for (i = 0; i < r->nmeta; i++)
        if ((size_t)r->meta[i].key_len == n && memcmp(r->meta[i].key, key, n) == 0) {
            size_t k = (size_t)r->meta[i].value_len;
            if (size == 0)
                return 1;
            if (k > size - 1)
                k = size - 1;
            memcpy(out, r->meta[i].value, k);
            out[k] = '\0';
            return 1;
        }
    return 0;
}

/* 1 if c may appear in a decimal number (hg_text_is_decimal: no hex float). */
static int number_char(char c)
{
    return (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.' || c == 'e' || c == 'E';
}

/* Field s[0..n) as a finite double of the column's kind into *v. */
static int parse_number(hg_record *r, const char *s, size_t n, long column, int field, double *v,
                        hg_record_error *e)
{
    char tmp[NUMBER_MAX + 1], ex[40], text[240], *end = 0;
    size_t i;
    double x;
    if (n == 0)
        return fail(r, e, HG_REC_ERR_NUMBER, r->line, column, field,
                    "empty field: every field is a number; the row is damaged, record again");
    excerpt(ex, sizeof ex, s, n);
    if (r->kind[field] == HG_REC_ANY &&
        ((n == 3 && (memcmp(s, "nan", 3) == 0 || memcmp(s, "inf", 3) == 0)) ||
         (n == 4 && (memcmp(s, "-nan", 4) == 0 || memcmp(s, "-inf", 4) == 0)))) {
        *v = s[n - 1] == 'n' ? (double)NAN : s[0] == '-' ? -(double)INFINITY : (double)INFINITY;
        return 0;
    }
    for (i = 0; i < n; i++)
        if (!number_char(s[i]))
            break;
    if (n > NUMBER_MAX || i < n) {
        snprintf(text, sizeof text, "'%s' is not a number%s; the row is damaged, record again "
                 "(or fix this field)", ex,
                 (i < n && (s[i] == 'n' || s[i] == 'N' || s[i] == 'i' || s[i] == 'I'))
                     ? " (NaN and inf are refused: a recorded pin was not finite)" : "");
        return fail(r, e, HG_REC_ERR_NUMBER, r->line, column + (long)(i < n ? i : 0), field, text);
    }
    memcpy(tmp, s, n);
    tmp[n] = '\0';
    errno = 0;
    x = strtod(tmp, &end);
    if (end != tmp + n || !hg_text_is_decimal(tmp, n)) {   /* (the tools' one syntax: hg_text.h) */
        snprintf(text, sizeof text, "'%s' is not a number; the row is damaged, record again "
                 "(or fix this field)", ex);
        return fail(r, e, HG_REC_ERR_NUMBER, r->line, column + (long)(end - tmp), field, text);
    }
    if ((!isfinite(x) || (errno == ERANGE && fabs(x) > 1.0)) && r->kind[field] != HG_REC_ANY) {
        snprintf(text, sizeof text, "'%s' is out of the range of a double; the row is damaged, "
                 "record again", ex);
        return fail(r, e, HG_REC_ERR_NUMBER, r->line, column, field, text);
    }
    switch (r->kind[field]) {
    case HG_REC_S32:
        if (x != floor(x) || x < -2147483648.0 || x > 2147483647.0) {
            snprintf(text, sizeof text, "'%s' is not an s32 integer; this column holds a signed "
                     "32-bit pin: the row is damaged, record again", ex);
            return fail(r, e, HG_REC_ERR_KIND, r->line, column, field, text);
        }
        break;
    case HG_REC_U32:
        if (x != floor(x) || x < 0.0 || x > 4294967295.0) {
            snprintf(text, sizeof text, "'%s' is not a u32 integer; this column holds an unsigned "
                     "32-bit pin: the row is damaged, record again", ex);
            return fail(r, e, HG_REC_ERR_KIND, r->line, column, field, text);
        }
        break;
    case HG_REC_BIT:
        if (x != 0.0 && x != 1.0) {
            snprintf(text, sizeof text, "'%s' is not 0 or 1; this column holds a bit pin: the row "
                     "is damaged, record again", ex);
            return fail(r, e, HG_REC_ERR_KIND, r->line, column, field, text);
        }
        break;
    default:
        break;
    }
    *v = x;
    return 0;
}

int hg_record_next(hg_record *r, double *row, hg_record_error *e)
{
    const char *s = 0;
    size_t n = 0, i = 0;
    int rc, field = 0;
    char text[200];
    rc = next_line(r, &s, &n, e);
    if (rc <= 0)
        return rc;
    if (n == 0)
        return fail(r, e, HG_REC_ERR_FIELDS, r->line, 1, -1,
                    "empty line: every line after the header is one row; delete it");
    while (1) {
        size_t k0 = i;
        while (i < n && s[i] != ',')
            i++;
        if (field == r->ncols) {
            snprintf(text, sizeof text, "more than the header's %d fields: the row does not match "
                     "the header (recorded by another version?); record again", r->ncols);
            return fail(r, e, HG_REC_ERR_FIELDS, r->line, (long)k0 + 1, -1, text);
        }
        rc = parse_number(r, s + k0, i - k0, (long)k0 + 1, field, &row[field], e);
        if (rc)
            return rc;
        field++;
        if (i == n)
            break;
        i++;
    }
    if (field < r->ncols) {
        snprintf(text, sizeof text, "%d fields, the header has %d: the row is cut short or does "
                 "not match the header; record again", field, r->ncols);
        return fail(r, e, HG_REC_ERR_FIELDS, r->line, (long)n + 1, field, text);
    }
    if (row[0] != (double)r->rows) {
        if (row[0] < (double)r->rows)   /* back in time: rows repeated or out of order, not lost */
            snprintf(text, sizeof text, "sample %.0f where %ld was due: the samples go back (rows "
                     "repeated or out of order: records joined or edited?); record again", row[0], r->rows);
        else
            snprintf(text, sizeof text, "sample %.0f where %ld was due: periods are missing (the "
                     "sampler FIFO overran?); record again with a deeper FIFO (docs/replay.md)",
                     row[0], r->rows);
        return fail(r, e, HG_REC_ERR_SAMPLE, r->line, 1, 0, text);
    }
    r->rows++;
    return 1;
}

const char *hg_record_strerror(int code)
{
    switch (code) {
    case HG_REC_OK: return "ok";
    case HG_REC_ERR_EMPTY: return "empty file";
    case HG_REC_ERR_MAGIC: return "not a record file";
    case HG_REC_ERR_BINARY: return "binary data";
    case HG_REC_ERR_LONG_LINE: return "line too long";
    case HG_REC_ERR_TRUNCATED: return "truncated";
    case HG_REC_ERR_HEADER: return "bad header";
    case HG_REC_ERR_FIELDS: return "wrong number of fields";
    case HG_REC_ERR_NUMBER: return "not a number";
    case HG_REC_ERR_KIND: return "out of the column's range";
    case HG_REC_ERR_SAMPLE: return "samples missing";
    case HG_REC_ERR_META: return "bad metadata line";
    case HG_REC_ERR_COLUMN: return "column missing";
    default: return "unknown record error";
    }
}
