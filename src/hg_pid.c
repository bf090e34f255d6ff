/* hg_pid.c - LinuxCNC's pid component (pid.c calc_pid), expression by expression. */
#include "hg_pid.h"

void hg_pid_defaults(hg_pid_gains *g)
{
    *g = (hg_pid_gains){0};
    g->pgain = 1.0;
    g->error_previous_target = 1;
}

void hg_pid_reset(hg_pid_state *s)
{
    *s = (hg_pid_state){0};
}

/* Clamp *v to +-lim when lim is not 0 (pid.c's "if (max != 0.0)" blocks). */
static void limit(double *v, double lim)
{
    if (lim != 0.0) {
        if (*v > lim)
            *v = lim;
        else if (*v < -lim)
            *v = -lim;
    }
}

double hg_pid_calc(const hg_pid_gains *g, hg_pid_state *s, double command, double feedback,
                   int enable, int index_enable, long period_ns)
{
    double tmp1, tmp2, tmp3;
    double periodfp = period_ns * 0.000000001;
    double periodrecip = 1.0 / periodfp;
    int ie_reset = s->prev_ie && !index_enable;   /* index-enable just dropped: counts were reset */

    /* error, against the previous command unless the index just reset the counts */
    if (!ie_reset && g->error_previous_target)
        tmp1 = s->prev_cmd - feedback;
    else
        tmp1 = command - feedback;
    s->error = tmp1;
    limit(&tmp1, g->maxerror);
    /* deadband */
    if (tmp1 > g->deadband)
        tmp1 -= g->deadband;
    else if (tmp1 < -g->deadband)
        tmp1 += g->deadband;
    else
        tmp1 = 0;
    /* integrator, held while the output is clamped in the error's direction */
    if (enable != 0) {
        if ((tmp1 * s->limit_state) <= 0.0)
            s->error_i += tmp1 * periodfp;
        limit(&s->error_i, g->maxerror_i);
    } else {
        s->error_i = 0;
    }
    /* command and feedback rates (the unconnected *-deriv pins) */
    if (!ie_reset) {
        s->cmd_v = (command - s->prev_cmd) * periodrecip;
        s->fb_v = (feedback - s->prev_fb) * periodrecip;
    }
    s->error_d = s->cmd_v - s->fb_v;
    s->prev_error = tmp1;
    limit(&s->error_d, g->maxerror_d);
    tmp2 = s->cmd_d;
    s->cmd_d = s->cmd_v;
    s->prev_ie = index_enable != 0;
    s->prev_cmd = command;
    s->prev_fb = feedback;
    limit(&s->cmd_d, g->maxcmd_d);
    tmp3 = s->cmd_dd;
    s->cmd_dd = (s->cmd_d - tmp2) * periodrecip;
    limit(&s->cmd_dd, g->maxcmd_dd);
    s->cmd_ddd = (s->cmd_dd - tmp3) * periodrecip;
    limit(&s->cmd_ddd, g->maxcmd_ddd);
    /* output */
    if (enable != 0) {
        tmp1 = g->bias + g->pgain * tmp1 + g->igain * s->error_i + g->dgain * s->error_d;
        tmp1 += command * g->ff0 + s->cmd_d * g->ff1 + s->cmd_dd * g->ff2 + s->cmd_ddd * g->ff3;
        if (g->maxoutput != 0.0) {
            if (tmp1 > g->maxoutput) {
                tmp1 = g->maxoutput;
                s->limit_state = 1.0;
            } else if (tmp1 < -g->maxoutput) {
                tmp1 = -g->maxoutput;
                s->limit_state = -1.0;
            } else {
                s->limit_state = 0.0;
            }
        }
    } else {
        tmp1 = 0.0;
        s->limit_state = 0.0;
    }
    s->output = tmp1;
    if (s->limit_state != 0.0) {
        s->saturated = 1;
        s->saturated_s += period_ns * 1e-9;
        if (s->saturated_count != 2147483647)
            s->saturated_count++;
    } else {
        s->saturated = 0;
        s->saturated_s = 0;
        s->saturated_count = 0;
    }
    return tmp1;
}
