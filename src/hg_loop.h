/* hg_loop.h - a machine's servo loops offline (one per channel of the
 * board's plant: the Hexaglide's six, a serial machine's axes): joint
 * commands in, following errors and DAC volts out, one servo period per
 * call, in the order of configs/hexaglide.hal's servo thread:
 *   encoder-read -> motion (command, f-error) -> pid.0..5 [-> biquad.0..5]
 *   -> dac-write -> dynamics
 * with LinuxCNC's pid (hg_pid), optionally its biquad filter per joint
 * between pid.N.output and the DAC (hg_biquad: a notch), and the virtual
 * board's core (the plant), so that what `hexaglide tune` predicts is what
 * LinuxCNC runs.
 *
 * Units: the config's (joint commands and feedback in mm, output in volts,
 * INPUT_SCALE counts per mm). f-error is motion's: the previous period's
 * command minus this period's encoder position.
 * Pure C, no allocation, no stdio; hg_loop is large (it holds the model):
 * allocate it, don't put it on a realtime stack. */
#ifndef HG_LOOP_H
#define HG_LOOP_H

#include "hg_biquad.h"
#include "hg_board.h"
#include "hg_pid.h"

#define HG_LOOP_JOINTS HG_CHANNELS_MAX   /* room for every channel a plant can use */

/* What a config's INI sets per joint, plus the servo period and the plant. */
typedef struct {
    hg_pid_gains pid[HG_LOOP_JOINTS];  /* pid.N pins */
    hg_biquad biquad[HG_LOOP_JOINTS];  /* biquad.N as set at load, between pid.N.output and the
                                          DAC (disabled: out = in, as without one) */
    double input_scale[HG_LOOP_JOINTS];   /* INPUT_SCALE: encoder counts per mm */
    double output_scale[HG_LOOP_JOINTS];  /* OUTPUT_SCALE: DAC gain */
    double output_offset[HG_LOOP_JOINTS]; /* OUTPUT_OFFSET (V) */
    double ferror_limit_mm;            /* stop a run when |f-error| exceeds it (0: never) */
    long period_ns;                    /* servo period */
    int plant;                         /* the board's plant (registry index, hg_plant.h; 0 the Hexaglide) */
    int variant;                       /* its model variant (the Hexaglide's: reduced-cartesian as HAL) */
} hg_loop_config;

/* The closed loop: board (plant) + six PID states + motion's memory. */
typedef struct {
    hg_loop_config cfg;
    hg_board board;                    /* the plant: the virtual board and its machine */
    hg_board_inputs in;                /* what the HAL glue would copy in each period */
    hg_board_outputs out;              /* the board's outputs after the last period */
    hg_pid_state pid[HG_LOOP_JOINTS];
    hg_biquad biquad[HG_LOOP_JOINTS];  /* the running biquad.N (cfg's settings, fresh state) */
    double prev_cmd_mm[HG_LOOP_JOINTS]; /* motion's command of the previous period */
    long periods;                      /* periods run since hg_loop_init */
    int joints;                        /* the plant's channels: one loop each */
} hg_loop;

/* One period's outputs. */
typedef struct {
    double fb_mm[HG_LOOP_JOINTS];      /* encoder position read this period */
    double ferror_mm[HG_LOOP_JOINTS];  /* motion's f-error */
    double output_v[HG_LOOP_JOINTS];   /* pid.N.output */
    double dac_value_v[HG_LOOP_JOINTS]; /* motenc.0.dac-NN-value: pid.N.output through biquad.N */
    double load_mm[HG_LOOP_JOINTS];    /* the load's (carriage's) position after the step: the
                                          tool's side of the drive train */
    double tool_error_mm;              /* the board's tool-error: the tool against this period's
                                          commands after its step (-1: the plant found no pose;
                                          HG_TOOL_ERROR_SKIPPED: the board skipped it) */
} hg_loop_sample;

/* Summary of a run. */
typedef struct {
    double peak_ferror_mm[HG_LOOP_JOINTS]; /* max |f-error| */
    double peak_output_v[HG_LOOP_JOINTS];  /* max |DAC value| (the pid output, through biquad.N) */
    double rms_ferror_mm[HG_LOOP_JOINTS];
    double peak_tool_error_mm;         /* max tool-error (-1 if the plant found no pose in some period,
                                          HG_TOOL_ERROR_SKIPPED if the board skipped it) */
    long periods;                      /* periods run */
    long tripped_at;                   /* first period with |f-error| > ferror_limit_mm, or -1 */
} hg_loop_summary;

/* Per-period traces of a run, n x joints each (row-major); any may be 0. */
typedef struct {
    double *ferror_mm;                 /* motion's f-error */
    double *output_v;                  /* pid.N.output */
    double *load_mm;                   /* the load's position (hg_loop_sample.load_mm) */
} hg_loop_trace;

/* Config with pid.c's load-time gains (hg_pid_defaults: Pgain 1, the rest 0),
 * no biquad (disabled instances: out = in), configs/hexaglide.ini's scales
 * (1000 counts/mm, DAC gain 1, offset 0), a 1 ms period, the Hexaglide with
 * its default model (reduced-cartesian), no trip limit. */
void hg_loop_config_default(hg_loop_config *c);

/* What hg_loop_config_check refused: the first field that fails its rule. */
typedef struct {
    int joint;                 /* the joint (channel) the field belongs to, or -1 (the loop's own) */
    const char *component;     /* "pid" (pid.N's pins), "biquad" (biquad.N's), "loop" (the config's own) */
    const char *field;         /* its name there: the pid pin ("Pgain", "maxoutput"), biquad's "f0",
                                  "Q" or "n0".."d2", or input_scale, output_scale, output_offset,
                                  ferror_limit_mm, period_ns, plant */
    const char *ini_key;       /* its key in a config's [JOINT_N] ("P", "MAX_OUTPUT", "INPUT_SCALE"), or 0 */
    const char *why;           /* what it must be */
    double value;              /* its value */
} hg_loop_check_report;

/* Check c against the rules of the loop, for the joints its plant uses
 * (hg_plant_channels_at): a known plant and model variant; period_ns in
 * (0, HG_PERIOD_MAX_NS]; ferror_limit_mm finite and >= 0; per joint every
 * pid setting (hg_pid_gains_check: gains finite and at most HG_PID_MAX_ABS
 * in magnitude, limits finite and >= 0), INPUT_SCALE finite and at least
 * HG_ENC_SCALE_MIN in magnitude (the board's encoder refuses less),
 * OUTPUT_SCALE and OUTPUT_OFFSET finite, and an enabled biquad.N's settings
 * finite and, for a low pass or notch, accepted by biquad.comp at this
 * period (valid; else LinuxCNC would pass the output unfiltered). 0, or
 * HG_ERR_BAD_DT (period_ns) or HG_ERR_BAD_PARAM, with *r (may be 0) naming
 * the first field that fails. With such a config every pid output is
 * finite for commands hg_pid_input_check takes. */
int hg_loop_config_check(const hg_loop_config *c, hg_loop_check_report *r);

/* Machine at HOME at rest, counters at 0, amplifiers on (E-STOP loop closed),
 * PIDs reset, motion's command 0. p: the board's parameter block (model
 * parameters, substeps, integrator; 0: the spec's defaults as on HAL load).
 * 0, or a negative code (hg_loop_config_check's: HG_ERR_BAD_PARAM / BAD_DT;
 * the board's for its parameters). */
int hg_loop_init(hg_loop *L, const hg_loop_config *c, const hg_board_params *p);

/* One servo period with motion's joint commands cmd_mm[L->joints]; out may be 0.
 * 0, or the board's fault code (latched: the board stays faulted),
 * or for a command hg_pid_input_check refuses (nothing run)
 * HG_ERR_NONFINITE_INPUT (NaN, inf) or HG_ERR_OUT_OF_RANGE (above
 * HG_PID_MAX_ABS in magnitude: pid.c's command derivatives would overflow
 * to inf and then NaN before any f-error limit could trip). */
int hg_loop_step(hg_loop *L, const double *cmd_mm, hg_loop_sample *out);

/* One servo period as LinuxCNC ran it, for a replay of a recorded run:
 * the board inputs are what the caller put in L->in (a record's, say;
 * the pids overwrite dac_v[0..5]), pid.N.enable is enable[N] (motion's
 * joint.N.amp-enable-out), pid.N.index-enable is L->in.index_enable[N]
 * (one signal with the encoder's, as in configs/hexaglide.hal), and the
 * period is period_ns for the pids and the board; the tool-path error's
 * joint commands are L->in.pos_cmd (LinuxCNC's joint.N.pos-cmd: motor-pos-cmd
 * without motor offset and backlash compensation). Otherwise as hg_loop_step,
 * which is this call with every pid enabled, cfg.period_ns and pos_cmd the
 * pids' commands. */
int hg_loop_step_io(hg_loop *L, const double *cmd_mm, const int *enable,
                    long period_ns, hg_loop_sample *out);

/* Run n periods of commands cmd_mm[n][J] (row-major, J = L->joints);
 * per-period f-errors and outputs into ferror_mm[n][J] / output_v[n][J]
 * when not 0; summary over the periods from `from` on. Stops early at a
 * trip (see ferror_limit_mm). 0 or the first step's negative code (a
 * refused command: sum->periods is its row, the rows before it ran). */
int hg_loop_run(hg_loop *L, const double *cmd_mm, long n, long from, double *ferror_mm,
                double *output_v, hg_loop_summary *sum);

/* A run's early stop, for a search that drops a candidate once it cannot
 * win (hexaglide tune): after each scored period, the lower bound
 *   max(peak0, max_k |f-error_k|) + w_rms max(rms0, max_k sqrt(S_k / N))
 *     + w_volts max(0, max(volts0, max_k |v_k|) - volts_free)
 * of the same sum over all the run's scored periods (S_k: f-error_k^2 summed
 * over the scored periods so far, N: the run's scored periods, v_k:
 * pid.N.output, or the DAC value with volts_dac; peak0, rms0, volts0: the
 * terms' values from earlier runs, 0 for none). Every term only grows as
 * periods come, so the whole run's sum is at least the bound at any period:
 * the run stops after the first one at which the bound exceeds `above`. */
typedef struct {
    const unsigned char *scored;       /* per period, nonzero: scored; 0: every period from `from` on */
    double above;                      /* stop once the bound exceeds this */
    double w_rms, w_volts, volts_free;
    double peak0, rms0, volts0;        /* floors of the three terms */
    int volts_dac;                     /* 1: v_k is the DAC value (the summary's), 0: pid.N.output */
} hg_loop_stop;

/* hg_loop_run_traced with an early stop (stop may be 0: none): the bound
 * that passed stop->above in *stop_bound, -1 when the run was not stopped
 * (then the same run and bits as hg_loop_run_traced's). */
int hg_loop_run_stop(hg_loop *L, const double *cmd_mm, long n, long from, const hg_loop_trace *tr,
                     const hg_loop_stop *stop, hg_loop_summary *sum, double *stop_bound);

/* hg_loop_run with the traces tr holds (tr may be 0). */
int hg_loop_run_traced(hg_loop *L, const double *cmd_mm, long n, long from, const hg_loop_trace *tr,
                       hg_loop_summary *sum);

/* sizeof the structs, for bindings that mirror them (tools/hexaglide.py). */
unsigned long hg_loop_sizeof(int which);   /* 0 hg_loop, 1 config, 2 summary, 3 pid gains,
                                             7 hg_board_params, 8 hg_board,
                                             9 hg_board_inputs, 10 hg_board_outputs,
                                             11 hg_pid_state, 13 hg_biquad,
                                             14 hg_loop_check_report, 15 hg_pid_setting; else 0 (the Hexaglide's own
                                             types: hg_hexaglide_sizeof) */

#endif
