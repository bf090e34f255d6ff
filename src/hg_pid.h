/* hg_pid.h - LinuxCNC's `pid` HAL component (src/hal/components/pid.c,
 * LinuxCNC 2.9, commit f1270d6ed7) as a pure-C function: the same terms,
 * limits and update order, and the same floating-point expressions in the
 * same order, so that offline closed loops (build/hexaglide tune, soak)
 * reproduce what LinuxCNC's pid.N.do-pid-calcs computes.
 *
 * Units are the HAL pins' own (here mm and volts: command and feedback in
 * machine units, output in DAC volts); the gains are the pid.N.* pins.
 * Not copied: the relay auto-tuner (tune-mode, never enabled here) and the
 * command-deriv / feedback-deriv input pins (left unconnected in
 * configs/hexaglide.hal, so pid.c differentiates command and feedback itself).
 * Pure C, no allocation, no stdio. */
#ifndef HG_PID_H
#define HG_PID_H

/* The pid.N input pins that are settings: a limit of 0 means "no limit". */
typedef struct {
    double pgain;              /* Pgain: output per unit of error (V/mm) */
    double igain;              /* Igain: per unit of integrated error (V/(mm s)) */
    double dgain;              /* Dgain: per unit of error rate (V/(mm/s)) */
    double bias;               /* bias: constant output (V) */
    double ff0;                /* FF0: per unit of command (V/mm) */
    double ff1;                /* FF1: per unit of command rate (V/(mm/s)) */
    double ff2;                /* FF2: per unit of command 2nd derivative (V/(mm/s^2)) */
    double ff3;                /* FF3: per unit of command 3rd derivative (V/(mm/s^3)) */
    double deadband;           /* deadband: error ignored below this (mm) */
    double maxerror;           /* maxerror: error clamp (mm) */
    double maxerror_i;         /* maxerrorI: integrated error clamp (mm s) */
    double maxerror_d;         /* maxerrorD: error-rate clamp (mm/s) */
    double maxcmd_d;           /* maxcmdD: command-rate clamp (mm/s) */
    double maxcmd_dd;          /* maxcmdDD (mm/s^2) */
    double maxcmd_ddd;         /* maxcmdDDD (mm/s^3) */
    double maxoutput;          /* maxoutput: output clamp (V) */
    int error_previous_target; /* error-previous-target: error = previous command - feedback
                                  (LinuxCNC's default 1, motion's own f-error definition) */
} hg_pid_gains;

/* One loop's memory plus its output pins. */
typedef struct {
    double error_i;            /* errorI: integrated error (mm s) */
    double error_d;            /* errorD: error rate (mm/s) */
    double prev_error;         /* error after limits and deadband, last call (mm) */
    double prev_cmd;           /* command of the last call (mm) */
    double prev_fb;            /* feedback of the last call (mm) */
    double limit_state;        /* +1 / -1 while the output is clamped, else 0 */
    double cmd_d;              /* commandD (mm/s) */
    double cmd_dd;             /* commandDD (mm/s^2) */
    double cmd_ddd;            /* commandDDD (mm/s^3) */
    double cmd_v;              /* the unconnected command-deriv pin (mm/s) */
    double fb_v;               /* the unconnected feedback-deriv pin (mm/s) */
    int prev_ie;               /* index-enable of the last call */
    double error;              /* error pin (mm) */
    double output;             /* output pin (V) */
    int saturated;             /* saturated pin */
    double saturated_s;        /* saturated-s pin (s) */
    int saturated_count;       /* saturated-count pin */
} hg_pid_state;

/* The largest magnitude of a gain (Pgain .. FF3, bias) and of a command or
 * feedback the offline pid takes: below it none of pid.c's products and
 * differences overflows, even at a 1 ns period (|FF3 * commandDDD| < 1e46),
 * so a finite input gives a finite output; no machine needs more (1e9 mm is
 * 1000 km). A larger command overflows: 1e300 mm stepped in one 1 ms period
 * is a commandDDD of 1e309 = inf, and inf * FF3 = 0 is NaN. */
#define HG_PID_MAX_ABS 1e9

/* One setting of pid.N (an hg_pid_gains field): its pin name, its key in a
 * config's [JOINT_N] section (configs/hexaglide.hal setp's it from there),
 * where it is, and which rule it obeys. */
enum {
    HG_PID_GAIN = 0,           /* finite, |value| <= HG_PID_MAX_ABS (any sign) */
    HG_PID_LIMIT = 1,          /* finite and >= 0 (0: no limit, as pid.c) */
    HG_PID_FLAG = 2            /* an int, 0 or not (error_previous_target) */
};
typedef struct {
    const char *pin;           /* pid.N.<pin>: "Pgain", "FF1", "maxoutput" */
    const char *ini_key;       /* its [JOINT_N] key ("P", "FF1", "MAX_OUTPUT"), or 0 (set it by setp) */
    unsigned long offset;      /* offsetof(hg_pid_gains, field) */
    int kind;                  /* HG_PID_GAIN, HG_PID_LIMIT, HG_PID_FLAG */
} hg_pid_setting;

/* Setting i of the table (the order of hg_pid_gains), or 0 past the last. */
const hg_pid_setting *hg_pid_setting_at(int i);

/* The value of setting s in g (a flag as 0.0 or 1.0). */
double hg_pid_setting_value(const hg_pid_gains *g, const hg_pid_setting *s);

/* Check every setting of g against its rule: 0, or HG_ERR_BAD_PARAM with
 * *bad (may be 0) the first setting that fails and *why (may be 0) what it
 * must be (static strings). */
int hg_pid_gains_check(const hg_pid_gains *g, const hg_pid_setting **bad, const char **why);

/* 0 if x may be a pid input (command or feedback): finite and |x| <=
 * HG_PID_MAX_ABS; else HG_ERR_NONFINITE_INPUT or HG_ERR_OUT_OF_RANGE. */
int hg_pid_input_check(double x);

/* The first of v[0..n) that hg_pid_input_check refuses: its index, with its
 * code in *rc (may be 0); or -1 (*rc 0) when every one may be. */
long hg_pid_inputs_check(const double *v, long n, int *rc);

/* The values pid.c gives its pins at load: Pgain 1, everything else 0,
 * error-previous-target 1. */
void hg_pid_defaults(hg_pid_gains *g);

/* The state pid.c starts with at load (all zero). */
void hg_pid_reset(hg_pid_state *s);

/* pid.N.do-pid-calcs for one servo period of period_ns with the given
 * command, feedback (mm), enable and index-enable pins; returns the output
 * pin (also in s->output). Non-finite inputs propagate as in pid.c: the
 * caller checks (hg_loop does: hg_pid_gains_check, hg_pid_input_check). */
double hg_pid_calc(const hg_pid_gains *g, hg_pid_state *s, double command, double feedback,
                   int enable, int index_enable, long period_ns);

#endif
