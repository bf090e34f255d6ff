/* fuzz_dynamics.c - the dynamics step with random parameter sets that pass
 * validation, every parametrization, random and garbage volts (NaN, inf,
 * 1e300) and time steps, and now and then broken bars.
 * Properties: no crash; every call returns 0 or a
 * documented code; the state in hg_data stays finite; a failed step leaves
 * the state exactly as it was. */
#include <stdio.h>
#include <stdlib.h>
#include "fuzz_input.h"
#include "hg_dynamics.h"
#include "hg_errors.h"

static void fail(const char *what)
{
    fprintf(stderr, "fuzz_dynamics: property violated: %s\n", what);
    abort();
}

/* every double of the state (not the diagnostics) is finite */
static int state_finite(const hg_data *d)
{
    int k;
    for (k = 0; k < 6; k++)
        if (!isfinite(d->z_m[k]) || !isfinite(d->zd_mps[k]) || !isfinite(d->pose[k]) ||
            !isfinite(d->posed[k]) || !isfinite(d->current_a[k]) || !isfinite(d->force_n[k]) ||
            !isfinite(d->zr_m[k]) || !isfinite(d->zrd_mps[k]) || !isfinite(d->vloop_int_m[k]))
            return 0;
    for (k = 0; k < 12; k++)
        if (!isfinite(d->bar_rad[k]) || !isfinite(d->bar_radps[k]))
            return 0;
    return isfinite(d->t_s) && isfinite(d->residual_m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in = {data, size, 0};
    static hg_model m;
    static hg_data d, before;
    hg_params p;
    const hg_param_info *t;
    const char *field, *why;
    int n, i, k, steps, rc;
    t = hg_params_table(&n);
    hg_params_default(&p);
    /* perturb a few fields by up to a factor of 2 either way */
    for (i = fuzz_byte(&in) % 4; i > 0; i--) {
        int f = fuzz_byte(&in) % n;
        double *cur = hg_params_field(&p, t[f].name);
        *cur *= fuzz_double(&in, 0.5, 2.0);
    }
    if (hg_params_check(&p, &field, &why) != HG_OK)
        return 0; /* only sets that pass validation go further */
    if (hg_model_init(&m, &p, (hg_model_kind)(fuzz_byte(&in) % HG_MODEL_COUNT), &field, &why))
        return 0; /* e.g. a geometry whose HOME cannot be assembled: refused, fine */
    if (hg_model_set_integrator(&m, fuzz_byte(&in) % HG_INTEGRATOR_COUNT))
        fail("a valid integrator was refused");
    if (hg_data_reset(&m, &d))
        return 0;
    if (fuzz_byte(&in) < 32)          /* now and then, fault injection: broken bars */
        d.broken_bars = fuzz_byte(&in) & HG_BARS_ALL;
    steps = 1 + fuzz_byte(&in) % 16;
    for (i = 0; i < steps; i++) {
        double volts[6], dt;
        for (k = 0; k < 6; k++)
            volts[k] = fuzz_double(&in, -12.0, 12.0);
        dt = (fuzz_byte(&in) < 240) ? 1e-3 : fuzz_double(&in, 0.0, 0.012);
        before = d;
        rc = hg_step(&m, &d, volts, dt);
        if (rc > 0 || rc < HG_ERR_LAST)
            fail("step returned an unknown code");
        if (!state_finite(&d))
            fail("state not finite after a step");
        if (rc != HG_OK) {
            before.last_error = d.last_error;     /* the failure's report: code and what struck */
            before.guard = d.guard;
            if (memcmp(&before, &d, HG_DATA_STATE_BYTES) != 0) /* the scratch d.work may change */
                fail("failed step changed the state");
            break;
        }
    }
    return 0;
}
