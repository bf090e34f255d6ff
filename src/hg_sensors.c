/* hg_sensors.c - converters, encoders, switches and watchdog of the
 * virtual MOTENC-100 board (contracts in hg_sensors.h). */
#include "hg_math.h"
#include "hg_sensors.h"

#define RAW_LIMIT 4503599627370496.0 /* 2^52: counts stay exact in a double */

/* Clamp x to [-limit, limit]; NaN gives 0. */
static double clamp_sym(double x, double limit)
{
    if (x > limit)
        return limit;
    if (x < -limit)
        return -limit;
    return x == x ? x : 0.0;
}

double hg_dac_volts(double value, double offset, double gain, int *garbage)
{
    double volts = (value - offset) * gain;
    if (garbage)
        *garbage = isnan(volts) ? 1 : 0;
    return clamp_sym(volts, HG_DAC_VOLTS_MAX);
}

double hg_dac_output(double volts)
{
    double count = floor(HG_DAC_COUNT_ZERO -
                         clamp_sym(volts, HG_DAC_VOLTS_MAX) * HG_DAC_COUNTS_PER_VOLT);
    return clamp_sym((HG_DAC_COUNT_ZERO - count) / HG_DAC_COUNTS_PER_VOLT, HG_DAC_VOLTS_MAX);
}

double hg_adc_sample(double volts)
{
    double count = floor(clamp_sym(volts, HG_ADC_VOLTS_MAX) * HG_ADC_COUNTS_PER_VOLT);
    if (count > HG_ADC_COUNTS_PER_VOLT * HG_ADC_VOLTS_MAX - 1)
        count = HG_ADC_COUNTS_PER_VOLT * HG_ADC_VOLTS_MAX - 1; /* 14-bit top code */
    return count / HG_ADC_COUNTS_PER_VOLT;
}

double hg_adc_value(double volts, double gain, double offset)
{
    double v = volts * gain - offset;
    return isfinite(v) ? v : 0.0;
}

/* floor(x) as an integer, saturated to +-2^52, 0 for NaN. */
static long long floor_saturated(double x)
{
    if (x != x)
        return 0;
    if (x > RAW_LIMIT)
        x = RAW_LIMIT;
    if (x < -RAW_LIMIT)
        x = -RAW_LIMIT;
    return (long long)floor(x);
}

long long hg_encoder_raw_counts(double turns, double counts_per_rev)
{
    if (!(counts_per_rev > 0) || !isfinite(turns))
        return 0;
    return floor_saturated(turns * counts_per_rev);
}

long long hg_encoder_revolution(double turns)
{
    if (!isfinite(turns))
        return 0;
    return floor_saturated(turns);
}

void hg_encoder_init(hg_encoder *e, double turns, double counts_per_rev)
{
    e->raw_counts = hg_encoder_raw_counts(turns, counts_per_rev);
    e->revolution = hg_encoder_revolution(turns);
    e->offset_counts = 0;
    e->latch_armed = 0;
    e->latch_hit = 0;
    e->index_pulse = 0;
}

int hg_encoder_update(hg_encoder *e, double turns, double counts_per_rev, int index_lost)
{
    long long rev = hg_encoder_revolution(turns);
    e->raw_counts = hg_encoder_raw_counts(turns, counts_per_rev);
    e->index_pulse = 0;
    if (rev != e->revolution && !index_lost) {
        /* the first index on the way: the top of the old revolution going
         * up, its bottom going down */
        long long first = rev > e->revolution ? e->revolution + 1 : e->revolution;
        e->index_pulse = 1;
        if (e->latch_armed && !e->latch_hit) {
            e->offset_counts = floor_saturated((double)first * counts_per_rev + 0.5);
            e->latch_hit = 1;
        }
    }
    e->revolution = rev;
    return e->index_pulse;
}

void hg_encoder_rescale(hg_encoder *e, double turns, double counts_per_rev)
{
    long long raw = hg_encoder_raw_counts(turns, counts_per_rev);
    e->offset_counts += raw - e->raw_counts;
    e->raw_counts = raw;
    e->revolution = hg_encoder_revolution(turns);
    e->index_pulse = 0;
}

void hg_encoder_arm(hg_encoder *e, int armed)
{
    e->latch_armed = armed ? 1 : 0;
    if (!armed)
        e->latch_hit = 0;
}

void hg_encoder_zero(hg_encoder *e)
{
    e->offset_counts = e->raw_counts;
}

void hg_encoder_glitch(hg_encoder *e, long long delta_counts)
{
    e->offset_counts -= delta_counts;
}

int hg_encoder_count(const hg_encoder *e)
{
    unsigned long long c = (unsigned long long)(e->raw_counts - e->offset_counts);
    return (int)(unsigned)(c & 0xffffffffull); /* the 32-bit counter wraps */
}

unsigned hg_switches_stuck(unsigned fresh, unsigned previous, unsigned stuck_mask)
{
    return (fresh & ~stuck_mask) | (previous & stuck_mask);
}

double hg_watchdog_timeout_s(unsigned control)
{
    return (control & HG_WD_CTL_16MS) ? 0.016 : 0.008;
}

void hg_watchdog_init(hg_watchdog *w)
{
    w->control = 0;
    w->remaining_s = hg_watchdog_timeout_s(0);
    w->expired = 0;
}

void hg_watchdog_set_control(hg_watchdog *w, unsigned control)
{
    int was_enabled = (w->control & HG_WD_CTL_ENABLE) != 0;
    if (control == w->control)
        return;
    w->control = control;
    if (!(control & HG_WD_CTL_ENABLE))
        w->expired = 0;
    else if (!was_enabled)
        hg_watchdog_kick(w);
}

void hg_watchdog_kick(hg_watchdog *w)
{
    w->remaining_s = hg_watchdog_timeout_s(w->control);
    w->expired = 0;
}

void hg_watchdog_dac_write(hg_watchdog *w)
{
    if (w->control & HG_WD_CTL_AUTO_RESET)
        hg_watchdog_kick(w);
}

int hg_watchdog_advance(hg_watchdog *w, double dt_s)
{
    if (!(w->control & HG_WD_CTL_ENABLE))
        return 0;
    if (dt_s > 0 && isfinite(dt_s))
        w->remaining_s -= dt_s;
    if (w->remaining_s <= 0)
        w->expired = 1;
    return w->expired;
}
