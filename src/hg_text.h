/* hg_text.h - numbers and sentences as text without stdio (realtime code:
 * rtapi_print_msg formats no floats in kernel builds), for the messages the
 * core composes (hg_guard_describe) and the HAL glue prints. Pure C. */
#ifndef HG_TEXT_H
#define HG_TEXT_H

/* v as text with 9 significant digits, trailing zeros dropped (a refused
 * 0.0009999 against a bound of 0.001 must not read "0.001"): "-12.5",
 * "0.00012345"; below 1e-4 and above 1e15 in magnitude "1.5e-9", "1e+300";
 * "nan", "inf". */
#define HG_TEXT_VALUE_LEN 32
void hg_text_value(char buf[HG_TEXT_VALUE_LEN], double v);

/* Append the string s to buf (capacity len, NUL-terminated), truncating;
 * returns buf. */
char *hg_text_add(char *buf, unsigned long len, const char *s);

/* Append v as hg_text_value writes it; returns buf. */
char *hg_text_add_value(char *buf, unsigned long len, double v);

/* Append s with every '_' written '-': the core's reasons name parameters
 * by their C names (k_axial), which the HAL glue prints as the HAL names
 * (k-axial: every parameter's HAL name is its C name so written); returns buf. */
char *hg_text_add_hal_names(char *buf, unsigned long len, const char *s);

/* 1 if s[0..n) is a decimal number as every tool of the project reads one (the C
 * options, INI values and records, tools/hg_csv.py's number()): a sign, ASCII digits
 * with at most one '.', an exponent e[+-]digits; nothing else, no spaces. C99's
 * hexadecimal floats ("0x1p3", which strtod takes) and the words nan, inf, infinity
 * are not decimal numbers (hg_text_is_nonfinite_word: which callers say are not finite). */
int hg_text_is_decimal(const char *s, unsigned long n);

/* 1 if s[0..n) is word (given in lower case) in any case. */
int hg_text_is_word(const char *s, unsigned long n, const char *word);

/* 1 if s[0..n) is [+-]nan, inf or infinity in any case (Python's float() takes them). */
int hg_text_is_nonfinite_word(const char *s, unsigned long n);

#endif
