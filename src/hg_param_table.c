/* hg_param_table.c - parameter tables, bit sets, rule collectors (hg_param_table.h). */
#include "hg_string.h"
#include "hg_param_table.h"
#include "hg_text.h"

const char hg_why_max_abs[] = "must be finite and below 1e9 in magnitude (SI units)";
const char hg_why_min_positive[] = "must be positive (at least 1e-9 in SI units)";

void hg_bitset_clear(hg_bitset *s)
{
    memset(s, 0, sizeof *s);
}

void hg_bitset_set(hg_bitset *s, int i)
{
    if (i >= 0 && i < HG_BITSET_BITS)
        s->w[i / 64] |= 1ull << (i % 64);
}

int hg_bitset_has(const hg_bitset *s, int i)
{
    return i >= 0 && i < HG_BITSET_BITS && ((s->w[i / 64] >> (i % 64)) & 1u);
}

int hg_bitset_empty(const hg_bitset *s)
{
    unsigned k;
    for (k = 0; k < sizeof s->w / sizeof s->w[0]; k++)
        if (s->w[k])
            return 0;
    return 1;
}

int hg_param_find(const hg_param_info *t, int n, const char *name)
{
    int i;
    for (i = 0; name && i < n; i++)
        if (strcmp(t[i].name, name) == 0)
            return i;
    return -1;
}

void hg_check_init(hg_check *c, const hg_param_info *t, int n, const char **why)
{
    int i;
    c->t = t;
    c->n = n;
    c->first_field = c->first_why = 0;
    hg_bitset_clear(&c->bad);
    c->why = why;
    for (i = 0; why && i < n; i++)
        why[i] = 0;
}

void hg_check_refuse(hg_check *c, const char *field, const char *reason)
{
    int i = hg_param_find(c->t, c->n, field);
    if (!c->first_field) {
        c->first_field = field;
        c->first_why = reason;
    }
    if (i >= 0 && !hg_bitset_has(&c->bad, i)) {
        hg_bitset_set(&c->bad, i);
        if (c->why)
            c->why[i] = reason;
    }
}

int hg_check_failed(const hg_check *c, const char *field)
{
    return hg_bitset_has(&c->bad, hg_param_find(c->t, c->n, field));
}

int hg_check_any(const hg_check *c)
{
    return c->first_field != 0;
}

int hg_param_same(double a, double b)
{
    return a == b || (a != a && b != b);
}

char *hg_param_hal_reason(char *buf, unsigned long len, const char *why, const hg_param_info *e)
{
    double bound = why == hg_why_max_abs ? HG_PARAM_MAX_ABS : why == hg_why_min_positive ? HG_PARAM_MIN_POSITIVE : 0.0;
    unsigned long n;
    hg_text_add_hal_names(buf, len, why);
    if (bound == 0.0 || !e || strcmp(e->unit, e->hal_unit) == 0)
        return buf;
    n = strlen(buf);
    if (n == 0 || buf[n - 1] != ')')
        return buf;                    /* cut short: nothing to add inside the parentheses */
    buf[n - 1] = '\0';
    hg_text_add(buf, len, "; ");
    hg_text_add_value(buf, len, bound * e->hal_scale);
    hg_text_add(buf, len, " ");
    hg_text_add(buf, len, e->hal_unit);
    return hg_text_add(buf, len, " here)");
}
