/* hg_param_table.h - parameter tables, knowing no machine: one entry per
 * parameter (spec name, SI unit, description, HAL name, HAL unit and
 * scale, INI key), lookup by name, bit sets over table entries, and a
 * collector of failed validation rules that names every invalid field.
 * A plant (hg_plant.h) owns one table and the rules of its parameters.
 * Pure C, no malloc, no stdio. */
#ifndef HG_PARAM_TABLE_H
#define HG_PARAM_TABLE_H

/* One entry of a parameter table. */
typedef struct {
    const char *name;      /* spec name, e.g. "m_head" */
    const char *unit;      /* SI unit, e.g. "kg" */
    const char *what;      /* one-line description */
    unsigned long offset;  /* offsetof(the plant's parameter struct, field) */
    const char *hal_name;  /* HAL parameter name: the spec name with _ -> -, e.g. "m-head" */
    const char *hal_unit;  /* unit on HAL: mm for lengths (LinuxCNC machine units), deg for
                              angles, else the SI unit */
    double hal_scale;      /* HAL value = SI value * hal_scale (1000 for lengths, 180/pi for
                              angles, else 1) */
    const char *ini_key;   /* key of the plant's INI section (value in the HAL unit), or 0:
                              set it by setp */
} hg_param_info;

/* A set of table entries (bit i = entry i), room for every parameter of a
 * plant plus a few of the board's own (hg_board.h). */
#define HG_BITSET_BITS 320
typedef struct {
    unsigned long long w[HG_BITSET_BITS / 64];
} hg_bitset;

/* Empty the set. */
void hg_bitset_clear(hg_bitset *s);

/* Add bit i (ignored outside 0..HG_BITSET_BITS-1). */
void hg_bitset_set(hg_bitset *s, int i);

/* 1 if bit i is in the set. */
int hg_bitset_has(const hg_bitset *s, int i);

/* 1 if the set is empty. */
int hg_bitset_empty(const hg_bitset *s);

/* Index of the entry called name in t[0..n), or -1. */
int hg_param_find(const hg_param_info *t, int n, const char *name);

/* A collector of failed rules over table t[0..n): the first (field,
 * reason) and every failed entry's bit and reason (the first per entry). */
typedef struct {
    const hg_param_info *t;
    int n;
    const char *first_field, *first_why;
    hg_bitset bad;
    const char **why;      /* n entries, or 0 */
} hg_check;

/* Start collecting over t[0..n); why (n entries, may be 0) is cleared. */
void hg_check_init(hg_check *c, const hg_param_info *t, int n, const char **why);

/* Record that field (a spec name of the table) failed for reason. */
void hg_check_refuse(hg_check *c, const char *field, const char *reason);

/* 1 if field has failed a rule already (rules that depend on it are skipped). */
int hg_check_failed(const hg_check *c, const char *field);

/* 1 if any rule failed. */
int hg_check_any(const hg_check *c);

/* The bounds every plant's rules put on every parameter (SI): no machine
 * needs a number this large (beyond it products overflow), nor a positive
 * one this small (1/x would overflow); and their reasons, one text each, so
 * that a printer knows them (hg_param_hal_reason). */
#define HG_PARAM_MAX_ABS 1e9
#define HG_PARAM_MIN_POSITIVE 1e-9
extern const char hg_why_max_abs[];      /* "must be finite and below 1e9 in magnitude (SI units)" */
extern const char hg_why_min_positive[]; /* "must be positive (at least 1e-9 in SI units)" */

/* 1 when b is the parameter value a again: equal (-0 is 0) or both NaN
 * (a NaN kept is no change). */
int hg_param_same(double a, double b);

/* Append why as the HAL face says it: parameter names in HAL spelling
 * (hg_text_add_hal_names), and for the two shared bounds of an entry e (may
 * be 0) whose HAL unit is not its SI unit, the bound in the HAL unit too
 * ("...(SI units; 1000000000000 mm here)"); returns buf. */
char *hg_param_hal_reason(char *buf, unsigned long len, const char *why, const hg_param_info *e);

#endif
