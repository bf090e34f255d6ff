/* hg_pid.c - LinuxCNC's pid component (pid.c calc_pid), expression by expression. */
#include <stddef.h>
#include "hg_errors.h"
#include "hg_math.h"
#include "hg_string.h"
#include "hg_pid.h"

/* pid.N's settings in hg_pid_gains' order: pin names as pid.c's, INI keys as
 * configs/hexaglide.ini's [JOINT_N] (the hal file setp's pid.N from them). */
static const hg_pid_setting settings[] = {
    {"Pgain", "P", offsetof(hg_pid_gains, pgain), HG_PID_GAIN},
    {"Igain", "I", offsetof(hg_pid_gains, igain), HG_PID_GAIN},
    {"Dgain", "D", offsetof(hg_pid_gains, dgain), HG_PID_GAIN},
    {"bias", "BIAS", offsetof(hg_pid_gains, bias), HG_PID_GAIN},
    {"FF0", "FF0", offsetof(hg_pid_gains, ff0), HG_PID_GAIN},
    {"FF1", "FF1", offsetof(hg_pid_gains, ff1), HG_PID_GAIN},
    {"FF2", "FF2", offsetof(hg_pid_gains, ff2), HG_PID_GAIN},
    {"FF3", "FF3", offsetof(hg_pid_gains, ff3), HG_PID_GAIN},
    {"deadband", "DEADBAND", offsetof(hg_pid_gains, deadband), HG_PID_LIMIT},
    {"maxerror", 0, offsetof(hg_pid_gains, maxerror), HG_PID_LIMIT},
    {"maxerrorI", "MAX_ERROR_I", offsetof(hg_pid_gains, maxerror_i), HG_PID_LIMIT},
    {"maxerrorD", 0, offsetof(hg_pid_gains, maxerror_d), HG_PID_LIMIT},
    {"maxcmdD", 0, offsetof(hg_pid_gains, maxcmd_d), HG_PID_LIMIT},
    {"maxcmdDD", 0, offsetof(hg_pid_gains, maxcmd_dd), HG_PID_LIMIT},
    {"maxcmdDDD", 0, offsetof(hg_pid_gains, maxcmd_ddd), HG_PID_LIMIT},
    {"maxoutput", "MAX_OUTPUT", offsetof(hg_pid_gains, maxoutput), HG_PID_LIMIT},
    {"error-previous-target", 0, offsetof(hg_pid_gains, error_previous_target), HG_PID_FLAG},
};

const hg_pid_setting *hg_pid_setting_at(int i)
{
    return i >= 0 && i < (int)(sizeof settings / sizeof settings[0]) ? &settings[i] : 0;
}

double hg_pid_setting_value(const hg_pid_gains *g, const hg_pid_setting *s)
{
    const char *at = (const char *)g + s->offset;
    double v;
    int flag;
    if (s->kind == HG_PID_FLAG) {
        memcpy(&flag, at, sizeof flag);
        return flag ? 1.0 : 0.0;
    }
    memcpy(&v, at, sizeof v);
    return v;
}

int hg_pid_gains_check(const hg_pid_gains *g, const hg_pid_setting **bad, const char **why)
{
    const hg_pid_setting *s;
    int i;
    for (i = 0; (s = hg_pid_setting_at(i)) != 0; i++) {
        double v = hg_pid_setting_value(g, s);
        const char *w = 0;
        if (s->kind == HG_PID_GAIN && !(fabs(v) <= HG_PID_MAX_ABS))
            w = "must be finite and at most 1e9 in magnitude (beyond it pid.c's products overflow)";
        else if (s->kind == HG_PID_LIMIT && !(isfinite(v) && v >= 0.0))
            w = "must be finite and >= 0 (0: none, as in pid.c: no limit, or no deadband)";
        if (w) {
            if (bad)
                *bad = s;
            if (why)
                *why = w;
            return HG_ERR_BAD_PARAM;
        }
    }
    return HG_OK;
}

int hg_pid_input_check(double x)
{
    if (!isfinite(x))
        return HG_ERR_NONFINITE_INPUT;
    return fabs(x) <= HG_PID_MAX_ABS ? HG_OK : HG_ERR_OUT_OF_RANGE;
}

long hg_pid_inputs_check(const double *v, long n, int *rc)
{
    long i0, i;
    for (i0 = 0; i0 < n; i0 += 256) {  /* a block without a branch per value, then the one refused */
        long end = n - i0 < 256 ? n : i0 + 256;
        int bad = 0;
        for (i = i0; i < end; i++)
            bad |= !(fabs(v[i]) <= HG_PID_MAX_ABS);   /* NaN too */
        for (i = i0; bad && i < end; i++) {
            int r = hg_pid_input_check(v[i]);
            if (r) {
                if (rc)
                    *rc = r;
                return i;
            }
        }
    }
    if (rc)
        *rc = HG_OK;
    return -1;
}

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
