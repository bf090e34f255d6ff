/* hg_text.c - numbers and sentences as text without stdio (hg_text.h). */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_text.h"

/* Append the decimal digits of u (no sign) at p; returns the new end. */
static char *put_uint(char *p, unsigned long long u, int min_digits)
{
    char tmp[24];
    int n = 0;
    do {
        tmp[n++] = (char)('0' + (int)(u % 10u));
        u /= 10u;
    } while (u && n < 20);
    while (n < min_digits && n < 20)
        tmp[n++] = '0';
    while (n)
        *p++ = tmp[--n];
    return p;
}

/* v > 0 finite as "1.23456789e-9" (9 significant digits, trailing zeros dropped)
 * at p, NUL-terminated. */
static void put_scientific(char *p, double v)
{
    unsigned long long ip, frac;
    int e = 0;
    while (v >= 10.0 && e < 400)      /* at most 308 and 324 steps */
        v /= 10.0, e++;
    while (v < 1.0 && e > -400)
        v *= 10.0, e--;
    ip = (unsigned long long)floor(v);
    frac = (unsigned long long)floor((v - (double)ip) * 1e8 + 0.5);
    if (frac >= 100000000ull)
        ip++, frac -= 100000000ull;
    if (ip >= 10ull)                  /* 9.9999999996 rounded up to 10 */
        ip = 1, e++;
    p = put_uint(p, ip, 1);
    if (frac) {
        *p++ = '.';
        p = put_uint(p, frac, 8);
        while (p[-1] == '0')
            p--;
    }
    *p++ = 'e';
    *p++ = e < 0 ? '-' : '+';
    p = put_uint(p, (unsigned long long)(e < 0 ? -e : e), 1);
    *p = '\0';
}

void hg_text_value(char buf[HG_TEXT_VALUE_LEN], double v)
{
    char *p = buf;
    unsigned long long ip, frac;
    double a, scale, t;
    int d;
    if (v != v) {
        memcpy(buf, "nan", 4);
        return;
    }
    if (v < 0 || (v == 0 && 1 / v < 0)) {
        *p++ = '-';
        v = -v;
    }
    if (v > 1.7976931348623157e308) {
        memcpy(p, "inf", 4);
        return;
    }
    if (v > 1e15 || (v > 0 && v < 1e-4)) {
        put_scientific(p, v);
        return;
    }
    a = floor(v);
    ip = (unsigned long long)a;
    for (d = 8, scale = 1e8, t = v; t >= 10.0 && d > 0; t /= 10.0) /* decimals for 9 significant digits */
        d--, scale /= 10.0;
    for (; t < 1.0 && v > 0 && d < 12; t *= 10.0)                   /* (v >= 1e-4: at most 12) */
        d++, scale *= 10.0;
    frac = (unsigned long long)floor((v - a) * scale + 0.5);
    if (frac >= (unsigned long long)scale) {
        ip++;
        frac -= (unsigned long long)scale;
    }
    p = put_uint(p, ip, 1);
    if (frac) {
        *p++ = '.';
        p = put_uint(p, frac, d);
        while (p[-1] == '0')          /* 1.500000 -> 1.5 */
            p--;
    }
    *p = '\0';
}

/* Append s to buf (capacity len), every character from written as to. */
static char *add_replacing(char *buf, unsigned long len, const char *s, char from, char to)
{
    unsigned long n = 0;
    while (n < len && buf[n])
        n++;
    for (; *s && n + 1 < len; s++)
        buf[n++] = *s == from ? to : *s;
    if (n < len)
        buf[n] = '\0';
    return buf;
}

char *hg_text_add(char *buf, unsigned long len, const char *s)
{
    return add_replacing(buf, len, s, '\0', '\0');
}

char *hg_text_add_hal_names(char *buf, unsigned long len, const char *s)
{
    return add_replacing(buf, len, s, '_', '-');
}

char *hg_text_add_value(char *buf, unsigned long len, double v)
{
    char t[HG_TEXT_VALUE_LEN];
    hg_text_value(t, v);
    return hg_text_add(buf, len, t);
}

int hg_text_is_decimal(const char *s, unsigned long n)
{
    unsigned long i = 0, digits = 0;
    if (i < n && (s[i] == '+' || s[i] == '-'))
        i++;
    for (; i < n && s[i] >= '0' && s[i] <= '9'; i++)
        digits++;
    if (i < n && s[i] == '.')
        for (i++; i < n && s[i] >= '0' && s[i] <= '9'; i++)
            digits++;
    if (!digits)
        return 0;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        unsigned long e0;
        i++;
        if (i < n && (s[i] == '+' || s[i] == '-'))
            i++;
        for (e0 = i; i < n && s[i] >= '0' && s[i] <= '9'; i++)
            ;
        if (i == e0)
            return 0;
    }
    return i == n;
}

int hg_text_is_word(const char *s, unsigned long n, const char *word)
{
    unsigned long i;
    for (i = 0; i < n && word[i]; i++)
        if ((s[i] | 0x20) != word[i])
            return 0;
    return i == n && !word[i];
}

int hg_text_is_nonfinite_word(const char *s, unsigned long n)
{
    if (n && (s[0] == '+' || s[0] == '-'))
        s++, n--;
    return hg_text_is_word(s, n, "nan") || hg_text_is_word(s, n, "inf") || hg_text_is_word(s, n, "infinity");
}
