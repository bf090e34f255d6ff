/* test_board.c - the virtual board's state machine (hg_board.h) without
 * halrun: reset refused while a bar is broken, the E-STOP loop, the
 * watchdog's 8 ms, refused parameters (every invalid field named, the set
 * in force kept), the fault latch with the state frozen, the index latch,
 * substeps against hg_step driven directly, bad periods, DAC NaN, encoder
 * scale, determinism. Facts come from the MOTENC-100 (8 ms watchdog, 13-bit
 * DAC), the spec (1000 counts/mm, 10 mm lead) and hg_step itself called
 * independently of the board. */
#include <limits.h>
#include <math.h>
#include <string.h>
#include "hg_test.h"
#include "hg_board.h"
#include "hg_plant_hexaglide.h"
#include "hg_text.h"
#include "hg_params.h"
#include "hg_dynamics.h"
#include "hg_errors.h"

#define PERIOD 1000000L              /* 1 ms */

static hg_board b, b2;
static hg_board_inputs in, in2;
static hg_board_outputs out, out2;

/* Fresh board (reduced Cartesian, defaults) with the E-STOP loop closed. */
static void fresh(void)
{
    int rc = hg_board_init(&b, 0, HG_MODEL_REDUCED_CARTESIAN, 0);
    if (rc)
        printf("# hg_board_init: %d\n", rc);
    hg_board_inputs_default(&b, &in);
    in.dout_values = 1u << 7;
}

/* Step n periods; returns the OR of the events seen. */
static unsigned run(int n)
{
    unsigned ev = 0;
    while (n-- > 0) {
        hg_board_step(&b, &in, &out, PERIOD);
        ev |= out.events;
    }
    return ev;
}

/* Bit (table entry) of the Hexaglide's parameter called name, or -1. */
static int bit_of(const char *name)
{
    int n;
    const hg_param_info *t = hg_params_table(&n);
    return hg_param_find(t, n, name);
}

/* The set of bits a..d (-1: none). */
static hg_bitset set_of(int a, int b, int c, int d)
{
    hg_bitset s;
    hg_bitset_clear(&s);
    hg_bitset_set(&s, a);
    hg_bitset_set(&s, b);
    hg_bitset_set(&s, c);
    hg_bitset_set(&s, d);
    return s;
}

/* 1 if the sets are equal. */
static int same_set(const hg_bitset *a, const hg_bitset *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

static void test_estop_loop(void)
{
    int k;
    fresh();
    in.dout_values = 0;
    for (k = 0; k < 6; k++)
        in.dac_v[k] = 2.0;
    run(1);
    CHECK(out.estop_in == 1 && out.amps_on == 0 && out.volts[0] == 0 && out.dout_word == 0,
          "out-07 off: E-STOP loop open, amplifiers off, 0 V, outputs off");
    in.dout_values = (1u << 7) | (1u << 3);
    run(1);
    CHECK(out.estop_in == 0 && out.amps_on == 1 && out.dout_word == ((1u << 7) | (1u << 3)) &&
          fabs(out.volts[0] - 2.0) <= 20.0 / 8191.0,
          "out-07 on: loop closed, amplifiers on, volts within one 13-bit DAC step of 2 V (%g)", out.volts[0]);
    in.dout_values = 0;
    in.dout_inverts = 1u << 7;
    run(1);
    CHECK(out.estop_in == 0 && out.amps_on == 1 && out.dout_word == (1u << 7),
          "out-07 FALSE with out-07-invert: commanded on, loop closed");
    in.estop_button = 1;
    run(1);
    CHECK(out.estop_in == 1 && out.amps_on == 0 && out.dout_word == 0 && out.current_a[0] == 0,
          "E-STOP button: loop open, drives off, outputs off, no current");
    in.estop_button = 0;
    in.dout_inverts = 0;
    in.estop_loop_out = -1;
    run(1);
    CHECK(out.estop_in == 0 && out.amps_on == 1, "estop-loop-out -1: no output in the loop, closed");
    /* a value that names no output (a typo: 32, 70, -5) is refused, once, and the
     * output in force stays in the loop: with out-07 off the drives stay off */
    in.estop_loop_out = 7;
    in.dout_values = 0;
    run(1);
    CHECK(out.estop_in == 1 && out.amps_on == 0 && out.estop_loop_out == 7 && !(out.events & HG_EV_ESTOP_OUT_BAD),
          "estop-loop-out 7 again, out-07 off: loop open");
    {
        static const int bad[] = {32, 70, -2, -100, 2147483647};
        unsigned i;
        for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
            in.estop_loop_out = bad[i];
            run(1);
            CHECK((out.events & HG_EV_ESTOP_OUT_BAD) && out.param_error && out.estop_loop_out == 7 &&
                  out.estop_in == 1 && out.amps_on == 0,
                  "estop-loop-out %d refused (event, param-error), out-07 stays in the loop: still open, drives off",
                  bad[i]);
            run(1);
            CHECK(!(out.events & HG_EV_ESTOP_OUT_BAD) && out.estop_in == 1 && out.amps_on == 0,
                  "estop-loop-out %d held: said once, loop still open", bad[i]);
        }
    }
    in.estop_loop_out = 31;
    run(1);
    CHECK(out.estop_loop_out == 31 && !(out.events & HG_EV_ESTOP_OUT_BAD) && out.estop_in == 1,
          "estop-loop-out 31 (the last output) taken: out-31 off, loop open");
    in.dout_values = 1u << 31;
    run(1);
    CHECK(out.estop_in == 0 && out.amps_on == 1, "out-31 on: loop closed");
}

static void test_watchdog(void)
{
    int i, first = -1, said = 0;
    fresh();
    in.watchdog_control = HG_WD_CTL_ENABLE;           /* 8 ms, no auto reset */
    for (i = 1; i <= 12 && first < 0; i++) {
        run(1);
        if (out.watchdog_expired)
            first = i;
    }
    CHECK(first == 8 || first == 9, "enabled watchdog (8 ms) expires after 8 periods of 1 ms unkicked (%d)", first);
    CHECK(out.events & HG_EV_WATCHDOG_EXPIRED, "the period it expires in has WATCHDOG_EXPIRED (the glue says it)");
    for (i = 0; i < 20; i++) {
        run(1);
        said += (out.events & HG_EV_WATCHDOG_EXPIRED) != 0;
    }
    CHECK(said == 0 && out.watchdog_expired, "still expired 20 periods on: said once (%d more)", said);
    CHECK(out.amps_on == 0 && out.dout_word == 0, "expired watchdog: amplifiers off, outputs off");
    in.watchdog_reset = 1;
    run(1);
    CHECK((out.events & HG_EV_WATCHDOG_KICKED) && !out.watchdog_expired && out.amps_on,
          "watchdog-reset: kicked (the driver clears the pin), alive again, amplifiers on");
    in.watchdog_reset = 0;
    in.watchdog_control = HG_WD_CTL_ENABLE | HG_WD_CTL_16MS | HG_WD_CTL_AUTO_RESET;
    in.dac_written = 1;
    for (i = 0; i < 100; i++) {
        run(1);
        if (out.watchdog_expired)
            break;
    }
    CHECK(i == 100, "auto reset (control 21) with a dac-write every period: alive for 100 periods");
    in.dac_written = 0;
    first = -1;
    for (i = 1; i <= 20 && first < 0; i++) {
        run(1);
        if (out.watchdog_expired)
            first = i;
    }
    /* the last dac-write's period already counted 1 ms of the 16 */
    CHECK(first == 15 || first == 16, "16 ms watchdog expires 16 ms after the last dac-write (%d more periods)", first);
}

static void test_refused_params(void)
{
    hg_board_params in_force;
    static const char *why[HG_BOARD_WHY_LEN];
    hg_bitset mask, want;
    unsigned ev;
    int k, same = 1;
    fresh();
    for (k = 0; k < 6; k++)
        in.dac_v[k] = 0.5 * (k - 2);
    b2 = b;
    in2 = in;
    run(10);
    in_force = out.params;
    *hg_test_pv(&in.params, "c_visc") = -1;
    *hg_test_pv(&in.params, "m_head") = 0;
    *hg_test_pv(&in.params, "lead") = 0;
    *hg_test_pv(&in.params, "l") = 0.1;
    ev = run(1);
    want = set_of(bit_of("c_visc"), bit_of("m_head"), bit_of("lead"), bit_of("l"));
    CHECK((ev & HG_EV_PARAM_REFUSED) && same_set(&out.refused, &want) && out.param_rc == HG_ERR_BAD_PARAM,
          "c_visc -1, m_head 0, lead 0, l 0.1: refused naming all four (mask %llx, want %llx)",
          out.refused.w[0], want.w[0]);
    CHECK(memcmp(&out.params, &in_force, sizeof in_force) == 0 && out.param_error == 1,
          "refused: the set in force is unchanged and shown, param-error set");
    hg_board_params_check(&b, &in.params, &mask, why);
    CHECK(same_set(&mask, &want) && why[bit_of("l")] && why[bit_of("m_head")] && why[bit_of("lead")] &&
          why[bit_of("c_visc")],
          "hg_board_params_check gives a reason for each (l: %s)", why[0] ? why[0] : "none");
    run(20);
    for (k = 0; k < 31; k++) {                          /* the twin never saw the change */
        hg_board_step(&b2, &in2, &out2, PERIOD);
    }
    for (k = 0; k < 6; k++)
        same = same && out.pos[k] == out2.pos[k];
    CHECK(same && out.param_error == 1 && !(out.events & HG_EV_PARAM_REFUSED),
          "refused block held in the inputs: simulated with the old set, bit-identical to a twin; refused once");
    in.params = out.params;                             /* the glue shows the set in force again */
    ev = run(1);
    CHECK(!(ev & (HG_EV_PARAM_REFUSED | HG_EV_PARAM_APPLIED)) && out.param_error == 1,
          "inputs put back to the set in force: nothing applied, param-error stays until a change is accepted");
    *hg_test_pv(&in.params, "c_visc") = 2 * 5665.6;
    ev = run(1);
    CHECK((ev & HG_EV_PARAM_APPLIED) && !(ev & HG_EV_GEOMETRY_RESTART) && out.param_error == 0 &&
          *hg_test_pv(&out.params, "c_visc") == 2 * 5665.6,
          "a valid change (c_visc doubled) is applied without a restart, param-error cleared");
    in.params.substeps = 0;
    in.params.integrator = 3;
    ev = run(1);
    want = set_of(HG_BOARD_BIT_SUBSTEPS, HG_BOARD_BIT_INTEGRATOR, -1, -1);
    CHECK((ev & HG_EV_PARAM_REFUSED) && same_set(&out.refused, &want) &&
          out.params.substeps == 1 && out.params.integrator == HG_INTEGRATOR_HEUN,
          "substeps 0 and integrator 3 refused, both named (%s, %s)",
          hg_board_param_hal_name(&b, HG_BOARD_BIT_SUBSTEPS), hg_board_param_hal_name(&b, HG_BOARD_BIT_INTEGRATOR));
    in.params.substeps = HG_SUBSTEPS_MAX + 1;
    in.params.integrator = 0;
    ev = run(1);
    want = set_of(HG_BOARD_BIT_SUBSTEPS, -1, -1, -1);
    CHECK((ev & HG_EV_PARAM_REFUSED) && same_set(&out.refused, &want),
          "substeps %u refused", HG_SUBSTEPS_MAX + 1);
    in.params.substeps = 2;
    in.params.integrator = HG_INTEGRATOR_RK4;
    ev = run(1);
    CHECK((ev & HG_EV_PARAM_APPLIED) && hg_hexaglide_model(&b.m)->integrator == HG_INTEGRATOR_RK4 &&
              b.substeps == 2,
          "substeps 2, integrator rk4 applied to the model");
    *hg_test_pv(&in.params, "l") = 1.1;
    ev = run(1);
    CHECK((ev & HG_EV_GEOMETRY_RESTART) && fabs(out.extra[0]) + fabs(out.extra[1]) + fabs(out.extra[2]) < 1e-4 &&
          fabs(out.pos[0]) < 1e-4,
          "l 1.1: new geometry, restarted at HOME: one period later head and carriages are within 0.1 mm of "
          "0 (h follows l; a stale h would put the head 109 mm off)");
}

static void test_fault_frozen(void)
{
    hg_board_outputs before;
    int i, latched = 0, events = 0;
    fresh();
    for (i = 0; i < 6; i++)                             /* opposed full volts: the machine strikes */
        in.dac_v[i] = i % 2 ? -10.0 : 10.0;
    for (i = 0; i < 2000 && !out.fault; i++) {
        before = out;
        run(1);
    }
    CHECK(out.fault && out.fault_code < 0 && (out.events & HG_EV_FAULT_LATCHED) && out.fault_cause == HG_FAULT_STEP,
          "opposed full volts: fault latched after %d periods with code %d (%s)", i, out.fault_code,
          hg_strerror(out.fault_code));
    CHECK(memcmp(out.pos, before.pos, sizeof out.pos) == 0 && out.sim_time_s == before.sim_time_s,
          "rollback: the state is the last good one (the failing period left no trace)");
    for (i = 0; i < 50; i++) {
        run(1);
        latched += out.fault;
        events += (out.events & HG_EV_FAULT_LATCHED) != 0;
    }
    CHECK(latched == 50 && events == 0 && memcmp(out.pos, before.pos, sizeof out.pos) == 0 &&
          out.sim_time_s == before.sim_time_s && out.amps_on == 0 && out.volts[0] == 0 && out.current_a[0] == 0,
          "faulted: state frozen for 50 periods, drives off, latched event once");
    for (i = 0; i < 6; i++)
        in.dac_v[i] = 0.0;
    in.reset = 1;
    run(1);
    CHECK(!out.fault && out.fault_code == 0 && (out.events & HG_EV_RESET_DONE), "reset edge clears the fault");
    /* all or nothing: with 8 substeps the failure comes mid-period; the
     * state must be the previous period's end, not a substep's */
    fresh();
    in.params.substeps = 8;
    for (i = 0; i < 6; i++)
        in.dac_v[i] = i % 2 ? -10.0 : 10.0;
    for (i = 0; i < 2000 && !out.fault; i++) {
        before = out;
        run(1);
    }
    CHECK(out.fault && memcmp(out.pos, before.pos, sizeof out.pos) == 0 && out.sim_time_s == before.sim_time_s &&
          fabs(fmod(out.sim_time_s * 1e3 + 0.5, 1.0) - 0.5) < 1e-9,
          "8 substeps, failure mid-period: state rolled back to the period's start (t = %.6f s, a whole period)",
          out.sim_time_s);
}

/* The Hexaglide's bars-broken output (a count among its plant outputs). */
static unsigned bars_broken(void)
{
    int i;
    for (i = 0; i < hg_plant_hexaglide.noutputs; i++)
        if (strcmp(hg_plant_hexaglide.outputs[i].hal_name, "bars-broken") == 0)
            return (unsigned)out.extra[i];
    return 99;
}

static void test_reset_bar_broken(void)
{
    int i;
    unsigned ev;
    fresh();
    in.inject[0] = 1;                 /* joint-0.bar-broken: the Hexaglide's injection 0 */
    ev = run(1);
    CHECK((ev & HG_EV_INJECTED) && out.injected[0] == 1 && bars_broken() == 1,
          "bar-broken 0: bar 0 breaks, event once");
    for (i = 0; i < 5000 && !out.fault; i++)
        run(1);
    CHECK(out.fault && out.fault_code == HG_ERR_OUT_OF_VOLUME, "broken bar: the head leaves the modelled volume, fault %d",
          out.fault_code);
    in.reset = 1;
    ev = run(1);
    CHECK((ev & HG_EV_RESET_REFUSED) && out.reset_refused_channel == 0 && out.reset_refused_injection == 0 &&
              out.fault && bars_broken() == 1,
          "reset while bar-broken 0 is set: refused, naming joint 0; still faulted, bar still broken");
    in.reset = 0;
    in.inject[0] = 0;
    run(1);
    in.reset = 1;
    ev = run(1);
    CHECK((ev & HG_EV_RESET_DONE) && !out.fault && bars_broken() == 0 && fabs(out.pos[0]) < 1e-3,
          "bar-broken cleared, new reset edge: HOME, all bars intact, no fault");
}

static void test_index_latch(void)
{
    int i, k, fired = -1;
    double z = 0;
    fresh();
    for (k = 0; k < 6; k++)
        in.dac_v[k] = 3.0;                              /* up at ~20 mm/s */
    run(100);
    in.index_enable[0] = 1;
    for (i = 0; i < 2000 && fired < 0; i++) {
        run(1);
        if (out.index_latched[0])
            fired = i;
    }
    z = out.motor_pos[0];                               /* the encoder is on the motor */
    {
        /* spec: 1000 counts/mm, index every 10 mm: the counter reads the
         * counts above the index mark just passed (floor of z in counts
         * minus the mark's counts) */
        long long above = (long long)floor(z * 1e6) - (long long)floor(z / 0.010) * 10000;
        CHECK(fired >= 0 && out.index[0] && out.count[0] == above,
              "index-enable: the latch fires at the next index (z %.6f mm), counter %d = counts above the mark %lld",
              z * 1e3, out.count[0], above);
    }
    in.index_enable[0] = 0;                             /* the driver clears index-enable */
    run(1);
    CHECK(out.index_latched[0] == 0, "index-enable cleared: latch handshake done");
    {
        int c0 = out.count[0];
        run(1000);                                      /* passes more index marks, no re-zero */
        CHECK(out.count[0] - c0 > 5000, "not armed: later index marks leave the counter alone (%d -> %d)", c0, out.count[0]);
    }
    {
        int pulses2 = 0, pulses3 = 0;
        in.index_lost[3] = 1;
        for (i = 0; i < 1000; i++) {                    /* ~20 mm more: two marks */
            run(1);
            pulses2 += out.index[2];
            pulses3 += out.index[3];
        }
        CHECK(pulses2 >= 1 && pulses3 == 0, "index-lost 3: no index pulse on channel 3 (%d), channel 2 saw %d",
              pulses3, pulses2);
        in.index_lost[3] = 0;
    }
    in.enc_reset[1] = 1;
    run(1);
    CHECK(out.count[1] == 0 && out.position[1] == 0, "enc-reset: counter 1 reads 0");
    in.enc_reset[1] = 0;
    in.enc_scale[2] = 0;
    run(1);
    CHECK((out.events & HG_EV_ENC_SCALE_BAD) && out.enc_scale_bad == 4 && out.enc_scale[2] == 1.0 && out.param_error,
          "enc-02-scale 0: set to 1.0 as hal_motenc, reported once, param-error");
}

/* enc_scale_odd: a scale that is none of the encoder's counts per mm, per inch (per deg for a rotary
 * axis), nor 1, said once per change. Independent facts: the spec's encoder, counts_per_rev over the
 * lead (10000 / 10 mm: 1000 per mm, 25400 per inch), and the serial plant's rotary axis (16384 counts
 * a motor turn, 90 motor turns an axis turn: 4096 per deg). */
static void test_enc_scale_odd(void)
{
    static const double fits[] = {1000.0, 25400.0, 1.0, 1000.0 * (1.0 + 0.5e-6)};
    char why[HG_BOARD_TEXT_LEN];
    hg_params p;
    unsigned said = 0;
    int i, k;
    hg_params_default(&p);
    fresh();
    run(1);
    CHECK(out.enc_scale_odd == 0 && hg_board_counts_per_unit(&b, 0) == p.counts_per_rev / (p.lead_m * 1000.0),
          "scale 1 (counts): not odd; the encoder gives %.9g counts per mm (%.9g / %.9g mm)",
          hg_board_counts_per_unit(&b, 0), p.counts_per_rev, p.lead_m * 1000.0);
    for (i = 0; i < 4; i++) {
        for (k = 0; k < 6; k++)
            in.enc_scale[k] = fits[i];
        run(1);
        said |= out.enc_scale_odd;
    }
    CHECK(said == 0, "scales 1000 (per mm), 25400 (per inch), 1 and 1000 (1 + 0.5e-6): none odd (0x%x)", said);
    in.enc_scale[3] = 800.0;
    run(1);
    hg_board_describe_enc_scale(&b, 3, 800.0, why);
    CHECK(out.enc_scale_odd == 1u << 3 && strstr(why, "1000 counts per mm (25400 per inch)") &&
              strstr(why, " 1.25 times as long in mm (31.75 in inches)"),
          "enc-03-scale 800: odd, \"%s\"", why);
    run(1);
    CHECK(out.enc_scale_odd == 0, "... said once: not again the next period");
    in.enc_scale[3] = -1000.0;
    run(1);
    hg_board_describe_enc_scale(&b, 3, -1000.0, why);
    CHECK(out.enc_scale_odd == 1u << 3 && strstr(why, "with the other sign (a position loop on it runs away)"),
          "enc-03-scale -1000: odd, \"%s\"", why);
    in.enc_scale[3] = 1000.0;
    *hg_params_at(&p, bit_of("lead")) = 0.005;                 /* a 5 mm lead: 2000 counts per mm */
    for (k = 0; k < (int)(sizeof p / sizeof(double)) && hg_params_at(&p, k); k++)
        in.params.plant.v[k] = *hg_params_at(&p, k);
    run(1);
    CHECK(out.enc_scale_odd == 0x3f && hg_board_counts_per_unit(&b, 0) == 2000.0,
          "lead 5 mm with scale 1000: every channel odd once the encoders rescale (0x%x, %.9g per mm)",
          out.enc_scale_odd, hg_board_counts_per_unit(&b, 0));
    {
        static hg_board s;
        hg_board_params bp;
        hg_param_info e;
        int plant = hg_plant_find("serial"), v = hg_plant_variant(hg_plant_at(plant), "XC"), n;
        int rc = hg_board_init(&s, plant, v, 0), bit = -1;
        double cpr = 0.0, ratio = 0.0;
        hg_board_params_default(plant, v, &bp);
        n = hg_plant_nparams_at(plant, v);
        for (k = 0; k < n; k++)
            if (hg_plant_param_at(plant, v, k, &e) == 0) {
                if (strcmp(e.name, "counts_per_rev_1") == 0)
                    cpr = bp.plant.v[k];
                if (strcmp(e.name, "ratio_1") == 0)
                    ratio = bp.plant.v[k], bit = k;
            }
        CHECK(rc == 0 && bit >= 0 && fabs(hg_board_counts_per_unit(&s, 1) / (cpr * ratio / 360.0) - 1.0) < 1e-12,
              "serial XC, rotary C: %.9g counts per deg (%.9g counts x %.9g turns / 360)", hg_board_counts_per_unit(&s, 1),
              cpr, ratio);
        hg_board_describe_enc_scale(&s, 1, 1000.0, why);
        CHECK(strstr(why, "counts per deg: counts / scale read the travel 4.096 times as long") && !strstr(why, "inch"),
              "... scale 1000: \"%s\"", why);
    }
}

static void test_switches(void)
{
    int k;
    /* spec: home switch on at or above +5 mm, limits at +-250 mm;
     * in-(4k+0..3) = limit-, limit+, home, amp fault */
    fresh();
    in.tripped[4] = HG_SW_MIN;
    in.stuck[5] = HG_SW_HOME;
    in.amp_fail[1] = 1;
    run(1);
    CHECK(out.in[16] == 1 && out.in[17] == 0 && out.in[18] == 0 && out.in[7] == 1 && out.in[3] == 0 &&
          fabs(out.pos[4]) < 1e-4,
          "at HOME: tripped-min 4 reads limit- (in-16), home off, amp-fail 1 on in-07 only");
    for (k = 0; k < 6; k++)
        in.dac_v[k] = 3.0;
    while (out.pos[4] < 0.010 && out.sim_time_s < 2)
        run(1);
    CHECK(out.in[18] == 1 && out.in[22] == 0 && out.pos[5] > 0.005 && out.in[16] == 1,
          "above +5 mm (z %.2f mm): joint 4's home on (in-18), stuck-home 5 keeps reading off (in-22), tripped stays",
          out.pos[5] * 1e3);
    in.stuck[5] = 0;
    in.tripped[4] = 0;
    run(1);
    CHECK(out.in[22] == 1 && out.in[16] == 0, "released: home 5 reads on, limit- 4 off");
}

static void test_substeps(void)
{
    static hg_model m;
    static hg_data d;
    const char *f, *w;
    double v[6] = {1.7, -0.9, 0.4, 1.1, -0.6, 0.8}, q[6], maxd = 0, maxd1 = 0;
    int i, j, k, rc = 0;
    /* independent: hg_step driven directly with P/N */
    hg_params p;
    hg_params_default(&p);
    rc |= hg_model_init(&m, &p, HG_MODEL_REDUCED_CARTESIAN, &f, &w);
    rc |= hg_data_reset(&m, &d);
    for (k = 0; k < 6; k++)
        q[k] = hg_dac_output(v[k]);                     /* the board's 13-bit DAC */
    for (i = 0; i < 250; i++)             /* 8: more than the default train's mode needs (5 with heun) */
        for (j = 0; j < 8; j++)
            rc |= hg_step(&m, &d, q, 0.001 / 8);
    fresh();
    in.params.substeps = 8;
    for (k = 0; k < 6; k++)
        in.dac_v[k] = v[k];
    run(250);
    for (k = 0; k < 6; k++)
        if (fabs(out.pos[k] - d.z_m[k]) > maxd)
            maxd = fabs(out.pos[k] - d.z_m[k]);
    fresh();
    for (k = 0; k < 6; k++)
        in.dac_v[k] = v[k];
    run(250);
    for (k = 0; k < 6; k++)
        if (fabs(out.pos[k] - d.z_m[k]) > maxd1)
            maxd1 = fabs(out.pos[k] - d.z_m[k]);
    CHECK(rc == 0 && maxd < 1e-12 && maxd1 > 1e-9,
          "substeps 8 over 1 ms = 8 hg_steps of 0.125 ms for 0.25 s (max diff %.3g m; the default substeps differ by %.3g m)",
          maxd, maxd1);
}

static void test_bad_period(void)
{
    static const long bad[3] = {0, -1000000, 20000000};
    int i;
    for (i = 0; i < 3; i++) {
        fresh();
        hg_board_step(&b, &in, &out, bad[i]);
        CHECK((out.events & HG_EV_PERIOD_BAD) && (out.events & HG_EV_FAULT_LATCHED) && out.fault_code == HG_ERR_BAD_DT &&
              out.fault_cause == HG_FAULT_PERIOD && out.steps == 0 && out.sim_time_s == 0,
              "period %ld ns: fault -10, nothing integrated", bad[i]);
    }
    hg_board_step(&b, &in, &out, PERIOD);
    CHECK(out.fault && !(out.events & HG_EV_PERIOD_BAD), "then a good period: still latched, reported once");
    in.reset = 1;
    run(2);
    CHECK(!out.fault && out.steps >= 1, "reset: integrating again");
}

static void test_dac_nan_determinism(void)
{
    int k, i;
    unsigned ev;
    fresh();
    in.dac_v[2] = NAN;
    in.dac_v[3] = INFINITY;
    ev = run(3);
    CHECK((ev & HG_EV_DAC_NAN) && out.dac_nan && out.volts[2] == 0 && out.volts[3] == 10.0,
          "DAC NaN: 0 V and flagged; inf clamps to 10 V");
    run(1);
    CHECK(!(out.events & HG_EV_DAC_NAN), "DAC NaN reported once");
    fresh();
    b2 = b;
    in2 = in;
    for (i = 0; i < 300; i++) {
        for (k = 0; k < 6; k++)
            in.dac_v[k] = in2.dac_v[k] = hg_test_uniform(-5, 5);
        hg_board_step(&b, &in, &out, PERIOD);
        hg_board_step(&b2, &in2, &out2, PERIOD);
        if (memcmp(&out, &out2, sizeof out) != 0)
            break;
    }
    CHECK(i == 300, "deterministic: two boards with the same inputs give bit-identical outputs for 300 periods");
}

static void test_check_all_and_format(void)
{
    hg_params p;
    const char *field = 0, *why = 0, *whys[HG_PARAMS_MAX];
    hg_bitset mask;
    char buf[HG_TEXT_VALUE_LEN];
    int i, agree = 1;
    for (i = 0; i < 200; i++) {
        int n, f;
        const hg_param_info *t = hg_params_table(&n);
        hg_params_default(&p);
        f = (int)hg_test_uniform(0, n);
        *hg_params_field(&p, t[f].name) = hg_test_uniform(-2, 2);
        if (hg_params_check(&p, &field, &why) == HG_OK) {
            agree = agree && hg_params_check_all(&p, &mask, whys) == HG_OK && hg_bitset_empty(&mask);
        } else {
            agree = agree && hg_params_check_all(&p, &mask, whys) == HG_ERR_BAD_PARAM &&
                    hg_bitset_has(&mask, bit_of(field)) && whys[bit_of(field)] != 0;
        }
    }
    CHECK(agree, "hg_params_check_all agrees with hg_params_check on 200 random single-field changes");
    hg_text_value(buf, -12.5);
    CHECK(strcmp(buf, "-12.5") == 0, "format -12.5: '%s'", buf);
    hg_text_value(buf, 1000.0);
    CHECK(strcmp(buf, "1000") == 0, "format 1000: '%s'", buf);
    hg_text_value(buf, NAN);
    CHECK(strcmp(buf, "nan") == 0, "format NaN: '%s'", buf);
    hg_text_value(buf, -INFINITY);
    CHECK(strcmp(buf, "-inf") == 0, "format -inf: '%s'", buf);
    hg_text_value(buf, 0.0731);
    CHECK(strcmp(buf, "0.0731") == 0, "format 0.0731: '%s'", buf);
    hg_text_value(buf, 1e-300);
    CHECK(strcmp(buf, "1e-300") == 0, "format 1e-300 (not 0): '%s'", buf);
    hg_text_value(buf, -1.5e-9);
    CHECK(strcmp(buf, "-1.5e-9") == 0, "format -1.5e-9: '%s'", buf);
    hg_text_value(buf, 1e300);
    CHECK(strcmp(buf, "1e+300") == 0, "format 1e300: '%s'", buf);
    hg_text_value(buf, 9.9999999996e20);
    CHECK(strcmp(buf, "1e+21") == 0, "format 9.9999999996e20 rounds to 1e+21: '%s'", buf);
    hg_text_value(buf, 4.9406564584124654e-324);
    CHECK(strcmp(buf, "4.94065646e-324") == 0, "format the smallest denormal: '%s'", buf);
    /* a refused value next to its bound reads as itself (0.0009999 read "0.001" against 0.001) */
    hg_text_value(buf, 0.0009999);
    CHECK(strcmp(buf, "0.0009999") == 0, "format 0.0009999: '%s'", buf);
    hg_text_value(buf, 0.00012345);
    CHECK(strcmp(buf, "0.00012345") == 0, "format 0.00012345: '%s'", buf);
    hg_text_value(buf, 5665.6);
    CHECK(strcmp(buf, "5665.6") == 0, "format 5665.6: '%s'", buf);
    hg_text_value(buf, 999999999.9999999);
    CHECK(strcmp(buf, "1000000000") == 0, "format 999999999.9999999 (9 digits): '%s'", buf);
    {   /* against C's %.9g: the same value to 9 significant digits, over 20 decades */
        int k, agree = 1;
        for (k = 0; k < 20000 && agree; k++) {
            double v = hg_test_uniform(1.0, 10.0) * pow(10.0, floor(hg_test_uniform(-30, 30)));
            double x = k % 2 ? -v : v, err;
            char ref[40];
            hg_text_value(buf, x);
            snprintf(ref, sizeof ref, "%.9g", x);
            err = fabs(strtod(buf, 0) - x);
            /* (above 1e9 every integer digit is written: closer than %.9g, never farther than its 5e-9) */
            agree = err <= fabs(strtod(ref, 0) - x) + 5e-10 * v && err <= 5.5e-9 * v && strlen(buf) < HG_TEXT_VALUE_LEN;
            if (!agree)
                CHECK(0, "format %.17g: '%s', %%.9g '%s'", x, buf, ref);
        }
        CHECK(agree, "hg_text_value reads back within 5.5e-9 relative, at most half a 10th digit farther than "
              "%%.9g, 20,000 values, 1e-30..1e30");
    }
}

/* Count of steps in n with the ADDF_ORDER event. */
static int order_events(int n)
{
    int c = 0;
    while (n-- > 0) {
        hg_board_step(&b, &in, &out, PERIOD);
        c += (out.events & HG_EV_ADDF_ORDER) != 0;
    }
    return c;
}

/* The servo thread's addf order, from the dac-write/encoder-read flags the
 * glue sets: fresh volts every period is quiet; the first period of a
 * thread that starts with dynamics is quiet; stale or missing volts two
 * periods in a row are said once, and again after a reset. */
static void test_addf_order(void)
{
    fresh();
    in.dac_written = 1;
    CHECK(order_events(200) == 0, "dac-write before dynamics every period: no addf-order event");
    fresh();
    in.dac_written = 0;
    run(1);
    in.dac_written = 1;
    CHECK(order_events(200) == 0 && !(out.events & HG_EV_ADDF_ORDER),
          "only the first period without a dac-write (dynamics first in the thread): no event");
    fresh();
    in.dac_written = 1;
    in.dac_stale = 1;
    CHECK(order_events(1) == 0 && order_events(1) == 1 && order_events(200) == 0,
          "dac-write before encoder-read (dynamics between them): one event, at the second period");
    fresh();
    in.dac_written = 0;
    CHECK(order_events(200) == 1, "no dac-write at all: one event");
    in.reset = 1;
    run(1);
    in.reset = 0;
    CHECK(order_events(200) == 1, "... and one again after a reset");
    {   /* dynamics in a thread of its own k times faster than dac-write's: fresh volts every k-th
         * step, held in between, as a DAC holds them: quiet up to k = 100 at 1 ms (100 ms unwritten) */
        int k, i, ev;
        for (k = 2; k <= 200; k += 198) {
            fresh();
            in.dac_stale = 0;
            for (i = 0, ev = 0; i < 400; i++) {
                in.dac_written = i % k == 0;
                ev += order_events(1);
            }
            CHECK(ev == (k > 100), "dynamics %d times as often as dac-write (1 ms steps): %s (%d events)", k,
                  k > 100 ? "one event (100 ms without volts)" : "no event", ev);
        }
        fresh();
        in.dac_written = 0;
        CHECK(order_events(99) == 0 && order_events(1) == 1, "no dac-write at all: the event at 100 ms of steps");
    }
}

/* The tool-path error against closed forms: the commands of the pose the
 * machine holds (0), of every carriage 0.5 mm higher (the tool 0.5 mm
 * higher: 0.5 mm), of the pose tilted by A = 0.2 deg about Op (the tip
 * tool_d below Op swings by 2 tool_d sin(A/2)), and of carriages no pose
 * can take (-1). The commands come from the closed-form inverse kinematics. */
static void test_tool_error(void)
{
    hg_params p;
    double pose[6] = {0, 0, 0, 0, 0, 0}, z[6], want, e;
    const double a = 0.2 * 3.14159265358979323846 / 180;
    int k;
    fresh();
    hg_params_default(&p);
    hg_inverse_kinematics(&p.geo, pose, z);
    for (k = 0; k < 6; k++)
        in.pos_cmd[k] = z[k];
    run(1);
    e = out.tool_error;
    for (k = 0; k < 6; k++)
        in.pos_cmd[k] = out.pos[k] + 0.5e-3;
    hg_board_step(&b, &in, &out, 0);         /* (a bad period: nothing moves, the sensors read again) */
    CHECK(fabs(out.tool_error - 0.5e-3) < 1e-11, "carriages commanded 0.5 mm above where the step left them: "
          "tool-error %.9f mm (HOME's commands, the machine sinking one period: %.6f mm)", 1e3 * out.tool_error,
          1e3 * e);
    memcpy(pose, out.extra, sizeof pose);    /* the pose the step left: commands of it tilted by a */
    pose[3] += a;
    hg_inverse_kinematics(&p.geo, pose, z);
    for (k = 0; k < 6; k++)
        in.pos_cmd[k] = z[k];
    hg_board_step(&b, &in, &out, 0);
    want = 2 * p.tool_d_m * sin(a / 2);
    CHECK(fabs(out.tool_error - want) < 1e-11, "the pose's commands tilted 0.2 deg about X: tool-error %.9f mm "
          "= 2 tool_d sin(A/2) = %.9f mm", 1e3 * out.tool_error, 1e3 * want);
    for (k = 0; k < 6; k++)
        in.pos_cmd[k] = 5.0;
    hg_board_step(&b, &in, &out, 0);
    CHECK(out.tool_error == -1.0, "carriages commanded 5 m high: no pose, tool-error -1 (%g)", out.tool_error);
    CHECK(!(out.events & HG_EV_POS_CMD_BAD), "5 m commands are numbers: no POS_CMD_BAD event");
    in.pos_cmd[2] = NAN;
    hg_board_step(&b, &in, &out, 0);
    CHECK(out.tool_error == -1.0 && (out.events & HG_EV_POS_CMD_BAD) && out.pos_cmd_bad_new == 1u << 2,
          "a NaN command: tool-error -1 (%g), POS_CMD_BAD naming channel 2 (mask %#x)", out.tool_error,
          out.pos_cmd_bad_new);
    hg_board_step(&b, &in, &out, 0);
    CHECK(!(out.events & HG_EV_POS_CMD_BAD), "still NaN: said once");
    in.pos_cmd[2] = 5.0;
    in.pos_cmd[4] = -INFINITY;
    hg_board_step(&b, &in, &out, 0);
    CHECK(out.pos_cmd_bad_new == 1u << 4, "channel 2 a number again, channel 4 -inf: channel 4 said (%#x)",
          out.pos_cmd_bad_new);
}

/* A hard stop moved beneath a carriage: the carriage is then deeper in the
 * stop than its spring represents (HG_THROUGH_STOP_M), and the next period
 * faults naming the carriage and the stop, instead of the spring flinging
 * the carriage back. */
static void test_stop_beneath(void)
{
    int k, i;
    char what[HG_PLANT_TEXT_LEN];
    fresh();
    in.dout_values = 1u << 7;
    for (i = 0; i < 4000 && out.pos[0] < 0.02; i++) {   /* all six up together, under 20 mm */
        for (k = 0; k < 6; k++)
            in.dac_v[k] = 1.5;
        run(1);
    }
    for (k = 0; k < 6; k++)
        in.dac_v[k] = 0.0;
    run(300);
    CHECK(!out.fault && out.pos[0] > 0.015, "the carriages driven up and held at %.1f mm", out.pos[0] * 1e3);
    *hg_test_pv(&in.params, "limit_max") = 0.004;
    *hg_test_pv(&in.params, "stop_max") = 0.005;    /* over 5 mm beneath every carriage */
    *hg_test_pv(&in.params, "home_switch") = 0.002;
    run(1);
    hg_board_plant(&b)->describe(&out.fault_report, 0, what);
    CHECK(out.fault && out.fault_code == HG_ERR_THROUGH_STOP && out.fault_report.kind == HG_GUARD_THROUGH_STOP &&
              out.fault_report.limit == 0.005 && strstr(what, "stop_max"),
          "stop_max moved to 5 mm beneath carriages at %.1f mm: fault %d, \"%s\"", out.pos[0] * 1e3, out.fault_code,
          what);
}

/* An ADC conversion that is not a number (a NaN gain) reads 0 and says so
 * once, until it is a number again; an adc_volts_per_amp not finite or not
 * above 0 is refused once (event, param_error) and the one in force kept. */
static void test_adc_nan(void)
{
    int events = 0, k;
    fresh();
    in.dout_values = 1u << 7;
    in.adc_read = 1;
    for (k = 0; k < 6; k++)
        in.dac_v[k] = 1.0;
    in.adc_gain[0] = NAN;
    for (k = 0; k < 6; k++) {
        run(1);
        events += (out.events & HG_EV_ADC_NAN) && out.adc_nan_new == 1u;
    }
    CHECK(events == 1 && out.adc[0] == 0.0 && isfinite(out.adc[1]) && out.adc[1] != 0.0,
          "adc-00 gain NaN: one event (%d), adc-00 reads 0, adc-01 %g", events, out.adc[1]);
    in.adc_gain[0] = 1.0;
    run(4);
    {
        static const double bad[] = {INFINITY, -INFINITY, NAN, 0.0, -0.5};
        unsigned i;
        for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
            in.adc_volts_per_amp = bad[i];
            for (k = 0, events = 0; k < 6; k++) {
                run(1);
                events += (out.events & HG_EV_ADC_VPA_BAD) != 0;
            }
            CHECK(events == 1 && out.param_error && out.adc_volts_per_amp == HG_BOARD_ADC_VOLTS_PER_AMP &&
                      !(out.events & HG_EV_ADC_NAN) && isfinite(out.adc[1]) && out.adc[1] != 0.0,
                  "adc-volts-per-amp %g refused once (%d events), param-error, 0.5 V/A kept: adc-01 reads %g",
                  bad[i], events, out.adc[1]);
        }
    }
    in.adc_volts_per_amp = 2.0;
    run(1);
    CHECK(out.adc_volts_per_amp == 2.0 && !(out.events & HG_EV_ADC_VPA_BAD), "adc-volts-per-amp 2 taken");
}

/* A geometry change by rounding only (a value shown in mm typed back:
 * 68.254 / 1000 is 1 ulp off the 0.068254 m in force) keeps the running
 * machine where it is; one before the first period is the power-up set,
 * no restart event; a real one restarts at HOME and says so. */
static void test_geometry_rounding(void)
{
    unsigned ev;
    double before;
    int k;
    fresh();
    *hg_test_pv(&in.params, "e") = 70.0 / 1000.0;
    ev = run(1);
    CHECK((ev & HG_EV_PARAM_APPLIED) && (ev & HG_EV_GEOMETRY_RESTART) && out.steps == 1,
          "e 70 mm before the first period: applied, restarted at HOME in the first period (steps %u: the "
          "glue says nothing of the power-up set's)", out.steps);
    fresh();
    in.dout_values = 1u << 7;
    for (k = 0; k < 6; k++)
        in.dac_v[k] = 1.5;
    run(200);
    before = out.pos[0];
    CHECK(68.254 / 1000.0 != *hg_test_pv(&out.params, "e") && before > 1e-3,
          "(68.254 / 1000 is not the default 0.068254 bit for bit; the carriages moved to %.3f mm)", before * 1e3);
    *hg_test_pv(&in.params, "e") = 68.254 / 1000.0;
    ev = run(1);
    CHECK((ev & HG_EV_PARAM_APPLIED) && !(ev & HG_EV_GEOMETRY_RESTART) && out.pos[0] > before &&
              *hg_test_pv(&out.params, "e") == 68.254 / 1000.0 && !out.fault,
          "e 68.254 mm typed back while running: applied without a restart, the carriages go on (%.3f mm)",
          out.pos[0] * 1e3);
    *hg_test_pv(&in.params, "e") = 68.3 / 1000.0;
    ev = run(1);
    CHECK((ev & HG_EV_GEOMETRY_RESTART) && fabs(out.pos[0]) < 1e-4,
          "e 68.3 mm while running: a new shape, restarted at HOME (%.4f mm)", out.pos[0] * 1e3);
}

/* encoder-read's check that the step runs at all: said once after 1 s of
 * thread time with no step, the count starts again at each step. */
static void test_unstepped(void)
{
    hg_board_rate r;
    int i, said = 0, first = -1;
    memset(&r, 0, sizeof r);
    for (i = 1; i <= 3000; i++)
        if (hg_board_rate_read(&r, PERIOD)) {
            said++;
            if (first < 0)
                first = i;
        }
    CHECK(said == 1 && first == 1000, "no step: said once, at the 1000th period of 1 ms (%d times, first %d)", said,
          first);
    hg_board_rate_step(&r);           /* a step ran */
    for (i = 0, said = 0; i < 999; i++)
        said += hg_board_rate_read(&r, PERIOD);
    CHECK(said == 0 && hg_board_rate_read(&r, 0) == 0 && hg_board_rate_read(&r, -5) == 0 &&
              hg_board_rate_read(&r, PERIOD) == 1,
          "after a step: quiet for 999 ms, a period <= 0 counts nothing, said at 1 s");
    memset(&r, 0, sizeof r);
    said = hg_board_rate_read(&r, PERIOD);
    said += hg_board_rate_read(&r, LONG_MAX);   /* a hostile period: no signed overflow (UBSan) */
    CHECK(said == 1 && r.unstepped_ns == HG_BOARD_UNSTEPPED_NS + PERIOD,
          "a period of LONG_MAX ns after 1 ms: said once, the time capped (%lld ns)", r.unstepped_ns);
    /* the mirror: steps without encoder-read (it was never added to a thread) */
    memset(&r, 0, sizeof r);
    for (i = 1, said = 0, first = -1; i <= 3000; i++) {
        hg_board_rate_step(&r);
        if (hg_board_rate_unread(&r, PERIOD)) {
            said++;
            if (first < 0)
                first = i;
        }
    }
    CHECK(said == 1 && first == 1000, "no encoder-read: said once, at the 1000th step of 1 ms (%d times, first %d)",
          said, first);
    hg_board_rate_read(&r, PERIOD);             /* it ran once, then stopped again */
    for (i = 1, said = 0; i <= 1000; i++) {
        hg_board_rate_step(&r);
        said += hg_board_rate_unread(&r, PERIOD);
    }
    CHECK(said == 1, "encoder-read ran once and stopped again: said again after 1 s (%d)", said);
    memset(&r, 0, sizeof r);
    for (i = 1, said = 0; i <= 3000; i++) {     /* a read every 10th period: reads run */
        if (i % 10 == 0)
            hg_board_rate_read(&r, PERIOD);
        hg_board_rate_step(&r);
        said += hg_board_rate_unread(&r, PERIOD) + hg_board_rate_unread(&r, 0) + hg_board_rate_unread(&r, -1);
    }
    CHECK(said == 0, "encoder-read every 10th step (a slower read thread): not said (%d)", said);
}

/* One step of dynamics after `reads` calls of encoder-read (1 ms thread). */
static int step_after_reads(hg_board_rate *r, unsigned reads)
{
    while (reads--)
        hg_board_rate_read(r, PERIOD);
    return hg_board_rate_step(r);
}

/* dynamics' check that its thread is not slower than encoder-read's: said
 * once when a window of 16 steps followed at least 1.5 reads per step; one
 * read per step (or none: a faster plant thread, or a jittery 0/2) is
 * quiet; a jittery 1/3 of a 2 ms plant thread is not; zeroed, said again. */
static void test_slow_step(void)
{
    hg_board_rate r;
    int i, said = 0, at = -1;
    memset(&r, 0, sizeof r);
    for (i = 0; i < 200; i++)           /* LinuxCNC's start: the load's read and the first: 2, then 1 or 0/2 */
        said += step_after_reads(&r, i == 0 ? 2u : i < 100 ? 1u : (unsigned)(i % 2) * 2u);
    CHECK(said == 0, "one read per step, 0/2 alternating, one 2 at the start: quiet");
    for (i = 0, said = 0; i < 100; i++)
        if (step_after_reads(&r, 2)) {
            said++;
            at = i;
        }
    CHECK(said == 1 && at < 32, "two reads per step (dynamics in a 2 ms thread, the servo 1 ms): said once, within "
          "two windows (%d times, at step %d)", said, at);
    memset(&r, 0, sizeof r);
    for (i = 0, said = 0; i < 100; i++)
        said += step_after_reads(&r, i % 2 ? 3u : 1u);
    CHECK(said == 1, "zeroed, the two threads waking in either order (1, 3, 1, 3 reads): said again (%d)", said);
    for (int late = 0; late < 2; late++) {   /* dynamics added 0.3 s or 2 s after encoder-read */
        memset(&r, 0, sizeof r);
        for (i = 0, said = 0; i < 100; i++)
            said += step_after_reads(&r, i == 0 ? (late ? 2000u : 300u) : 1u);
        CHECK(said == 0, "dynamics added %s s late, then one read per step: not a slower thread (said %d)",
              late ? "2" : "0.3", said);
    }
    memset(&r, 0, sizeof r);
    for (i = 0, said = 0; i < 100; i++)     /* a 1.5 s pause of the plant thread alone, then one read per step */
        said += step_after_reads(&r, i == 50 ? 1500u : 1u);
    CHECK(said == 0, "one gap of 1.5 s without a step (said by encoder-read) is not a slower thread (said %d)", said);
    for (i = 0, said = 0; i < 100; i++)     /* and after it the check still works */
        said += step_after_reads(&r, 2);
    CHECK(said == 1, "after the gap, two reads per step: said (%d)", said);
}

/* hg_board_param_value reads a block by refused bit: the plant's
 * parameters, then substeps and integrator. */
static void test_param_value(void)
{
    hg_board_params p;
    memset(&p, 0, sizeof p);
    p.plant.v[3] = 0.25;
    p.substeps = 7;
    p.integrator = 2;
    CHECK(hg_board_param_value(&p, 3) == 0.25 && hg_board_param_value(&p, HG_BOARD_BIT_SUBSTEPS) == 7.0 &&
              hg_board_param_value(&p, HG_BOARD_BIT_INTEGRATOR) == 2.0,
          "parameter 3, substeps and integrator by their bits (0.25, 7, 2)");
}

/* A refusal's reason as the HAL face prints it: HAL names, and the shared
 * bounds in the entry's HAL unit (1e9 m is 1e12 mm; 1e-9 m/rev is 1e-6 mm/rev). */
static void test_hal_reason(void)
{
    hg_params p;
    hg_bitset bad;
    const char *why[HG_PARAMS_MAX];
    char a[256] = "", b[256] = "", c[256] = "", d[256] = "";
    int n;
    const hg_param_info *t = hg_params_table(&n);
    const int lb = hg_param_find(t, n, "lb"), lead = hg_param_find(t, n, "lead"), m = hg_param_find(t, n, "m_head");
    hg_params_default(&p);
    p.geo.lb_m = 2e9;
    p.lead_m = 0.0;
    p.m_head_kg = 0.0;
    CHECK(hg_params_check_all(&p, &bad, why) != 0 && why[lb] == hg_why_max_abs && why[lead] == hg_why_min_positive &&
              why[m] == hg_why_min_positive, "lb 2e9 m, lead 0 and m_head 0 are refused on the shared bounds");
    hg_param_hal_reason(a, sizeof a, why[lb], &t[lb]);
    hg_param_hal_reason(b, sizeof b, why[lead], &t[lead]);
    hg_param_hal_reason(c, sizeof c, why[m], &t[m]);
    CHECK(strcmp(a, "must be finite and below 1e9 in magnitude (SI units; 1000000000000 mm here)") == 0,
          "lb's bound on HAL: 1e9 m is 1e12 mm (%s)", a);
    CHECK(strcmp(b, "must be positive (at least 1e-9 in SI units; 1e-6 mm/rev here)") == 0,
          "lead's bound on HAL: 1e-9 m/rev is 1e-6 mm/rev (%s)", b);
    CHECK(strcmp(c, hg_why_min_positive) == 0, "m_head's unit is kg on both faces: the reason as it is (%s)", c);
    CHECK(hg_param_same(0.0, -0.0) && hg_param_same(NAN, NAN) && hg_param_same(2.5, 2.5) && !hg_param_same(1.0, NAN) &&
              !hg_param_same(NAN, 1.0) && !hg_param_same(1.0, 2.0),
          "a parameter is the same value again when equal (-0 is 0) or both NaN, not otherwise");
    hg_param_hal_reason(d, sizeof d, "must be below k_axial's limit", 0);
    CHECK(strcmp(d, "must be below k-axial's limit") == 0, "another reason: HAL names only (%s)", d);
}

int main(void)
{
    test_estop_loop();
    test_watchdog();
    test_refused_params();
    test_fault_frozen();
    test_reset_bar_broken();
    test_index_latch();
    test_switches();
    test_enc_scale_odd();
    test_substeps();
    test_bad_period();
    test_dac_nan_determinism();
    test_check_all_and_format();
    test_addf_order();
    test_tool_error();
    test_stop_beneath();
    test_adc_nan();
    test_geometry_rounding();
    test_unstepped();
    test_slow_step();
    test_param_value();
    test_hal_reason();
    return hg_test_exit();
}
