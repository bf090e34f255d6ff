/* hg_param_table.c - parameter tables, bit sets, rule collectors (hg_param_table.h). */
#include "hg_string.h"
#include "hg_param_table.h"

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
