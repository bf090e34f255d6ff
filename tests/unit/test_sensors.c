/* test_sensors.c - the virtual MOTENC-100's converters, encoders, switches
 * and watchdog (hg_sensors.h) against facts stated independently: the
 * MOTENC-100 ranges and resolutions, the spec's 1000 counts/mm and 10 mm
 * lead, the switch positions of the parameter set. */
#include <math.h>
#include "hg_test.h"
#include "hg_sensors.h"
#include "hg_plant.h"

static void test_dac(void)
{
    int garbage = -1;
    CHECK(fabs(hg_dac_volts(5.0, 1.0, 2.0, &garbage) - 8.0) < 1e-12 && garbage == 0,
          "dac volts = (value - offset) * gain");
    CHECK(hg_dac_volts(7.0, 1.0, 2.0, 0) == 10.0, "dac volts clamp at +10 V");
    CHECK(hg_dac_volts(-7.0, 1.0, 2.0, 0) == -10.0, "dac volts clamp at -10 V");
    CHECK(hg_dac_volts(NAN, 0.0, 1.0, &garbage) == 0.0 && garbage == 1, "dac NaN counts as 0 V and is flagged");
    CHECK(hg_dac_volts(INFINITY, 0.0, 1.0, &garbage) == 10.0 && garbage == 0, "dac +inf clamps to +10 V");
    CHECK(hg_dac_volts(-INFINITY, 0.0, 1.0, 0) == -10.0, "dac -inf clamps to -10 V");
    CHECK(hg_dac_volts(1e30, 0.0, 1.0, 0) == 10.0, "dac 1e30 clamps to +10 V");
    CHECK(hg_dac_volts(INFINITY, 0.0, 0.0, &garbage) == 0.0 && garbage == 1, "dac inf * 0 gain (NaN) is 0 V");
    CHECK(hg_dac_output(0.0) == 0.0, "dac 0 V is exactly 0 V out (count 4096)");
    {
        int i, bad = 0;
        double lsb = 20.0 / 8191.0;
        for (i = 0; i < 2000; i++) {
            double v = hg_test_uniform(-10, 10);
            double o = hg_dac_output(v);
            double steps = o / lsb;
            if (!(fabs(o - v) <= lsb * (1 + 1e-9)) || fabs(steps - floor(steps + 0.5)) > 1e-6 ||
                fabs(o) > 10.0)
                bad++;
        }
        CHECK(bad == 0, "dac output within one 13-bit step (20/8191 V) of the request, on the grid (%d bad)", bad);
    }
    CHECK(hg_dac_output(10.0) == 10.0 && hg_dac_output(-10.0) <= -9.99, "dac full scale");
    CHECK(hg_dac_output(NAN) == 0.0, "dac output of NaN is 0 V");
}

static void test_adc(void)
{
    double lsb = 10.0 / 16384.0;
    CHECK(fabs(hg_adc_sample(1.0) - 1.0) <= lsb, "adc 1 V reads within one 14-bit step");
    CHECK(fabs(hg_adc_sample(-3.3) + 3.3) <= lsb, "adc -3.3 V reads within one 14-bit step");
    CHECK(hg_adc_sample(7.0) < 5.0 && hg_adc_sample(7.0) > 5.0 - 2 * lsb, "adc clamps above +5 V");
    CHECK(hg_adc_sample(-7.0) == -5.0, "adc clamps below -5 V");
    CHECK(hg_adc_sample(NAN) == 0.0, "adc NaN reads 0");
    CHECK(fabs(hg_adc_value(2.0, 3.0, 1.0) - 5.0) < 1e-12, "adc value = volts * gain - offset (hal_motenc)");
    CHECK(hg_adc_value(2.0, INFINITY, 1.0) == 0.0, "adc value never infinite");
}

static void test_encoder_counts(void)
{
    const double lead = 0.010, cpr = 10000;
    hg_encoder e;
    CHECK(hg_encoder_raw_counts(0.001 / lead, cpr) == 1000, "1 mm is 1000 counts");
    CHECK(hg_encoder_raw_counts(0.2345678 / lead, cpr) == 234567, "234.5678 mm is 234567 counts (floor)");
    CHECK(hg_encoder_raw_counts(-1e-9 / lead, cpr) == -1, "just below HOME is count -1");
    CHECK(hg_encoder_raw_counts(NAN / lead, cpr) == 0, "NaN position gives count 0");
    CHECK(hg_encoder_raw_counts(1.0 / 0.0, cpr) == 0, "an infinite turn count (a zero lead) gives count 0");
    CHECK(hg_encoder_raw_counts(1.0, 0.0) == 0, "zero counts per revolution give count 0");
    CHECK(hg_encoder_raw_counts(1e300 / lead, cpr) > 0, "huge position saturates");
    hg_encoder_init(&e, 0.0 / lead, cpr);
    CHECK(hg_encoder_count(&e) == 0, "counter reads 0 at HOME after power-up");
    hg_encoder_update(&e, 0.0123005 / lead, cpr, 0);
    CHECK(hg_encoder_count(&e) == 12300, "12.3 mm up reads 12300");
    hg_encoder_zero(&e);
    CHECK(hg_encoder_count(&e) == 0, "reset zeroes the counter");
    hg_encoder_update(&e, 0.0113005 / lead, cpr, 0);
    CHECK(hg_encoder_count(&e) == -1000, "then 1 mm down reads -1000");
    hg_encoder_glitch(&e, 7);
    CHECK(hg_encoder_count(&e) == -993, "a glitch of +7 counts adds 7");
    hg_encoder_rescale(&e, 0.0113005 / 0.005, cpr);
    CHECK(hg_encoder_count(&e) == -993, "a new lead keeps the counter's reading");
    hg_encoder_update(&e, 0.0123005 / 0.005, cpr, 0);
    CHECK(hg_encoder_count(&e) == -993 + 2000, "and counts 2000 per mm with a 5 mm lead (%d)", hg_encoder_count(&e));
    e.offset_counts = e.raw_counts - 2147483647LL - 5;
    CHECK(hg_encoder_count(&e) == -2147483644, "the 32-bit counter wraps like an s32");
}

static void test_index(void)
{
    const double lead = 0.010, cpr = 10000;
    hg_encoder e;
    int i, pulses = 0, misplaced = 0;
    double z = -0.025, zprev;
    /* sweep -25 mm .. +25 mm in 0.37 mm steps: indexes at -20 -10 0 10 20 mm */
    hg_encoder_init(&e, z / lead, cpr);
    for (i = 0; i < 200 && z < 0.025; i++) {
        zprev = z;
        z += 0.00037;
        if (hg_encoder_update(&e, z / lead, cpr, 0)) {
            double k = floor(z / lead) * lead; /* the multiple of lead just passed */
            pulses++;
            if (!(zprev < k && k <= z + 1e-15))
                misplaced++;
        }
    }
    CHECK(pulses == 5 && misplaced == 0, "5 index pulses between -25 and +25 mm, each where z passes a multiple of 10 mm (%d, %d misplaced)", pulses, misplaced);
    /* and back down */
    pulses = 0;
    for (i = 0; i < 200 && z > -0.025; i++) {
        z -= 0.00041;
        pulses += hg_encoder_update(&e, z / lead, cpr, 0);
    }
    CHECK(pulses == 5, "5 index pulses on the way down (%d)", pulses);
    hg_encoder_init(&e, 0.004 / lead, cpr);
    CHECK(hg_encoder_update(&e, 0.009 / lead, cpr, 0) == 0, "no index between 4 and 9 mm");
    CHECK(hg_encoder_update(&e, 0.0101 / lead, cpr, 0) == 1, "index between 9 and 10.1 mm");
    CHECK(hg_encoder_update(&e, 0.0102 / lead, cpr, 0) == 0, "index pulse lasts one update");
    CHECK(hg_encoder_update(&e, 0.0302 / lead, cpr, 1) == 0, "lost index: no pulse");

    /* index latch going up: armed at 3 mm, index at 10 mm, now at 10.5 mm */
    hg_encoder_init(&e, 0.003 / lead, cpr);
    hg_encoder_arm(&e, 1);
    hg_encoder_update(&e, 0.0099 / lead, cpr, 0);
    CHECK(e.latch_hit == 0 && hg_encoder_count(&e) == 9900, "armed latch waits for the index (9900)");
    hg_encoder_update(&e, 0.0105 / lead, cpr, 0);
    CHECK(e.latch_hit == 1 && hg_encoder_count(&e) == 500, "latch zeroes the count at the 10 mm index: 10.5 mm reads 500 (%d)", hg_encoder_count(&e));
    hg_encoder_update(&e, 0.0205 / lead, cpr, 0);
    CHECK(hg_encoder_count(&e) == 10500, "the latch fires once: the next index does not re-zero (%d)", hg_encoder_count(&e));
    hg_encoder_arm(&e, 0);
    CHECK(e.latch_hit == 0, "disarming clears the latch flag");
    /* going down: armed at 3 mm, index at 0, now at -0.5 mm */
    hg_encoder_init(&e, 0.003 / lead, cpr);
    hg_encoder_glitch(&e, 12345);
    hg_encoder_arm(&e, 1);
    hg_encoder_update(&e, -0.0005 / lead, cpr, 0);
    CHECK(hg_encoder_count(&e) == -500, "latch on the way down: -0.5 mm reads -500 (%d)", hg_encoder_count(&e));
    /* lost index: an armed latch does not fire */
    hg_encoder_init(&e, 0.003 / lead, cpr);
    hg_encoder_arm(&e, 1);
    hg_encoder_update(&e, 0.0105 / lead, cpr, 1);
    CHECK(e.latch_hit == 0 && hg_encoder_count(&e) == 10500, "a lost index does not fire the latch");
}

/* The Hexaglide's switches on a carriage at z (its limit and home positions). */
static unsigned switches(const hg_params *p, double z)
{
    return hg_plant_switches(z, p->limit_min_m, p->limit_max_m, p->home_switch_m);
}

static void test_switches(void)
{
    hg_params p;
    hg_params_default(&p);
    CHECK(switches(&p, -0.250) == HG_SW_MIN, "limit- trips at -250 mm");
    CHECK(switches(&p, -0.2499) == 0, "nothing on at -249.9 mm");
    CHECK(switches(&p, 0.0049) == 0, "home switch off at 4.9 mm");
    CHECK(switches(&p, 0.005) == HG_SW_HOME, "home switch on at 5 mm");
    CHECK(switches(&p, 0.2499) == HG_SW_HOME, "only home at 249.9 mm");
    CHECK(switches(&p, 0.250) == (HG_SW_MAX | HG_SW_HOME), "limit+ and home at 250 mm");
    CHECK(switches(&p, NAN) == (HG_SW_MIN | HG_SW_MAX), "NaN position trips both limits");
    CHECK(hg_switches_stuck(HG_SW_MAX, HG_SW_MIN, HG_SW_MIN | HG_SW_MAX) == HG_SW_MIN,
          "stuck switches keep their previous reading");
    CHECK(hg_switches_stuck(HG_SW_MAX | HG_SW_HOME, HG_SW_MIN, HG_SW_MIN) == (HG_SW_MIN | HG_SW_MAX | HG_SW_HOME),
          "only stuck bits are held");
}

static void test_watchdog(void)
{
    hg_watchdog w;
    int i, expired_at = -1;
    hg_watchdog_init(&w);
    for (i = 0; i < 100; i++)
        hg_watchdog_advance(&w, 0.001);
    CHECK(!w.expired, "disabled watchdog never expires");
    hg_watchdog_set_control(&w, HG_WD_CTL_ENABLE);
    for (i = 1; i <= 20 && expired_at < 0; i++)
        if (hg_watchdog_advance(&w, 0.001))
            expired_at = i;
    CHECK(expired_at == 8, "8 ms watchdog expires at the 8th 1 ms tick (%d)", expired_at);
    hg_watchdog_advance(&w, 0.001);
    CHECK(w.expired, "and stays expired");
    hg_watchdog_kick(&w);
    CHECK(!w.expired, "a reset clears the expiry");
    hg_watchdog_set_control(&w, HG_WD_CTL_ENABLE | HG_WD_CTL_16MS);
    hg_watchdog_kick(&w);
    expired_at = -1;
    for (i = 1; i <= 40 && expired_at < 0; i++)
        if (hg_watchdog_advance(&w, 0.001))
            expired_at = i;
    CHECK(expired_at == 16, "16 ms watchdog expires at the 16th tick (%d)", expired_at);
    hg_watchdog_set_control(&w, HG_WD_CTL_ENABLE | HG_WD_CTL_AUTO_RESET);
    hg_watchdog_kick(&w);
    for (i = 0; i < 100; i++) {
        hg_watchdog_dac_write(&w);
        hg_watchdog_advance(&w, 0.001);
    }
    CHECK(!w.expired, "auto-reset watchdog fed by DAC writes does not expire");
    hg_watchdog_set_control(&w, HG_WD_CTL_ENABLE);
    hg_watchdog_kick(&w);
    for (i = 0; i < 10; i++) {
        hg_watchdog_dac_write(&w);
        hg_watchdog_advance(&w, 0.001);
    }
    CHECK(w.expired, "without auto-reset, DAC writes do not feed the watchdog");
    hg_watchdog_set_control(&w, 0);
    CHECK(!w.expired, "disabling clears the expiry");
}

int main(void)
{
    test_dac();
    test_adc();
    test_encoder_counts();
    test_index();
    test_switches();
    test_watchdog();
    return hg_test_exit();
}
