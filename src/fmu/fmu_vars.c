/* fmu_vars.c - the FMU's variable list (fmu_vars.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fmu_vars.h"
#include "hg_units.h"

#define FNV_BASIS 14695981039346656037ull    /* FNV-1a 64-bit offset basis */

static unsigned long long fnv(unsigned long long h, const void *data, size_t n);

/* One group of variables. */
typedef struct {
    const char *name;                 /* base name: name_k per joint, name + suffix for the head */
    int count;                        /* FMU_JOINTS, 3 or 1 (FMU_G_PARAM: the plant's table) */
    const char *suffix;               /* head groups: one letter per element */
    fmu_type type;
    fmu_causality causality;
    const char *variability;
    const char *unit, *display_unit;
    double display_factor;
    const char *description;
} group_info;

#define J FMU_JOINTS

static const group_info groups[FMU_G_N] = {
    [FMU_G_TIME] = {"time", 1, 0, FMU_FLOAT64, FMU_INDEPENDENT, "continuous", "s", 0, 1,
                    "simulation time: start time + servo periods integrated x period"},
    [FMU_G_MODEL] = {"model", 1, 0, FMU_ENUM, FMU_PARAMETER, "fixed", 0, 0, 1,
                     "parametrization of the multibody dynamics (docs/dynamics.md)"},
    [FMU_G_INTEGRATOR] = {"integrator", 1, 0, FMU_ENUM, FMU_PARAMETER, "fixed", 0, 0, 1,
                          "time integration scheme of each (sub)step"},
    [FMU_G_SUBSTEPS] = {"substeps", 1, 0, FMU_UINT32, FMU_PARAMETER, "fixed", 0, 0, 1,
                        "integration steps per servo period (the board takes more when the parameters need them)"},
    [FMU_G_PERIOD] = {"period", 1, 0, FMU_FLOAT64, FMU_PARAMETER, "fixed", "s", 0, 1,
                      "servo period, whole nanoseconds: the fixed communication step (a step of n periods runs n "
                      "periods with the inputs held)"},
    [FMU_G_ENC_SCALE] = {"enc_scale", 1, 0, FMU_FLOAT64, FMU_PARAMETER, "fixed", 0, 0, 1,
                         "encoder scale, counts per position unit (motenc enc-CC-scale, LinuxCNC's INPUT_SCALE): "
                         "position_k = count_k / enc_scale"},
    [FMU_G_DAC] = {"dac", J, 0, FMU_FLOAT64, FMU_INPUT, "continuous", "V", 0, 1,
                   "DAC command of the amplifier (13 bits, +-10 V; NaN gives 0 V)"},
    [FMU_G_ESTOP] = {"estop", 1, 0, FMU_BOOLEAN, FMU_INPUT, "discrete", 0, 0, 1,
                     "the E-STOP button is pressed: the E-STOP loop opens, amplifiers off"},
    [FMU_G_RESET] = {"reset", 1, 0, FMU_BOOLEAN, FMU_INPUT, "discrete", 0, 0, 1,
                     "board reset: a rising edge puts the machine at HOME at rest, counters 0, fault cleared"},
    [FMU_G_AMP_ENABLE] = {"amp_enable", 1, 0, FMU_BOOLEAN, FMU_INPUT, "discrete", 0, 0, 1,
                          "the digital output in the E-STOP loop (out-07, iocontrol.0.user-enable-out): "
                          "amplifiers powered while TRUE and no E-STOP, watchdog or fault"},
    [FMU_G_COUNT] = {"count", J, 0, FMU_INT32, FMU_OUTPUT, "discrete", 0, 0, 1,
                     "encoder counts (counts_per_rev per motor revolution; 0 at HOME after load; a 32-bit "
                     "counter that wraps, as the board's)"},
    [FMU_G_POSITION] = {"position", J, 0, FMU_FLOAT64, FMU_OUTPUT, "discrete", 0, 0, 1,   /* (whole counts) */
                        "encoder position, count / enc_scale"},
    [FMU_G_INDEX] = {"index", J, 0, FMU_BOOLEAN, FMU_OUTPUT, "discrete", 0, 0, 1,
                     "an encoder index pulse passed in the last communication step (in any of its periods)"},
    [FMU_G_LIMIT_MIN] = {"limit_min", J, 0, FMU_BOOLEAN, FMU_OUTPUT, "discrete", 0, 0, 1,
                         "lower limit switch (carriage at or below limit_min)"},
    [FMU_G_LIMIT_MAX] = {"limit_max", J, 0, FMU_BOOLEAN, FMU_OUTPUT, "discrete", 0, 0, 1,
                         "upper limit switch (carriage at or above limit_max)"},
    [FMU_G_HOME] = {"home", J, 0, FMU_BOOLEAN, FMU_OUTPUT, "discrete", 0, 0, 1,
                    "home switch (carriage at or above home_switch)"},
    [FMU_G_FAULT] = {"fault", 1, 0, FMU_BOOLEAN, FMU_OUTPUT, "discrete", 0, 0, 1,
                     "the board's fault latch: state frozen, drives off until a rising edge of reset"},
    [FMU_G_FAULT_CODE] = {"fault_code", 1, 0, FMU_INT32, FMU_OUTPUT, "discrete", 0, 0, 1,
                          "cause of the fault (src/hg_errors.h; the log says it in words), 0 if none"},
    [FMU_G_AMPS_ON] = {"amps_on", 1, 0, FMU_BOOLEAN, FMU_OUTPUT, "discrete", 0, 0, 1,
                       "the amplifiers are powered"},
    [FMU_G_Z] = {"z", J, 0, FMU_FLOAT64, FMU_OUTPUT, "continuous", "m", "mm", HG_MM_PER_M,
                 "carriage height from HOME, positive up"},
    [FMU_G_ZD] = {"zd", J, 0, FMU_FLOAT64, FMU_OUTPUT, "continuous", "m/s", "mm/s", HG_MM_PER_M,
                  "carriage velocity"},
    [FMU_G_HEAD_POS] = {"head_", 3, "xyz", FMU_FLOAT64, FMU_OUTPUT, "continuous", "m", "mm", HG_MM_PER_M,
                        "head reference point Op in world coordinates"},
    [FMU_G_HEAD_ROT] = {"head_", 3, "abc", FMU_FLOAT64, FMU_OUTPUT, "continuous", "rad", "deg", HG_DEG_PER_RAD,
                        "head orientation, R = Rz(c) Ry(b) Rx(a)"},
    [FMU_G_CURRENT] = {"current", J, 0, FMU_FLOAT64, FMU_OUTPUT, "continuous", "A", 0, 1,
                       "motor winding current (0 while faulted)"},
    [FMU_G_FORCE] = {"force", J, 0, FMU_FLOAT64, FMU_OUTPUT, "continuous", "N", 0, 1,
                     "drive force on the carriage"},
    [FMU_G_PARAM] = {0, 0, 0, FMU_FLOAT64, FMU_PARAMETER, "fixed", 0, 0, 1, 0},
};

static const char *const joint_names[J] = {"z11", "z12", "z21", "z22", "z31", "z32"};

/* Elements of group g. */
static int group_count(fmu_group g)
{
    return g == FMU_G_PARAM ? fmu_plant_param_count() : groups[g].count;
}

unsigned fmu_var_count(void)
{
    unsigned n = 0;
    int g;
    for (g = 0; g < FMU_G_N; g++)
        n += (unsigned)group_count((fmu_group)g);
    return n;
}

unsigned fmu_var_vr(fmu_group g, int k)
{
    unsigned vr = 0;
    int i;
    for (i = 0; i < (int)g; i++)
        vr += (unsigned)group_count((fmu_group)i);
    return vr + (unsigned)k;
}

int fmu_var_get(unsigned vr, fmu_var *v)
{
    const group_info *gi;
    unsigned rest = vr;
    int g, k;
    memset(v, 0, sizeof *v);
    for (g = 0; g < FMU_G_N && rest >= (unsigned)group_count((fmu_group)g); g++)
        rest -= (unsigned)group_count((fmu_group)g);
    if (g == FMU_G_N)
        return -1;
    k = (int)rest;
    gi = &groups[g];
    v->group = (fmu_group)g;
    v->k = k;
    v->type = gi->type;
    v->causality = gi->causality;
    v->variability = gi->variability;
    v->unit = gi->unit;
    v->display_unit = gi->display_unit;
    v->display_factor = gi->display_factor;
    if (g == FMU_G_PARAM) {
        fmu_param p;
        fmu_plant_param(k, &p);
        snprintf(v->name, sizeof v->name, "%s", p.name);
        snprintf(v->description, sizeof v->description, "%s", p.description);
        v->unit = strcmp(p.unit, "1") != 0 ? p.unit : 0;
        v->display_unit = v->unit && strcmp(p.display_unit, p.unit) != 0 ? p.display_unit : 0;
        v->display_factor = p.display_factor;
        v->has_range = 1;
        v->min = p.min;
        v->max = p.max;
        v->quantum = p.quantum;
        return 0;
    }
    if (gi->count == J) {
        snprintf(v->name, sizeof v->name, "%s_%d", gi->name, k);
        snprintf(v->description, sizeof v->description, "%s, joint %d (%s)", gi->description, k, joint_names[k]);
    } else if (gi->suffix) {
        snprintf(v->name, sizeof v->name, "%s%c", gi->name, gi->suffix[k]);
        snprintf(v->description, sizeof v->description, "%s: %c", gi->description, gi->suffix[k] - 'a' + 'A');
    } else {
        snprintf(v->name, sizeof v->name, "%s", gi->name);
        snprintf(v->description, sizeof v->description, "%s", gi->description);
    }
    if (g == FMU_G_MODEL)
        v->declared_type = "Model";
    if (g == FMU_G_INTEGRATOR)
        v->declared_type = "Integrator";
    if (g == FMU_G_SUBSTEPS) {
        v->has_range = 1;
        v->min = 1;
        v->max = (double)fmu_plant_substeps_max();
    }
    if (g == FMU_G_PERIOD) {
        v->has_range = 1;
        v->min = fmu_plant_period_min_s();
        v->max = fmu_plant_period_max_s();
        v->quantum = 1e-9;
    }
    return 0;
}

const char *fmu_num(char buf[32], double x)
{
    int p;
    if (x == floor(x) && fabs(x) < 1e15) {   /* 1000, not 1e+03 */
        snprintf(buf, 32, "%.0f", x);
        return buf;
    }
    for (p = 1; p <= 17; p++) {
        snprintf(buf, 32, "%.*g", p, x);
        if (strtod(buf, 0) == x)
            break;
    }
    return buf;
}

int fmu_var_refuse(const fmu_var *v, double x, const double *vals, char *why, size_t len)
{
    char lo[32], hi[32];
    if (v->causality != FMU_PARAMETER)
        return 0;                     /* inputs take any value (NaN volts give 0 V) */
    if (x != x) {
        snprintf(why, len, "is not a number");
        return -1;
    }
    if (v->declared_type) {
        int i, n = fmu_enum_count(v->declared_type), k = 0;
        if (x >= 0 && x < n && x == floor(x))
            return 0;
        k = snprintf(why, len, "must be ");
        for (i = 0; i < n && k >= 0 && (size_t)k < len; i++)
            k += snprintf(why + k, len - (size_t)k, "%s%d (%s)", i ? (i + 1 < n ? ", " : " or ") : "", i,
                          fmu_enum_item(v->declared_type, i));
        return -1;
    }
    if (v->group == FMU_G_PERIOD)
        return fmu_plant_period_why(x, why, len);
    if (v->group == FMU_G_ENC_SCALE)
        return fmu_plant_enc_scale_why(x, why, len);
    if (v->has_range && (x < v->min || x > v->max || (v->quantum > 0 && x / v->quantum != floor(x / v->quantum)))) {
        const char *core = v->group == FMU_G_PARAM ? fmu_plant_param_why(v->k, &vals[fmu_var_vr(FMU_G_PARAM, 0)], x)
                                                   : 0;
        if (v->type == FMU_UINT32 || v->type == FMU_INT32)
            snprintf(why, len, "must be an integer in %s..%s", fmu_num(lo, v->min), fmu_num(hi, v->max));
        else
            snprintf(why, len, "%s; its range is %s .. %s%s", core ? core : "out of its range", fmu_num(lo, v->min),
                     fmu_num(hi, v->max), v->quantum == 1 ? ", whole numbers" : "");
        return -1;
    }
    return 0;
}

int fmu_vars_start(double *v)
{
    long long substeps, integrator;
    double enc_scale;
    unsigned n = fmu_var_count(), vr;
    int k;
    if (fmu_plant_defaults(&substeps, &integrator, &enc_scale))
        return -1;
    for (vr = 0; vr < n; vr++)
        v[vr] = 0.0;
    v[fmu_var_vr(FMU_G_MODEL, 0)] = fmu_plant_model_default();
    v[fmu_var_vr(FMU_G_INTEGRATOR, 0)] = (double)integrator;
    v[fmu_var_vr(FMU_G_SUBSTEPS, 0)] = (double)substeps;
    v[fmu_var_vr(FMU_G_PERIOD, 0)] = fmu_plant_period_default_s();
    v[fmu_var_vr(FMU_G_ENC_SCALE, 0)] = enc_scale;
    v[fmu_var_vr(FMU_G_AMP_ENABLE, 0)] = 1.0;   /* as hexaglide sim: E-STOP loop closed */
    for (k = 0; k < fmu_plant_param_count(); k++) {
        fmu_param p;
        fmu_plant_param(k, &p);
        v[fmu_var_vr(FMU_G_PARAM, k)] = p.start;
    }
    return 0;
}

unsigned long long fmu_hash(const void *data, size_t n)
{
    return fnv(FNV_BASIS, data, n);
}

/* FNV-1a over n bytes, continuing h. */
static unsigned long long fnv(unsigned long long h, const void *data, size_t n)
{
    const unsigned char *c = data;
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= c[i];
        h *= 1099511628211ull;
    }
    return h;
}

/* FNV-1a of a string and its terminator (0 hashes as ""). */
static unsigned long long fnv_str(unsigned long long h, const char *s)
{
    return fnv(h, s ? s : "", strlen(s ? s : "") + 1);
}

int fmu_vars_token(char token[FMU_TOKEN_LEN])
{
    unsigned n = fmu_var_count(), vr;
    unsigned long long h = FNV_BASIS;
    double *start = calloc(n, sizeof *start);
    if (!start || fmu_vars_start(start)) {
        free(start);
        return -1;
    }
    for (vr = 0; vr < n; vr++) {
        fmu_var v;
        unsigned char t[2];
        if (fmu_var_get(vr, &v))
            break;
        t[0] = (unsigned char)v.type;
        t[1] = (unsigned char)v.causality;
        h = fnv_str(h, v.name);
        h = fnv(h, t, sizeof t);
        h = fnv_str(h, v.variability);
        h = fnv_str(h, v.unit);
        h = fnv(h, &start[vr], sizeof start[vr]);
    }
    free(start);
    snprintf(token, FMU_TOKEN_LEN, "{%s-%016llx}", fmu_plant_name(), h);
    return 0;
}

int fmu_enum_count(const char *declared_type)
{
    if (declared_type && !strcmp(declared_type, "Model"))
        return fmu_plant_model_count();
    if (declared_type && !strcmp(declared_type, "Integrator"))
        return fmu_plant_integrator_count();
    return 0;
}

const char *fmu_enum_item(const char *declared_type, int i)
{
    if (declared_type && !strcmp(declared_type, "Model"))
        return fmu_plant_model_name(i);
    if (declared_type && !strcmp(declared_type, "Integrator"))
        return fmu_plant_integrator_name(i);
    return 0;
}
