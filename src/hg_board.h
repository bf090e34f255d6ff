/* hg_board.h - the virtual MOTENC-100 board with a machine (a plant,
 * hg_plant.h) behind it: one servo period of everything
 * motenc_hexaglide_dyns_virtual does (parameter apply/refuse, reset edge,
 * E-STOP loop, watchdog, amplifier enables, the plant's dynamics with
 * substeps, fault latch with rollback, the plant's fault injections,
 * encoders with index latch, switches with stuck/tripped injection, ADCs,
 * digital I/O), as a pure function of the board's state and one input
 * record. The HAL glue copies pins into hg_board_inputs, calls
 * hg_board_step once per period (from motenc.<board>.dynamics) and copies
 * hg_board_outputs back to pins; `hexaglide sim`/`soak`, the unit tests,
 * the fuzzers, the FMU and `hexaglide replay` drive the same function.
 *
 * The board knows no plant's facts: channels, parameters, positions,
 * switches and faults come through hg_plant. Units: SI and radians inside
 * (a channel's load position in m or rad); the glue converts to mm and
 * degrees for HAL. Deterministic: the same initial board and the same
 * input sequence give bit-identical outputs.
 *
 * Pure C (hg_math.h, hg_string.h): no LinuxCNC include, no malloc, no stdio,
 * bounded loops; hg_board has no pointers (its plant is an index into the
 * registry), so it can live in hal_malloc'd memory; no output is ever NaN
 * or inf. Not thread-safe per board. */
#ifndef HG_BOARD_H
#define HG_BOARD_H

#include "hg_plant.h"
#include "hg_sensors.h"

#define HG_SUBSTEPS_MAX 64u           /* substeps param: 1..HG_SUBSTEPS_MAX */
#define HG_PERIOD_MAX_NS 10000000L    /* the longest period integrated (10 ms) */
#define HG_BOARD_ESTOP_LOOP_OUT 7     /* the E-STOP loop's output at load: out-07, as motenc_io.hal wires it */
#define HG_BOARD_ADC_VOLTS_PER_AMP 0.5 /* the drives' current monitors at load (V/A) */
#define HG_BOARD_UNWRITTEN_NS 100000000LL /* steps' time without a dac-write before ADDF_ORDER (100 ms:
                                         a faster plant thread is fine, and so is a servo thread the
                                         host stalls a few ms on a loaded non-realtime machine) */
#define HG_ENC_SCALE_MIN 1e-20        /* the smallest |enc-CC-scale| taken; a smaller or non-finite one
                                         reads 1.0 (as hal_motenc) and sets enc_scale_bad */
#define HG_ENC_SCALE_TEXT_(x) #x
#define HG_ENC_SCALE_TEXT(x) HG_ENC_SCALE_TEXT_(x)
#define HG_ENC_SCALE_MIN_TEXT HG_ENC_SCALE_TEXT(HG_ENC_SCALE_MIN) /* "1e-20", for messages */
#define HG_ENC_SCALE_FIT 1e-6         /* enc-CC-scale is the channel's counts per unit when within this
                                         fraction of them (1 um in a metre) */

/* Bits of the refused-field set (hg_board_outputs.refused): bit i is entry
 * i of the plant's parameter table (i < HG_PLANT_PARAMS_MAX), plus these two. */
#define HG_BOARD_BIT_SUBSTEPS HG_PLANT_PARAMS_MAX
#define HG_BOARD_BIT_INTEGRATOR (HG_PLANT_PARAMS_MAX + 1)
#define HG_BOARD_WHY_LEN (HG_PLANT_PARAMS_MAX + 2)

/* The parameter block: the plant's parameters and the integration settings.
 * HAL: motenc-hexaglide.<board>.<HAL name of the plant's table> (mm and
 * degrees there, converted with the table's hal_scale), .substeps, .integrator. */
typedef struct {
    hg_plant_params plant;            /* SI units, entry i of the plant's table at plant.v[i] */
    unsigned substeps;                /* integration steps per servo period, 1..HG_SUBSTEPS_MAX */
    unsigned integrator;              /* hg_integrator, 0..HG_INTEGRATOR_COUNT-1 */
} hg_board_params;

/* One servo period's inputs. Which HAL pin or parameter feeds each field
 * (board B; CC two-digit channel; N channel 0..7) - what a recorder captures: */
typedef struct {
    /* dac-write: (motenc.B.dac-CC-value - dac-CC-offset) * dac-CC-gain,
     * exactly as hal_motenc computes it, before any clamp (NaN, inf allowed) */
    double dac_v[HG_BOARD_DACS];
    int dac_written;                  /* 1 if motenc.B.dac-write ran since the last step (watchdog auto reset) */
    int dac_stale;                    /* 1 if motenc.B.encoder-read ran after that dac-write: the volts
                                         are the previous period's (dynamics addf'd before dac-write) */
    unsigned dout_values;             /* bit j = motenc.B.out-JJ (j 0..31) */
    unsigned dout_inverts;            /* bit j = motenc.B.out-JJ-invert */
    int estop_loop_out;               /* motenc-hexaglide.B.estop-loop-out: -1 (no output in the loop)
                                         or 0..31; another value is refused (ESTOP_OUT_BAD), the one in
                                         force stays */
    int estop_button;                 /* motenc-hexaglide.B.estop-button */
    int reset;                        /* motenc-hexaglide.B.reset (rising edge acts) */
    unsigned watchdog_control;        /* motenc.B.watchdog-control */
    int watchdog_reset;               /* motenc.B.watchdog-reset (the glue clears the pin) */
    int index_enable[HG_BOARD_ENCODERS]; /* motenc.B.enc-CC-index-enable: arms the index latch
                                             (after index_latched the driver clears it; if it
                                             stays set, the latch re-arms for the next index) */
    int enc_reset[HG_BOARD_ENCODERS];    /* motenc.B.enc-CC-reset: counter reads 0 while set */
    double enc_scale[HG_BOARD_ENCODERS]; /* motenc.B.enc-CC-scale */
    int adc_read;                     /* 1 if motenc.B.adc-read ran since the last step */
    double adc_gain[HG_BOARD_ADCS];   /* motenc.B.adc-CC-gain */
    double adc_offset[HG_BOARD_ADCS]; /* motenc.B.adc-CC-offset */
    double adc_volts_per_amp;         /* motenc-hexaglide.B.adc-volts-per-amp: finite and > 0, else refused
                                         (ADC_VPA_BAD), the one in force kept */
    /* fault injection, per channel: motenc-hexaglide.B.joint-N.<name> */
    int amp_fail[HG_CHANNELS_MAX];    /* amp-fail */
    unsigned stuck[HG_CHANNELS_MAX];  /* HG_SW_* bits: stuck-min, stuck-max, stuck-home */
    unsigned tripped[HG_CHANNELS_MAX]; /* HG_SW_* bits: tripped-min, tripped-max, tripped-home */
    int index_lost[HG_CHANNELS_MAX];  /* index-lost */
    int enc_glitch[HG_CHANNELS_MAX];  /* enc-glitch: counts added in every step it is non-zero
                                         (the glue clears the pin after the step: added once) */
    unsigned inject[HG_CHANNELS_MAX]; /* bit i: the plant's fault injection i (its table's HAL
                                         name, e.g. the Hexaglide's bar-broken) */
    /* motenc-hexaglide.B.joint-N.pos-cmd: the joint's commanded position (LinuxCNC's
     * joint.N.pos-cmd, without backlash compensation), SI; only for the tool-path error */
    double pos_cmd[HG_CHANNELS_MAX];
    /* the parameter block as HAL shows it (converted to SI: HAL value /
     * hg_param_info.hal_scale), .substeps, .integrator; a change is tried
     * when it differs (bitwise) from the block of the previous step, so a
     * refused block held in the inputs is refused once */
    hg_board_params params;
} hg_board_inputs;

/* Event bits (hg_board_outputs.events): what happened in this step, for
 * the glue's RTAPI messages. Each names its data fields. */
enum {
    HG_EV_PARAM_REFUSED = 1u << 0,    /* refused (every invalid field), param_rc; previous set kept */
    HG_EV_PARAM_APPLIED = 1u << 1,    /* a changed parameter block is in force */
    HG_EV_GEOMETRY_RESTART = 1u << 2, /* with PARAM_APPLIED: the machine's shape changed, restarted at HOME */
    HG_EV_RESET_DONE = 1u << 3,       /* reset edge: HOME at rest, counters 0, fault cleared */
    HG_EV_RESET_REFUSED = 1u << 4,    /* reset edge refused: reset_refused_channel's injection
                                         reset_refused_injection (one that blocks resets) is set */
    HG_EV_FAULT_LATCHED = 1u << 5,    /* fault latched now: fault_code, fault_cause */
    HG_EV_INJECTED = 1u << 6,         /* injected[i]: bit ch = the plant's injection i acted on channel ch */
    HG_EV_PERIOD_BAD = 1u << 7,       /* period_ns outside (0, HG_PERIOD_MAX_NS]: not integrated */
    HG_EV_DAC_NAN = 1u << 8,          /* dac_nan_new: bit ch = channel ch became NaN (outputs 0 V) */
    HG_EV_ENC_SCALE_BAD = 1u << 9,    /* enc_scale_bad: bit ch = scale was 0/NaN, set to 1.0 */
    HG_EV_WATCHDOG_KICKED = 1u << 10, /* watchdog_reset input consumed (glue clears the pin) */
    HG_EV_SUBSTEPS_AUTO = 1u << 11,   /* substeps_run changed: more substeps than asked for, because
                                         stiff_param at the period needs steps of stiff_dt_max_s */
    HG_EV_ADDF_ORDER = 1u << 12,      /* the addf order is wrong: two steps in a row whose volts were
                                         written before the encoders were read (dac_stale), or no
                                         dac_written for HG_BOARD_UNWRITTEN_NS: once per load or reset */
    HG_EV_ADC_NAN = 1u << 13,         /* adc_nan_new: bit ch = channel ch's conversion (current x
                                         adc_volts_per_amp, x gain - offset) became Inf or NaN (reads 0) */
    HG_EV_ESTOP_OUT_BAD = 1u << 14,   /* estop_loop_out was set to neither -1 nor 0..31: refused, the
                                         output in force (estop_loop_out of the outputs) stays in the loop */
    HG_EV_ADC_VPA_BAD = 1u << 15,     /* adc_volts_per_amp was set to a value not finite or not > 0:
                                         refused, the one in force (adc_volts_per_amp of the outputs) kept */
    HG_EV_POS_CMD_BAD = 1u << 16,     /* pos_cmd_bad_new: bit ch = motion's command of channel ch became
                                         NaN or inf (the tool-path error reads -1 while one is) */
    HG_EV_WATCHDOG_EXPIRED = 1u << 17, /* the watchdog expired this period (amplifiers and outputs off until
                                          watchdog_reset kicks it) */
    HG_EV_ALL = (HG_EV_WATCHDOG_EXPIRED << 1) - 1u /* every event bit (a new event goes before this line and here) */
};

/* Why the fault latched (hg_board_outputs.fault_cause). */
typedef enum {
    HG_FAULT_NONE = 0,
    HG_FAULT_STEP = 1,                /* a dynamics (sub)step failed or left a non-finite state */
    HG_FAULT_PERIOD = 2,              /* bad thread period (code HG_ERR_BAD_DT) */
    HG_FAULT_HOME = 3,                /* the machine could not be assembled at HOME on reset */
    HG_FAULT_STIFF = 4                /* the thread's period is too long for the parameters even with
                                         the most substeps (code HG_ERR_STIFF): stiff_param, stiff_dt_max_s */
} hg_fault_cause;

/* One servo period's outputs (all finite). HAL pin of each field: */
typedef struct {
    /* encoder-read: motenc.B.enc-CC-count, -position, -index */
    int count[HG_BOARD_ENCODERS];
    double position[HG_BOARD_ENCODERS];   /* count / scale in force */
    int index[HG_BOARD_ENCODERS];         /* an index pulse passed in this step */
    int index_latched[HG_BOARD_ENCODERS]; /* the armed latch fired: glue clears enc-CC-index-enable */
    double enc_scale[HG_BOARD_ENCODERS];  /* scale in force (1.0 after a refused one): enc-CC-scale */
    /* digital-in-read: motenc.B.in-CC (and -not = !in) */
    unsigned char in[HG_BOARD_INPUTS];
    /* digital-out-write: motenc-hexaglide.B.digital-out-word */
    unsigned dout_word;
    /* misc-update: motenc.B.estop-in (-not = !estop_in) */
    int estop_in;
    /* adc-read: motenc.B.adc-CC-value */
    double adc[HG_BOARD_ADCS];
    /* motenc-hexaglide.B.*: the machine (SI; the glue shows mm, mm/s, deg) */
    int channels;                     /* channels the plant uses */
    unsigned rotary;                  /* bit ch: channel ch is rotary (rad) */
    double pos[HG_CHANNELS_MAX];      /* joint-N.pos: the load (carriage, axis) */
    double vel[HG_CHANNELS_MAX];      /* joint-N.vel */
    double motor_pos[HG_CHANNELS_MAX]; /* joint-N.motor-pos: the encoder's side, as a load position */
    double volts[HG_CHANNELS_MAX];    /* joint-N.volts: what the amplifier got (0 when off) */
    double current_a[HG_CHANNELS_MAX]; /* joint-N.current (0 while faulted) */
    double force[HG_CHANNELS_MAX];    /* joint-N.force (N or N m) */
    double extra[HG_PLANT_EXTRA_MAX]; /* the plant's own outputs (SI; its output table) */
    double tool_error;                /* tool-error: the tool's distance from where pos_cmd puts it
                                         (m), -1 when the plant finds no such place,
                                         HG_TOOL_ERROR_SKIPPED when the board skips it */
    double sim_time_s;                /* sim-time */
    unsigned steps;                   /* steps: servo periods integrated since load/reset */
    int fault;                        /* fault */
    int fault_code;                   /* fault-code (hg_errors.h), 0 if none */
    hg_plant_report fault_report;     /* what the failed step struck (kind 0 otherwise) */
    int amps_on;                      /* amps-on */
    int watchdog_expired;             /* watchdog-expired */
    int param_error;                  /* param-error: the last change was refused (or an enc scale) */
    int dac_nan;                      /* dac-nan: some DAC's product is NaN */
    hg_board_params params;           /* the block in force (the glue shows it on the HAL params) */
    /* events of this step and their data */
    unsigned events;                  /* HG_EV_* bits */
    hg_bitset refused;                /* PARAM_REFUSED: every invalid field (bits as above) */
    int param_rc;                     /* PARAM_REFUSED: HG_ERR_BAD_PARAM, or the code of a set that
                                         passed the checks but could not be built */
    int reset_refused_channel;        /* RESET_REFUSED: first channel whose blocking injection is set */
    int reset_refused_injection;      /* ... and which injection */
    int fault_cause;                  /* FAULT_LATCHED: hg_fault_cause */
    unsigned injected[HG_PLANT_INJECT_MAX]; /* INJECTED */
    unsigned dac_nan_new;             /* DAC_NAN */
    unsigned enc_scale_bad;           /* ENC_SCALE_BAD */
    unsigned enc_scale_odd;           /* bit ch: channel ch's scale, now set or its encoder now changed, is
                                         none of its counts per mm, per inch (linear) or per deg (rotary),
                                         nor 1 (counts): hg_board_describe_enc_scale says it. Not an
                                         event: records and their replay stay as they were */
    unsigned substeps_run;            /* substeps-run: integration steps of the last period, >= substeps */
    int stiff_param;                  /* SUBSTEPS_AUTO, FAULT_STIFF or PARAM_REFUSED with param_rc
                                         HG_ERR_STIFF: table index of the limiting parameter, else -1 */
    double stiff_dt_max_s;            /* ... and the longest step it allows with the scheme */
    double stiff_value;               /* ... the limiting parameter's value (SI) in the set it names */
    int stiff_integrator;             /* ... and that set's integrator (refused or in force) */
    unsigned adc_nan_new;             /* ADC_NAN */
    unsigned pos_cmd_bad_new;         /* POS_CMD_BAD */
    int estop_loop_out;               /* the E-STOP loop's output in force (-1 none; the glue shows it on
                                         estop-loop-out after ESTOP_OUT_BAD) */
    double adc_volts_per_amp;         /* the current monitors' V/A in force (shown after ADC_VPA_BAD) */
} hg_board_outputs;

/* The board: plant, model, state, sensors and latches (no pointers). */
typedef struct {
    int plant;                        /* index of the plant in the registry (hg_plants.c) */
    int variant;                      /* the plant's model variant (hexaglide: the parametrization) */
    int integrator;                   /* in force */
    hg_board_params in_force;         /* the parameter block in force */
    hg_plant_model m;                 /* the model in force */
    hg_plant_model m_new;             /* scratch: a candidate model being built */
    hg_plant_data d;                  /* the machine's state */
    hg_plant_data d_saved;            /* state at the start of the period (rollback) */
    hg_plant_sense sense;             /* what the plant showed after the last step */
    unsigned substeps;                /* in force (asked for) */
    unsigned substeps_run;            /* run: at least substeps, as the period and parameters need */
    long stab_period_ns;              /* the period substeps_run was found for (0: find it again) */
    int stiff_param;                  /* what set substeps_run above substeps (-1: nothing) */
    double stiff_dt_max_s;
    hg_board_params last_in;          /* the input block of the previous step (change detection) */
    hg_encoder enc[HG_BOARD_ENCODERS];
    double enc_scale[HG_BOARD_ENCODERS]; /* in force */
    double enc_scale_in[HG_BOARD_ENCODERS]; /* input of the previous step (change detection) */
    double enc_scale_judged[HG_BOARD_ENCODERS]; /* the scale and counts per unit enc_scale_odd last judged */
    double enc_counts_judged[HG_BOARD_ENCODERS];
    hg_watchdog wd;
    unsigned switches[HG_CHANNELS_MAX]; /* HG_SW_* as the inputs read them */
    double adc_sample_v[HG_BOARD_ADCS]; /* converted, not yet published */
    double adc_value[HG_BOARD_ADCS];  /* published */
    int adc_state;                    /* 0 power-up, 1/2: which group of 4 converts next */
    unsigned dac_nan;                 /* bit ch: channel ch's product is NaN */
    unsigned pos_cmd_bad;             /* bit ch: motion's command of channel ch is NaN or inf */
    unsigned adc_nan;                 /* bit ch: channel ch's conversion is Inf or NaN (reads 0) */
    unsigned adc_sample_bad;          /* bit ch: its sample's current x adc_volts_per_amp was not finite */
    int prev_reset;
    int fault, fault_code;
    hg_plant_report fault_report;     /* what a failed step struck */
    int param_error;
    unsigned steps;                   /* servo periods integrated since load */
    int order_bad_run;                /* consecutive steps with stale volts (ADDF_ORDER) */
    int order_reported;               /* ADDF_ORDER already reported since load or reset */
    double tool_error;                /* the tool-path error after the last step (m, -1: none) */
    int skip_tool_error;              /* set by a caller that never reads tool_error (an offline
                                         search): no forward solve, tool_error HG_TOOL_ERROR_SKIPPED */
    int estop_loop_out;               /* the E-STOP loop's output in force: -1 none, 0..31 */
    int estop_loop_out_in;            /* its input of the previous step (change detection) */
    double adc_volts_per_amp;         /* the current monitors' V/A in force: finite, > 0 */
    double adc_volts_per_amp_in;      /* its input of the previous step (bitwise: a NaN equals itself) */
    long long unwritten_ns;           /* steps' time since the last dac-write (ADDF_ORDER) */
} hg_board;

/* The tool-path error of a board that was told to skip it (hg_board.skip_tool_error). */
#define HG_TOOL_ERROR_SKIPPED (-2.0)

/* The plant of a board (the registry's entry). */
const hg_plant *hg_board_plant(const hg_board *b);

/* The spec's parameter block of plant `plant` (registry index) with model
 * variant `variant`: its defaults, 1 substep, Heun. 0, or
 * HG_ERR_BAD_PARAM for an unknown plant or variant. */
int hg_board_params_default(int plant, int variant, hg_board_params *p);

/* Power-up: plant `plant` (registry index, hg_plants.c) with model
 * variant `variant` and parameter block p (0: the plant's defaults, 1
 * substep, Heun), machine at HOME at rest, counters 0, watchdog disabled,
 * no fault. 0, or HG_ERR_BAD_PARAM (p refused, or an unknown plant or
 * variant; hg_board_params_check names the fields) or another negative code. */
int hg_board_init(hg_board *b, int plant, int variant, const hg_board_params *p);

/* Inputs that leave the board idle: DAC 0 V, outputs off (so the E-STOP
 * loop of out-07 is OPEN: set bit 7 of dout_values, or estop_loop_out -1,
 * to power the amplifiers), estop_loop_out 7, watchdog disabled, enc scale
 * 1, adc gain 1 offset 0, adc-volts-per-amp 0.5, no fault injection, the
 * parameter block in force on b. */
void hg_board_inputs_default(const hg_board *b, hg_board_inputs *in);

/* Outputs of the board as it stands (what the glue shows after load),
 * without stepping: no events. */
void hg_board_peek(const hg_board *b, hg_board_outputs *out);

/* Empty the plant's caches (its data's scratch, zeroed: hg_plant.h's
 * rule), which a board of unknown origin (a deserialized FMU state) must
 * not bring: a cache's fact would be taken unchecked. The next step gives
 * the bits it gives with the caches full. */
void hg_board_forget(hg_board *b);

/* One servo period of period_ns (the HAL thread's period): see the file
 * comment. Order: reset edge, parameter change, watchdog (control, kick,
 * DAC auto reset, advance), amplifier enables, the plant's injections,
 * `substeps` plant steps of period/substeps (all or nothing: a failure
 * restores the state of the period's start and latches the fault),
 * encoders (update, glitch, latch, reset, scale), switches, ADC, digital
 * I/O, E-STOP. Faulted: state frozen, drives off, until a reset edge. */
void hg_board_step(hg_board *b, const hg_board_inputs *in, hg_board_outputs *out, long period_ns);

/* Whether a board of plant and variant built with block p (0: the
 * plant's defaults) integrates it at period_ns: b and in are scratch (the
 * caller's storage: no allocation, no large frame here), left as a board
 * after one idle period and its inputs.
 * 0; the code of hg_board_init when it cannot be built; or HG_ERR_STIFF
 * with out's stiff_* fields set (hg_board_describe_stiffness names the
 * parameter) when no count of substeps up to HG_SUBSTEPS_MAX is enough.
 * The check the CLI and the Python binding make before a run. */
int hg_board_integrable(hg_board *b, hg_board_inputs *in, int plant, int variant, const hg_board_params *p,
                        long period_ns, hg_board_outputs *out);

/* Check a parameter block for b's plant: 0, or HG_ERR_BAD_PARAM with
 * *bad (may be 0) holding every invalid field (bits as refused) and why[i]
 * (may be 0; HG_BOARD_WHY_LEN entries) the reason for bit i (static strings). */
int hg_board_params_check(const hg_board *b, const hg_board_params *p, hg_bitset *bad,
                          const char *why[HG_BOARD_WHY_LEN]);

/* What made the board run more substeps than asked, or refuse a
 * parameter set or fault as too stiff (out's stiff_param, stiff_value,
 * stiff_integrator, stiff_dt_max_s: of the refused set when the event is
 * PARAM_REFUSED, else of the set in force), as one sentence naming the parameter by its
 * HAL name (hal 1, value in HAL units) or spec name (hal 0). Empty when
 * nothing limits. */
#define HG_BOARD_TEXT_LEN 240
/* Simulated time encoder-read may run without a step (the board's dynamics
 * function) before the glue says the step is in no running thread: 1 s,
 * a hundred of the longest period a step integrates (HG_PERIOD_MAX_NS). */
#define HG_BOARD_UNSTEPPED_NS 1000000000LL
#define HG_BOARD_RATE_WINDOW 16u      /* steps per window of hg_board_rate_step */
#define HG_BOARD_RATE_READS_MAX 1000u /* reads counted between two steps (more: a step that never runs) */

/* The glue's watch on the rates of its two functions, encoder-read and
 * dynamics; all 0 at load (zero it to have each said again). */
typedef struct {
    long long unstepped_ns;           /* thread time encoder-read ran since the last step */
    unsigned reads;                   /* encoder-read calls since the last step (up to HG_BOARD_RATE_READS_MAX) */
    unsigned steps, window_reads;     /* steps and their reads in the window so far */
    int stepped;                      /* a step ran since load (the reads before the first are not counted) */
    int said;                         /* the slow step was said */
    long long unread_ns;              /* thread time dynamics ran since the last encoder-read */
} hg_board_rate;

/* Called by the glue's encoder-read with its thread's period: counts the
 * read and adds the period (a period <= 0 adds nothing); 1 exactly once,
 * when the time since the last step first reaches HG_BOARD_UNSTEPPED_NS:
 * the counters stand still because nothing integrates the machine
 * (motenc.N.dynamics never added to a thread). */
int hg_board_rate_read(hg_board_rate *r, long period_ns);

/* Called by the glue's dynamics: the time without a step starts again, and
 * the reads since the previous step join the window (not those before the
 * first step, nor those of a gap that hg_board_rate_read said: dynamics
 * added to its thread late, or a thread stopped, is not a slower thread); 1 exactly once, at
 * the end of a window of HG_BOARD_RATE_WINDOW steps that followed at least
 * 1.5 reads per step: the step's thread is slower than encoder-read's
 * (dynamics in a 2 ms thread beside a 1 ms servo thread), so the counters
 * move only at every n-th read and the PIDs' volts of the periods between
 * are never applied: a loop tuned for the servo period trips on following
 * error. A window, not a single step: the two threads of a non-realtime
 * host wake in either order. */
int hg_board_rate_step(hg_board_rate *r);

/* Called by the glue's dynamics with its thread's period, after
 * hg_board_rate_step: 1 exactly once, when the steps' time since the last
 * encoder-read first reaches HG_BOARD_UNSTEPPED_NS: the machine moves but
 * the encoder and switch pins stand still (motenc.N.encoder-read never
 * added to a thread, the mirror of hg_board_rate_read's case; said again
 * if encoder-read stops once more after running). */
int hg_board_rate_unread(hg_board_rate *r, long period_ns);

/* Channel ch's encoder counts per HAL unit of its travel: per mm (linear)
 * or per deg (rotary), signed as it counts; 0 for a channel not in use. */
double hg_board_counts_per_unit(const hg_board *b, int ch);

/* 1 when scale (counts per machine unit) suits channel ch's encoder: its
 * counts per mm or per inch (linear), per deg (rotary), within
 * HG_ENC_SCALE_FIT, or 1 (counts); 1 for a channel not in use. What
 * enc_scale_odd judges, for a config checked before it runs. */
int hg_board_enc_scale_fits(const hg_board *b, int ch, double scale);

/* Why scale (channel ch's enc-CC-scale, counts per machine unit) is not the
 * encoder's (enc_scale_odd): what the encoder gives per mm and per inch (or
 * per deg), and how counts / scale (LinuxCNC's joint position) read the
 * travel (times as long, or with the other sign: a loop that runs away). */
void hg_board_describe_enc_scale(const hg_board *b, int ch, double scale, char buf[HG_BOARD_TEXT_LEN]);

void hg_board_describe_stiffness(const hg_board *b, const hg_board_outputs *out, long period_ns, int hal,
                                 char buf[HG_BOARD_TEXT_LEN]);

/* What to change after a stiffness refusal (out's stiff_* fields), in the
 * caller's words for the integrator and the period (period 0: the caller's
 * period cannot change): "a softer value, another <integrator> or a
 * shorter <period>" when some step integrates the mode, else "the mode
 * damping or another <integrator> (no step is short enough)". */
void hg_board_stiff_remedy(const hg_board_outputs *out, const char *integrator, const char *period,
                           char buf[HG_BOARD_TEXT_LEN]);

/* Field bit of block p, bits as refused (the plant's parameters in SI, then
 * substeps and integrator), as a double. */
double hg_board_param_value(const hg_board_params *p, int bit);

/* HAL name of refused bit i of b's plant ("c-visc", "substeps", ...), 0 if none. */
const char *hg_board_param_hal_name(const hg_board *b, int bit);

#endif
