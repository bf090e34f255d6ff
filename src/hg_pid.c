/* hg_pid.c - position PID with velocity feed-forward (LinuxCNC pid semantics). */
#include "hg_math.h"
#include "hg_pid.h"

void hg_pid_reset(hg_pid_state *s)
{
    s->integral_ms = 0.0;
    s->prev_error_m = 0.0;
    s->primed = 0;
}

double hg_pid_update(const hg_pid_gains *g, hg_pid_state *s, double cmd_m, double cmd_vel_mps,
                     double fb_m, double dt_s)
{
    double e = cmd_m - fb_m, de, out;
    if (!(isfinite(e) && isfinite(cmd_vel_mps) && isfinite(dt_s) && dt_s > 0.0))
        return 0.0;
    de = s->primed ? (e - s->prev_error_m) / dt_s : 0.0;
    s->prev_error_m = e;
    s->primed = 1;
    s->integral_ms += e * dt_s;
    if (s->integral_ms > g->max_integral_ms)
        s->integral_ms = g->max_integral_ms;
    if (s->integral_ms < -g->max_integral_ms)
        s->integral_ms = -g->max_integral_ms;
    out = g->bias_v + g->p_v_per_m * e + g->i_v_per_ms * s->integral_ms + g->d_v_s_per_m * de +
          g->ff1_v_s_per_m * cmd_vel_mps;
    if (out > g->max_out_v)
        out = g->max_out_v;
    if (out < -g->max_out_v)
        out = -g->max_out_v;
    return out;
}
