/* fuzz_record.c - the record file reader (src/hg_record.c) on damaged
 * files: raw bytes, or a valid magic line and header followed by rows
 * built from a vocabulary of numbers, near-numbers, NaN, separators,
 * control bytes and cut lines.
 * Properties: no crash, no sanitizer report; every refusal has a known
 * negative code and a message that names its line; every row handed out
 * is finite (but in HG_REC_ANY columns), integral in integer columns, and numbered 0, 1, 2, ... */
#include <stdio.h>
#include <stdlib.h>
#include "fuzz_input.h"
#include "hg_record.h"

static void fail(const char *what)
{
    fprintf(stderr, "fuzz_record: property violated: %s\n", what);
    abort();
}

static const char *const tokens[] = {
    "0", "1", "-1", "2", "0.1", "-3.5e-7", "1e308", "1e309", "-1e999", "4.9e-324", "1e-400",
    "0x1.999999999999ap-4", "0x", "0x1p", "nan", "NaN", "inf", "-inf", "infinity", "1.5.2",
    "+", "-", ".", "e5", "1e", "12abc", " 1", "1 ", "", "4294967295", "4294967296",
    "2147483647", "-2147483648", "-2147483649", "0.5", "3", ",", ",,", "\n", "\r\n", "\t",
    "\x01", "\x7f", "#", "# key value", "sample", "\xff\xfe",
};

/* header used by the structured modes: sample + 4 columns */
#define HEADER HG_RECORD_MAGIC "\n# model reduced-cartesian\n# period-ns 1000000\nsample,a,b,c,d\n"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in = {data, size, 0};
    static char buf[8192];
    static hg_record r;
    hg_record_error e;
    double row[HG_RECORD_MAX_COLS];
    size_t n = 0, k;
    uint8_t mode = fuzz_byte(&in), kinds = fuzz_byte(&in);
    int rc, c;
    long rows = 0;
    if ((mode & 3) != 0) {                  /* a valid start */
        const char *h = (mode & 3) == 1 ? HG_RECORD_MAGIC "\n" : HEADER;
        size_t hl = strlen(h);
        memcpy(buf, h, hl);
        n = hl;
    }
    if ((mode & 3) == 3) {                  /* rows of vocabulary tokens */
        long sample = 0;
        while (in.pos < in.size && n + 64 < sizeof buf) {
            uint8_t t = fuzz_byte(&in);
            if (t < 40) {                   /* a correct sample number starts a row */
                n += (size_t)snprintf(buf + n, sizeof buf - n, "%s%ld", n && buf[n - 1] != '\n' ? "\n" : "", sample++);
            } else if (t < 140) {           /* a field */
                const char *tok = tokens[t % (sizeof tokens / sizeof tokens[0])];
                buf[n++] = ',';
                k = strlen(tok);
                memcpy(buf + n, tok, k);
                n += k;
            } else if (t < 200) {           /* a valid number */
                buf[n++] = ',';
                n += (size_t)snprintf(buf + n, sizeof buf - n, "%d", (int)fuzz_byte(&in) - 128);
            } else {
                buf[n++] = (char)fuzz_byte(&in);
            }
        }
        if (fuzz_byte(&in) & 1)
            buf[n++] = '\n';
    } else {                                /* the rest verbatim */
        k = in.size - in.pos;
        if (k > sizeof buf - n)
            k = sizeof buf - n;
        memcpy(buf + n, in.data + in.pos, k);
        n += k;
    }
    rc = hg_record_open(&r, buf, n, &e);
    if (rc == 0) {
        if (r.ncols < 1 || r.ncols > HG_RECORD_MAX_COLS)
            fail("open accepted a column count out of range");
        for (c = 1; c < r.ncols; c++)
            hg_record_set_kind(&r, c, (hg_record_kind)(((kinds >> (2 * (c % 4))) + (unsigned)c) % 5));
        while ((rc = hg_record_next(&r, row, &e)) == 1) {
            if (row[0] != (double)rows++)
                fail("a row's sample number is not the next one");
            for (c = 0; c < r.ncols; c++) {
                if (!isfinite(row[c]) && r.kind[c] != HG_REC_ANY)
                    fail("a row holds a non-finite value");
                if ((r.kind[c] == HG_REC_S32 || r.kind[c] == HG_REC_U32 || r.kind[c] == HG_REC_BIT) &&
                    row[c] != floor(row[c]))
                    fail("an integer column holds a fraction");
                if (r.kind[c] == HG_REC_BIT && row[c] != 0.0 && row[c] != 1.0)
                    fail("a bit column holds something else than 0 or 1");
            }
        }
    }
    if (rc < 0) {
        if (rc < HG_REC_ERR_COLUMN || rc != e.code)
            fail("unknown error code or code not in the error");
        if (strncmp(e.msg, "line ", 5) != 0 && strncmp(e.msg, "file", 4) != 0)
            fail("the message does not start with its line");
        if (strcmp(hg_record_strerror(rc), "unknown record error") == 0)
            fail("an error code without a name");
        if (strlen(e.msg) < 20)
            fail("a message too short to say what to do");
    }
    return 0;
}
