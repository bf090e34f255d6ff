/* fuzz_params.c - the parameter set by name: random names (table names,
 * near misses, garbage) and extreme values, then validation and model
 * building, and the board's all-fields check. Properties: no crash; a
 * refusal names a real field and a reason; hg_params_check_all flags the
 * field hg_params_check names, gives every flagged field a reason and
 * flags nothing for a valid set; a set that passes validation builds a
 * model. */
#include <stdio.h>
#include <stdlib.h>
#include "fuzz_input.h"
#include "hg_dynamics.h"
#include "hg_errors.h"

static void fail(const char *what)
{
    fprintf(stderr, "fuzz_params: property violated: %s\n", what);
    abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in = {data, size, 0};
    static hg_model m;
    hg_params p;
    const hg_param_info *t;
    const char *field = 0, *why = 0;
    int n, i, rc, count = fuzz_byte(&in) % 8;
    t = hg_params_table(&n);
    hg_params_default(&p);
    for (i = 0; i < count; i++) {
        uint8_t sel = fuzz_byte(&in);
        char name[24];
        double v, scale;
        if (sel < 200) {
            int f = sel % n;
            double *cur = hg_params_field(&p, t[f].name);
            scale = fuzz_double(&in, -2.0, 3.0);
            v = (fuzz_byte(&in) & 1) ? *cur * scale : scale;
            rc = hg_params_set(&p, t[f].name, v);
            if ((rc == HG_OK) != (isfinite(v) != 0))
                fail("set accepted a non-finite value or refused a finite one");
        } else { /* a name that is not in the table */
            size_t k, len = fuzz_byte(&in) % (sizeof name - 1);
            for (k = 0; k < len; k++)
                name[k] = (char)(fuzz_byte(&in) | 1);
            name[len] = '\0';
            if (!hg_params_field(&p, name) && hg_params_set(&p, name, 1.0) != HG_ERR_BAD_PARAM)
                fail("set accepted an unknown name");
        }
    }
    rc = hg_params_check(&p, &field, &why);
    if (rc != HG_OK && rc != HG_ERR_BAD_PARAM)
        fail("check returned an unknown code");
    if (rc == HG_ERR_BAD_PARAM && (!field || !why || !hg_params_field(&p, field)))
        fail("refusal does not name a real field and a reason");
    {
        const char *whys[HG_PARAMS_MAX];
        hg_bitset mask;
        int all = hg_params_check_all(&p, &mask, whys), first = -1, beyond = 0;
        for (i = 0; i < n; i++) {
            if (hg_bitset_has(&mask, i) && !whys[i])
                fail("check_all flags a field without a reason");
            if (rc == HG_ERR_BAD_PARAM && strcmp(t[i].name, field) == 0)
                first = i;
        }
        for (i = n; i < HG_BITSET_BITS; i++)
            beyond |= hg_bitset_has(&mask, i);
        if (all != rc || (rc == HG_OK) != hg_bitset_empty(&mask) || beyond)
            fail("check_all disagrees with check");
        if (rc == HG_ERR_BAD_PARAM && (first < 0 || !hg_bitset_has(&mask, first)))
            fail("check_all does not flag the field check names");
    }
    rc = hg_model_init(&m, &p, (hg_model_kind)(fuzz_byte(&in) % HG_MODEL_COUNT), &field, &why);
    if (rc == HG_ERR_BAD_PARAM && (!field || !why))
        fail("model init refusal without field and reason");
    if (hg_params_check(&p, 0, 0) == HG_OK && rc == HG_ERR_BAD_PARAM &&
        !hg_params_field(&p, field ? field : ""))
        fail("model refused a valid set without naming a field");
    return 0;
}
