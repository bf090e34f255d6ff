/* fuzz_board.c - the virtual board (hg_board_step) fed random input
 * sequences: DAC values (NaN, inf, 1e300), digital outputs and inverts,
 * E-STOP button and loop output, resets, watchdog control and kicks,
 * index-enable, encoder resets and scales, ADC gains, fault injection
 * (amp-fail, stuck/tripped switches, lost index, glitches, the plant's
 * own: broken bars), hostile parameter changes (any field, substeps,
 * integrator) and periods, on every plant of the registry
 * (0, negative, huge). Properties: no crash; every output number finite;
 * codes and event data within their documented ranges; the block in force
 * always passes validation; a refusal names at least one field and each
 * named field has a reason; a faulted board keeps its state frozen and its
 * drives off. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include "fuzz_input.h"
#include "hg_board.h"
#include "hg_string.h"
#include "hg_errors.h"

static void fail(const char *what)
{
    fprintf(stderr, "fuzz_board: property violated: %s\n", what);
    abort();
}

/* every double of the outputs is finite */
static int outputs_finite(const hg_board_outputs *o)
{
    int k, ok = isfinite(o->sim_time_s);
    for (k = 0; k < HG_BOARD_ENCODERS; k++)
        ok = ok && isfinite(o->position[k]) && isfinite(o->enc_scale[k]);
    for (k = 0; k < HG_BOARD_ADCS; k++)
        ok = ok && isfinite(o->adc[k]);
    for (k = 0; k < HG_PLANT_EXTRA_MAX; k++)
        ok = ok && isfinite(o->extra[k]);
    for (k = 0; k < HG_CHANNELS_MAX; k++)
        ok = ok && isfinite(o->pos[k]) && isfinite(o->vel[k]) && isfinite(o->motor_pos[k]) &&
             isfinite(o->volts[k]) && isfinite(o->current_a[k]) && isfinite(o->force[k]);
    return ok;
}

/* One random change to the inputs. */
static void mutate(fuzz_input *f, hg_board_inputs *in, int n_params)
{
    uint8_t what = fuzz_byte(f), ch = fuzz_byte(f);
    int k = ch % 8, j = ch % HG_CHANNELS_MAX;
    switch (what % 16) {
    case 0: case 1: case 2:
        in->dac_v[k] = fuzz_double(f, -12.0, 12.0);
        break;
    case 3:
        in->dout_values ^= 1u << (ch % 32);
        if (fuzz_byte(f) & 1)
            in->dout_inverts ^= 1u << (fuzz_byte(f) % 32);
        break;
    case 4:
        in->estop_button = fuzz_byte(f) & 1;
        in->estop_loop_out = (int)fuzz_byte(f) - 40;
        break;
    case 5:
        in->reset = !in->reset;
        break;
    case 6:
        in->watchdog_control = fuzz_byte(f);
        in->watchdog_reset = fuzz_byte(f) & 1;
        in->dac_written = fuzz_byte(f) & 1;
        break;
    case 7:
        in->index_enable[k] = !in->index_enable[k];
        in->enc_reset[k] = fuzz_byte(f) < 32;
        break;
    case 8:
        in->enc_scale[k] = fuzz_double(f, -2000.0, 2000.0);
        break;
    case 9:
        in->adc_read = fuzz_byte(f) & 1;
        in->adc_gain[k] = fuzz_double(f, -10.0, 10.0);
        in->adc_offset[k] = fuzz_double(f, -10.0, 10.0);
        in->adc_volts_per_amp = fuzz_double(f, -2.0, 2.0);
        break;
    case 10:
        in->amp_fail[j] = fuzz_byte(f) & 1;
        in->stuck[j] = fuzz_byte(f) & 7u;
        in->tripped[j] = fuzz_byte(f) & 7u;
        in->index_lost[j] = fuzz_byte(f) & 1;
        break;
    case 11: {
        static const int glitch[] = {0, 1, -1, 5000, INT_MAX, INT_MIN};
        in->enc_glitch[j] = glitch[fuzz_byte(f) % 6];
        break;
    }
    case 12:                     /* the plant's injections (the Hexaglide's bar-broken) */
        in->inject[j] = fuzz_byte(f) < 64 ? 1u << (fuzz_byte(f) % HG_PLANT_INJECT_MAX) : 0u;
        break;
    case 13: case 14: {          /* a hostile or a slightly changed parameter */
        double *v = &in->params.plant.v[ch % n_params];
        *v = (fuzz_byte(f) & 1) ? *v * fuzz_double(f, 0.5, 2.0) : fuzz_double(f, -2.0, 2.0);
        break;
    }
    default: {                  /* substeps and integrator, mostly small */
        uint8_t s = fuzz_byte(f);
        in->params.substeps = s < 200 ? 1u + s % 4u : s < 250 ? 0u : (unsigned)(s - 250) * 1000000000u;
        in->params.integrator = fuzz_byte(f) % 5u;
        break;
    }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static hg_board b;
    static hg_board_inputs in;
    static hg_board_outputs out, prev;
    static const char *why[HG_BOARD_WHY_LEN];
    fuzz_input f = {data, size, 0};
    int n, i, k, steps, nplants = 0, plant, variant, nch;
    const hg_plant *pl;
    while (hg_plant_at(nplants))
        nplants++;
    plant = fuzz_byte(&f) % nplants;
    pl = hg_plant_at(plant);
    variant = fuzz_byte(&f);             /* the plant's default when it is none of its variants */
    if (!hg_plant_nparams_at(plant, variant))
        variant = pl->default_variant;
    n = pl->nparams(variant);
    nch = pl->channels(variant);
    if (hg_board_init(&b, plant, variant, 0))
        fail("the default board does not build");
    hg_board_inputs_default(&b, &in);
    in.dout_values = 1u << 7;
    hg_board_peek(&b, &prev);
    steps = 1 + fuzz_byte(&f) % 24;
    for (i = 0; i < steps; i++) {
        long period = 1000000;
        uint8_t p = fuzz_byte(&f);
        for (k = fuzz_byte(&f) % 4; k > 0; k--)
            mutate(&f, &in, n);
        if (p >= 240) {             /* 0, negative, 1 ns, beyond 10 ms, extremes */
            static const long odd[] = {0, -1, 1, 250000, 10000000, 10000001, 20000000, LONG_MIN, LONG_MAX};
            double v = fuzz_double(&f, -2e7, 2e7);
            period = (p & 1) ? odd[fuzz_byte(&f) % 9] : isfinite(v) && fabs(v) < 1e15 ? (long)v : 1000000;
        }
        hg_board_step(&b, &in, &out, period);
        if (!outputs_finite(&out))
            fail("an output is not finite");
        if (out.fault_code > 0 || out.fault_code < HG_ERR_LAST || (out.fault == 0) != (out.fault_code == 0))
            fail("fault code out of range or inconsistent with the fault flag");
        if (out.events & ~(unsigned)HG_EV_ALL)
            fail("unknown event bit");
        if (out.fault_cause < HG_FAULT_NONE || out.fault_cause > HG_FAULT_STIFF ||
            out.reset_refused_channel < -1 || out.reset_refused_channel >= nch ||
            out.reset_refused_injection < -1 || out.reset_refused_injection >= pl->ninjections ||
            out.channels != nch)
            fail("event data out of range");
        for (k = 0; k < HG_PLANT_INJECT_MAX; k++)
            if (out.injected[k] >> nch || (k >= pl->ninjections && out.injected[k]))
                fail("an injection acted on no channel of the plant or is no injection of it");
        if (hg_board_params_check(&b, &out.params, 0, 0) != HG_OK)
            fail("the block in force does not pass validation");
        if (out.events & HG_EV_PARAM_REFUSED) {
            hg_bitset mask;
            if (out.param_rc == HG_ERR_BAD_PARAM) {
                int any = 0;
                for (k = 0; k < HG_BITSET_BITS; k++)
                    if (hg_bitset_has(&out.refused, k)) {
                        any = 1;
                        if (k >= n && k != HG_BOARD_BIT_SUBSTEPS && k != HG_BOARD_BIT_INTEGRATOR)
                            fail("refusal names a bit outside the table");
                    }
                if (!any)
                    fail("refusal names no field");
                hg_board_params_check(&b, &in.params, &mask, why);
                if (memcmp(&mask, &out.refused, sizeof mask) != 0)
                    fail("explain_refusal disagrees with the refusal");
                for (k = 0; k < HG_BOARD_WHY_LEN; k++)
                    if (hg_bitset_has(&mask, k) && (!why[k] || !hg_board_param_hal_name(&b, k)))
                        fail("a refused field without a reason or a HAL name");
            } else if (out.param_rc >= 0 || out.param_rc < HG_ERR_LAST) {
                fail("refusal code out of range");
            }
        }
        for (k = 0; k < HG_BOARD_INPUTS; k++)
            if (out.in[k] > 1)
                fail("a digital input is not 0 or 1");
        if (prev.fault && out.fault && !(out.events & (HG_EV_RESET_DONE | HG_EV_GEOMETRY_RESTART))) {
            if (memcmp(out.pos, prev.pos, sizeof out.pos) != 0 || out.sim_time_s != prev.sim_time_s)
                fail("a faulted board moved");
            for (k = 0; k < HG_CHANNELS_MAX; k++)
                if (out.volts[k] != 0 || out.current_a[k] != 0)
                    fail("a faulted board drives");
        }
        for (k = 0; k < HG_CHANNELS_MAX; k++)
            in.enc_glitch[k] = 0;     /* as the glue: applied once */
        prev = out;
    }
    return 0;
}
