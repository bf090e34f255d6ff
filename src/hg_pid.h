/* hg_pid.h - a position PID loop with feed-forward, as LinuxCNC's pid
 * component computes it, for host-side closed-loop runs (build/hexaglide
 * soak). Pure C, no allocation. */
#ifndef HG_PID_H
#define HG_PID_H

typedef struct {
    double p_v_per_m;          /* proportional gain */
    double i_v_per_ms;         /* integral gain (V per m s) */
    double d_v_s_per_m;        /* derivative gain on the error */
    double ff1_v_s_per_m;      /* velocity feed-forward */
    double bias_v;             /* constant output offset */
    double max_out_v;          /* output clamp, > 0 */
    double max_integral_ms;    /* anti-windup clamp of the error integral (m s) */
} hg_pid_gains;

typedef struct {
    double integral_ms;        /* integral of the error */
    double prev_error_m;       /* error of the previous call */
    int primed;                /* prev_error_m is valid */
} hg_pid_state;

/* Reset the state of one loop. */
void hg_pid_reset(hg_pid_state *s);

/* Output volts for command cmd (m), its velocity (m/s) and feedback fb (m)
 * over dt_s; clamped to +-max_out_v; a non-finite input gives 0 V. */
double hg_pid_update(const hg_pid_gains *g, hg_pid_state *s, double cmd_m, double cmd_vel_mps,
                     double fb_m, double dt_s);

#endif
