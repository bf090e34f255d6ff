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

/* The values pid.c gives its pins at load: Pgain 1, everything else 0,
 * error-previous-target 1. */
void hg_pid_defaults(hg_pid_gains *g);

/* The state pid.c starts with at load (all zero). */
void hg_pid_reset(hg_pid_state *s);

/* pid.N.do-pid-calcs for one servo period of period_ns with the given
 * command, feedback (mm), enable and index-enable pins; returns the output
 * pin (also in s->output). Non-finite inputs propagate as in pid.c: the
 * caller checks (hg_loop does). */
double hg_pid_calc(const hg_pid_gains *g, hg_pid_state *s, double command, double feedback,
                   int enable, int index_enable, long period_ns);

#endif
