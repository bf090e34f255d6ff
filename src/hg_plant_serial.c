/* hg_plant_serial.c - a serial-axis machine as a plant of the virtual
 * board (hg_plant_serial.h): the axes' parameter table and rules, their
 * stability test systems (hg_stability.h), and one step of each axis with
 * the board's integrator: the drive (hg_drive.h) from the step's start,
 * the load (and, behind a flexible train, the rotor: hg_drivetrain.h)
 * through the scheme's stages with viscous friction, the hard stops
 * (hg_stop.h), the weight and the counterbalance, then sliding and
 * static friction at the velocity level (hg_friction.h), as the
 * Hexaglide's step does for its carriages (hg_integrate.h). */
#include <stddef.h>
#include "hg_math.h"
#include "hg_string.h"
#include "hg_plant_serial.h"
#include "hg_drive.h"
#include "hg_drivetrain.h"
#include "hg_friction.h"
#include "hg_stability.h"
#include "hg_stop.h"
#include "hg_errors.h"
#include "hg_text.h"
#include "hg_units.h"

#define AXES_MAX 8
#define DT_MAX_S 0.01                /* the longest step (the board's longest period) */
#define LETTERS "XYZABCUVW"          /* variant digit d (1..9) is LETTERS[d - 1] */

typedef char hg_serial_table_fits[AXES_MAX * HG_SF_COUNT <= HG_PLANT_PARAMS_MAX ? 1 : -1];

/* ---- the parameter table ---- */

/* The names of field f of axis N, linear [0] and rotary [1]. */
typedef struct {
    const char *spec[2], *hal[2], *ini[2];
} field_names;

#define NM(N, sl, sr, hl, hr, il, ir)                                                              \
    {{sl "_" #N, sr "_" #N}, {"joint-" #N "." hl, "joint-" #N "." hr}, {il "_" #N, ir "_" #N}}
#define SAME(N, s, h, i) NM(N, s, s, h, h, i, i)
#define FIELD_NAMES(N)                                                                             \
    {NM(N, "mass", "inertia", "mass", "inertia", "MASS", "INERTIA"), SAME(N, "g", "gravity", "GRAVITY"), \
     SAME(N, "counterbalance", "counterbalance", "COUNTERBALANCE"),                                  \
     NM(N, "lead", "ratio", "lead", "ratio", "LEAD", "RATIO"), SAME(N, "j_rotor", "j-rotor", "J_ROTOR"), \
     SAME(N, "kt", "kt", "KT"), SAME(N, "r_winding", "r-winding", "R_WINDING"),                      \
     SAME(N, "l_winding", "l-winding", "L_WINDING"), SAME(N, "amp_mode", "amp-mode", "AMP_MODE"),     \
     SAME(N, "ka", "ka", "KA"), SAME(N, "i_max", "i-max", "I_MAX"), SAME(N, "v_bus", "v-bus", "V_BUS"), \
     SAME(N, "v_rated", "v-rated", "V_RATED"), SAME(N, "kp_vel", "kp-vel", "KP_VEL"),                \
     SAME(N, "ki_vel", "ki-vel", "KI_VEL"), SAME(N, "k_axial", "k-axial", "K_AXIAL"),                \
     SAME(N, "c_axial", "c-axial", "C_AXIAL"), SAME(N, "backlash", "backlash", "BACKLASH"),          \
     SAME(N, "c_visc", "c-visc", "C_VISC"), SAME(N, "f_coulomb", "f-coulomb", "F_COULOMB"),          \
     SAME(N, "f_static", "f-static", "F_STATIC"), SAME(N, "v_stribeck", "v-stribeck", "V_STRIBECK"), \
     SAME(N, "stop_min", "stop-min", "STOP_MIN"), SAME(N, "stop_max", "stop-max", "STOP_MAX"),        \
     SAME(N, "k_stop", "k-stop", "K_STOP"), SAME(N, "c_stop", "c-stop", "C_STOP"),                   \
     SAME(N, "limit_min", "limit-min", "LIMIT_MIN"), SAME(N, "limit_max", "limit-max", "LIMIT_MAX"), \
     SAME(N, "home_switch", "home-switch", "HOME_SWITCH"),                                           \
     SAME(N, "counts_per_rev", "counts-per-rev", "COUNTS_PER_REV")}

static const field_names names[AXES_MAX][HG_SF_COUNT] = {
    FIELD_NAMES(0), FIELD_NAMES(1), FIELD_NAMES(2), FIELD_NAMES(3),
    FIELD_NAMES(4), FIELD_NAMES(5), FIELD_NAMES(6), FIELD_NAMES(7),
};

/* Units and meaning of field f, linear [0] and rotary [1] (a rotary axis's
 * unit 0: it has no such field). */
typedef struct {
    const char *unit[2], *hal_unit[2];
    double hal_scale[2];
    const char *what[2];
} field_units;

#define POS_UNITS {"m", "rad"}, {"mm", "deg"}, {HG_MM_PER_M, HG_DEG_PER_RAD}
#define SI1(l, r) {l, r}, {l, r}, {1.0, 1.0}
static const field_units units[HG_SF_COUNT] = {
    {SI1("kg", "kg m^2"), {"moving mass of the load (table, saddle, head)",
                           "moment of inertia of the load (table and part)"}},
    {SI1("m/s^2", 0), {"gravity along -axis: the load's weight mass g pulls toward - (9.81 for a vertical axis, "
                       "+ up; 0 horizontal)", 0}},
    {SI1("N", 0), {"counterbalance (gas spring, counterweight's pull) holding the load toward +", 0}},
    {{"m/rev", "1"}, {"mm/rev", "1"}, {HG_MM_PER_M, 1.0}, {"ball-screw lead: travel per motor revolution",
                                                           "gear ratio: motor revolutions per axis revolution"}},
    {SI1("kg m^2", "kg m^2"), {"rotor + screw inertia", "rotor + worm inertia"}},
    {SI1("N m/A", "N m/A"), {"motor torque constant (= back-EMF constant, V s/rad)",
                             "motor torque constant (= back-EMF constant, V s/rad)"}},
    {SI1("ohm", "ohm"), {"motor winding resistance", "motor winding resistance"}},
    {SI1("H", "H"), {"motor winding inductance", "motor winding inductance"}},
    {SI1("1", "1"), {"amplifier mode: 0 torque (current), 1 velocity", "amplifier mode: 0 torque (current), 1 velocity"}},
    {SI1("A/V", "A/V"), {"torque mode: amplifier gain", "torque mode: amplifier gain"}},
    {SI1("A", "A"), {"amplifier current limit", "amplifier current limit"}},
    {SI1("V", "V"), {"amplifier supply (bus) voltage", "amplifier supply (bus) voltage"}},
    {{"m/s", "rad/s"}, {"mm/s", "deg/s"}, {HG_MM_PER_M, HG_DEG_PER_RAD},
     {"velocity mode: axis speed at +10 V", "velocity mode: axis speed at +10 V"}},
    {SI1("A s/m", "A s/rad"), {"velocity mode: velocity-loop proportional gain", "velocity mode: velocity-loop proportional gain"}},
    {SI1("A/m", "A/rad"), {"velocity mode: velocity-loop integral gain", "velocity mode: velocity-loop integral gain"}},
    {SI1("N/m", "N m/rad"), {"drive train: axial stiffness motor to load (0: rigid)",
                             "drive train: torsional stiffness motor to load (0: rigid)"}},
    {SI1("N s/m", "N m s/rad"), {"drive train: damping", "drive train: damping"}},
    {POS_UNITS, {"drive train: total lost motion", "drive train: total lost motion"}},
    {SI1("N s/m", "N m s/rad"), {"viscous friction", "viscous friction"}},
    {SI1("N", "N m"), {"sliding (Coulomb) friction", "sliding (Coulomb) friction"}},
    {SI1("N", "N m"), {"breakaway (static) friction", "breakaway (static) friction"}},
    {{"m/s", "rad/s"}, {"mm/s", "deg/s"}, {HG_MM_PER_M, HG_DEG_PER_RAD},
     {"Stribeck speed (sliding friction falls from f_static to f_coulomb)",
      "Stribeck speed (sliding friction falls from f_static to f_coulomb)"}},
    {POS_UNITS, {"hard stop, - end", "hard stop, - end"}},
    {POS_UNITS, {"hard stop, + end", "hard stop, + end"}},
    {SI1("N/m", "N m/rad"), {"hard-stop stiffness", "hard-stop stiffness"}},
    {SI1("N s/m", "N m s/rad"), {"hard-stop damping", "hard-stop damping"}},
    {POS_UNITS, {"limit switch, - end (trips at or below)", "limit switch, - end (trips at or below)"}},
    {POS_UNITS, {"limit switch, + end (trips at or above)", "limit switch, + end (trips at or above)"}},
    {POS_UNITS, {"home switch: on at or above", "home switch: on at or above"}},
    {SI1("1/rev", "1/rev"), {"encoder counts per motor revolution (negative: counts down as the axis moves +)",
                             "encoder counts per motor revolution (negative: counts down as the axis moves +)"}},
};

/* ---- variants: the axes string as decimal digits, axis 0 the lowest ---- */

static int axes_of(int variant)
{
    int n = 0;
    while (variant > 0 && n < AXES_MAX + 1) {
        if (variant % 10 == 0)
            return 0;
        variant /= 10;
        n++;
    }
    return variant == 0 && n <= AXES_MAX ? n : 0;
}

/* Letter code (1..9) of axis k. */
static int code_of(int variant, int k)
{
    while (k-- > 0)
        variant /= 10;
    return variant % 10;
}

/* 1 if axis k of variant is rotary (A, B, C). */
static int rotary_axis(int variant, int k)
{
    int c = code_of(variant, k);
    return c >= 4 && c <= 6;
}

/* The variant of an axes string, in upper or lower case as trivkins' coordinates= takes it; -1 if none. */
static int variant_of(const char *name)
{
    int k, v = 0, scale = 1;
    for (k = 0; name[k]; k++) {
        const char up = name[k] >= 'a' && name[k] <= 'z' ? (char)(name[k] - 'a' + 'A') : name[k];
        int c;
        for (c = 0; LETTERS[c] && LETTERS[c] != up; c++)
            ;
        if (!LETTERS[c] || k >= AXES_MAX)
            return -1;
        v += (c + 1) * scale;
        scale *= 10;
    }
    return k ? v : -1;
}

/* hg_plant.variant_name: the axes' letters, one per channel ("XYZ"). */
static int variant_name(int variant, char *buf, int len)
{
    int k, n = axes_of(variant);
    if (!n || len < n + 1)
        return -1;
    for (k = 0; k < n; k++)
        buf[k] = LETTERS[code_of(variant, k) - 1];
    buf[n] = '\0';
    return 0;
}

/* hg_plant.channels: one channel per axis. */
static int channels(int variant)
{
    return axes_of(variant);
}

/* 1 if an axis of kind rot has field f. */
static int has_field(int rot, int f)
{
    return !(rot && (f == HG_SF_G || f == HG_SF_COUNTERBALANCE));
}

int hg_serial_entry(int variant, int axis, int field)
{
    int k, f, i = 0, n = axes_of(variant);
    if (axis < 0 || axis >= n || field < 0 || field >= HG_SF_COUNT || !has_field(rotary_axis(variant, axis), field))
        return -1;
    for (k = 0; k < axis; k++)
        i += rotary_axis(variant, k) ? HG_SF_COUNT - 2 : HG_SF_COUNT;
    for (f = 0; f < field; f++)
        i += has_field(rotary_axis(variant, axis), f);
    return i;
}

/* Axis and field of table entry i: 0, or -1 past the table. */
static int field_of(int variant, int i, int *axis, int *field)
{
    int k, f, n = axes_of(variant);
    for (k = 0; k < n; k++) {
        int rot = rotary_axis(variant, k);
        for (f = 0; f < HG_SF_COUNT; f++) {
            if (!has_field(rot, f))
                continue;
            if (i-- == 0) {
                *axis = k;
                *field = f;
                return 0;
            }
        }
    }
    return -1;
}

/* hg_plant.nparams: every axis's fields (a rotary axis has no g and no counterbalance). */
static int nparams(int variant)
{
    int k, n = 0;
    for (k = 0; k < axes_of(variant); k++)
        n += rotary_axis(variant, k) ? HG_SF_COUNT - 2 : HG_SF_COUNT;
    return n;
}

/* hg_plant.param: entry i, axis k's field f, with its axis-numbered names and units. */
static int param(int variant, int i, hg_param_info *out)
{
    int k, f, r;
    if (field_of(variant, i, &k, &f))
        return -1;
    r = rotary_axis(variant, k);
    out->name = names[k][f].spec[r];
    out->unit = units[f].unit[r];
    out->what = units[f].what[r];
    out->offset = (unsigned long)i * sizeof(double);
    out->hal_name = names[k][f].hal[r];
    out->hal_unit = units[f].hal_unit[r];
    out->hal_scale = units[f].hal_scale[r];
    out->ini_key = names[k][f].ini[r];
    return 0;
}

/* Field f of axis k in v (0 for one the axis lacks). */
static double get(int variant, const hg_plant_params *v, int k, int f)
{
    int i = hg_serial_entry(variant, k, f);
    return i >= 0 ? v->v[i] : 0.0;
}

/* Set field f of axis k in v (nothing for one the axis lacks). */
static void set(int variant, hg_plant_params *v, int k, int f, double x)
{
    int i = hg_serial_entry(variant, k, f);
    if (i >= 0)
        v->v[i] = x;
}

/* ---- defaults: a small servo mill (docs/serial.md) ---- */

/* The defaults of one linear axis: a 5 TPI (5.08 mm) ball screw behind a
 * 0.2 N m/A servo motor with a velocity-mode amplifier (10 V = 2 in/s),
 * 4096-line encoder (16384 counts/rev), preloaded nut; mass by letter
 * (X the table, Y table and saddle, Z the head, vertical, 80 % of its
 * weight on a counterbalance). Travel from the power-up position: -510
 * mm to the stop, +20 mm to the other, home switch at +6.35 mm. */
static void linear_defaults(double *a, int letter)
{
    static const double mass[9] = {80, 150, 50, 0, 0, 0, 80, 150, 50};
    a[HG_SF_MASS] = mass[letter - 1];
    a[HG_SF_G] = letter == 3 || letter == 9 ? 9.81 : 0.0;
    a[HG_SF_COUNTERBALANCE] = 0.8 * a[HG_SF_MASS] * a[HG_SF_G];
    a[HG_SF_LEAD] = 0.00508;
    a[HG_SF_J_ROTOR] = 1.0e-4;
    a[HG_SF_V_RATED] = 0.0508;
    a[HG_SF_KP_VEL] = 635.0;
    a[HG_SF_KI_VEL] = 1.0e5;
    a[HG_SF_K_AXIAL] = 1.5e8;
    a[HG_SF_C_AXIAL] = 5300.0;
    a[HG_SF_C_VISC] = 1000.0;
    a[HG_SF_F_COULOMB] = 150.0;
    a[HG_SF_F_STATIC] = 200.0;
    a[HG_SF_V_STRIBECK] = 0.001;
    a[HG_SF_STOP_MIN] = -0.510;
    a[HG_SF_STOP_MAX] = 0.020;
    a[HG_SF_K_STOP] = 5e7;
    a[HG_SF_LIMIT_MIN] = -0.500;
    a[HG_SF_LIMIT_MAX] = 0.0127;
    a[HG_SF_HOME_SWITCH] = 0.00635;
}

/* A rotary table's: 90:1 worm, rigid, +-10 turns between its stops. */
static void rotary_defaults(double *a)
{
    a[HG_SF_MASS] = 0.05;
    a[HG_SF_LEAD] = 90.0;
    a[HG_SF_J_ROTOR] = 1.0e-4;
    a[HG_SF_V_RATED] = 200.0 / HG_DEG_PER_RAD;
    a[HG_SF_KP_VEL] = 30.0;
    a[HG_SF_KI_VEL] = 4700.0;
    a[HG_SF_C_VISC] = 2.0;
    a[HG_SF_F_COULOMB] = 3.0;
    a[HG_SF_F_STATIC] = 4.0;
    a[HG_SF_V_STRIBECK] = 1.0 / HG_DEG_PER_RAD;
    a[HG_SF_STOP_MIN] = -3600.0 / HG_DEG_PER_RAD;
    a[HG_SF_STOP_MAX] = 3600.0 / HG_DEG_PER_RAD;
    a[HG_SF_K_STOP] = 1e6;
    a[HG_SF_LIMIT_MIN] = -3590.0 / HG_DEG_PER_RAD;
    a[HG_SF_LIMIT_MAX] = 3590.0 / HG_DEG_PER_RAD;
    a[HG_SF_HOME_SWITCH] = 2.0 / HG_DEG_PER_RAD;
}

/* hg_plant.defaults: each axis as linear_defaults or rotary_defaults makes it. */
static void defaults(int variant, hg_plant_params *v)
{
    int k, f;
    memset(v, 0, sizeof *v);
    for (k = 0; k < axes_of(variant); k++) {
        int r = rotary_axis(variant, k);
        double a[HG_SF_COUNT];
        memset(a, 0, sizeof a);
        a[HG_SF_KT] = 0.2;
        a[HG_SF_R_WINDING] = 1.0;
        a[HG_SF_L_WINDING] = 0.0025;
        a[HG_SF_AMP_MODE] = 1.0;
        a[HG_SF_KA] = 2.0;
        a[HG_SF_I_MAX] = 20.0;
        a[HG_SF_V_BUS] = 90.0;
        a[HG_SF_C_STOP] = 2e4;
        a[HG_SF_COUNTS_PER_REV] = 16384.0;
        if (r)
            rotary_defaults(a);
        else
            linear_defaults(a, code_of(variant, k));
        if (r)
            a[HG_SF_C_STOP] = 1e3;
        for (f = 0; f < HG_SF_COUNT; f++)
            set(variant, v, k, f, a[f]);
    }
}

/* No earlier record format carried this plant. */
static void legacy(int format, int variant, hg_plant_params *v)
{
    (void)format;
    (void)variant;
    (void)v;
}

/* ---- rules ---- */

/* A collector of failed rules by table entry: the first one, every
 * entry's bit and its first reason. */
typedef struct {
    int variant, first;
    const char *first_why;
    hg_bitset *bad;
    const char **why;
} rules;

/* Record that field f of axis k failed for reason. */
static void refuse(rules *r, int k, int f, const char *reason)
{
    int i = hg_serial_entry(r->variant, k, f);
    if (i < 0)
        return;
    if (r->first < 0) {
        r->first = i;
        r->first_why = reason;
    }
    if (!hg_bitset_has(r->bad, i)) {
        hg_bitset_set(r->bad, i);
        if (r->why)
            r->why[i] = reason;
    }
}

/* 1 if field f of axis k failed a rule already. */
static int failed(const rules *r, int k, int f)
{
    return hg_bitset_has(r->bad, hg_serial_entry(r->variant, k, f));
}

/* Travel per motor revolution of axis k (m, or rad: 2 pi / ratio). */
static double lead_of(int variant, const hg_plant_params *v, int k)
{
    double x = get(variant, v, k, HG_SF_LEAD);
    return rotary_axis(variant, k) ? 2.0 * HG_PI / x : x;
}

/* Every rule of axis k. */
static void axis_rules(rules *r, const hg_plant_params *v, int k)
{
    static const int positive[] = {HG_SF_MASS, HG_SF_LEAD, HG_SF_KT, HG_SF_R_WINDING, HG_SF_L_WINDING, HG_SF_KA,
                                   HG_SF_I_MAX, HG_SF_V_BUS, HG_SF_V_RATED, HG_SF_V_STRIBECK, HG_SF_K_STOP};
    static const int nonneg[] = {HG_SF_J_ROTOR, HG_SF_KP_VEL, HG_SF_KI_VEL, HG_SF_K_AXIAL, HG_SF_C_AXIAL,
                                 HG_SF_BACKLASH, HG_SF_C_VISC, HG_SF_F_COULOMB, HG_SF_F_STATIC, HG_SF_C_STOP};
    const int var = r->variant, rot = rotary_axis(var, k);
    double a[HG_SF_COUNT], cpr;
    unsigned i;
    int f;
    for (f = 0; f < HG_SF_COUNT; f++) {
        a[f] = get(var, v, k, f);
        if (has_field(rot, f) && !(fabs(a[f]) < HG_PARAM_MAX_ABS))
            refuse(r, k, f, hg_why_max_abs);
    }
    for (i = 0; i < sizeof positive / sizeof positive[0]; i++)
        if (!(a[positive[i]] >= HG_PARAM_MIN_POSITIVE))
            refuse(r, k, positive[i], hg_why_min_positive);
    for (i = 0; i < sizeof nonneg / sizeof nonneg[0]; i++)
        if (!(a[nonneg[i]] >= 0.0))
            refuse(r, k, nonneg[i], "must be finite and >= 0");
    if (!(a[HG_SF_AMP_MODE] == 0.0 || a[HG_SF_AMP_MODE] == 1.0))
        refuse(r, k, HG_SF_AMP_MODE, "must be 0 (torque mode) or 1 (velocity mode)");
    if (!failed(r, k, HG_SF_F_STATIC) && !failed(r, k, HG_SF_F_COULOMB) && !(a[HG_SF_F_STATIC] >= a[HG_SF_F_COULOMB]))
        refuse(r, k, HG_SF_F_STATIC, "must be at least f_coulomb (breakaway below the sliding force)");
    if (!(a[HG_SF_STOP_MIN] < 0.0))
        refuse(r, k, HG_SF_STOP_MIN, "must lie below 0, the power-up position (the machine would start in its stop)");
    if (!(a[HG_SF_STOP_MAX] > 0.0))
        refuse(r, k, HG_SF_STOP_MAX, "must lie above 0, the power-up position (the machine would start in its stop)");
    if (!failed(r, k, HG_SF_STOP_MIN) && !failed(r, k, HG_SF_LIMIT_MIN) && !(a[HG_SF_STOP_MIN] < a[HG_SF_LIMIT_MIN]))
        refuse(r, k, HG_SF_STOP_MIN, "must lie below limit_min (the switch trips before the stop)");
    if (!failed(r, k, HG_SF_LIMIT_MIN) && !failed(r, k, HG_SF_LIMIT_MAX) && !(a[HG_SF_LIMIT_MIN] < a[HG_SF_LIMIT_MAX]))
        refuse(r, k, HG_SF_LIMIT_MAX, "must lie above limit_min");
    if (!failed(r, k, HG_SF_STOP_MAX) && !failed(r, k, HG_SF_LIMIT_MAX) && !(a[HG_SF_STOP_MAX] > a[HG_SF_LIMIT_MAX]))
        refuse(r, k, HG_SF_STOP_MAX, "must lie above limit_max (the switch trips before the stop)");
    if (!failed(r, k, HG_SF_LIMIT_MIN) && !failed(r, k, HG_SF_LIMIT_MAX) && !failed(r, k, HG_SF_HOME_SWITCH) &&
        !(a[HG_SF_HOME_SWITCH] > a[HG_SF_LIMIT_MIN] && a[HG_SF_HOME_SWITCH] < a[HG_SF_LIMIT_MAX]))
        refuse(r, k, HG_SF_HOME_SWITCH, "must lie between the limit switches");
    cpr = a[HG_SF_COUNTS_PER_REV];
    if (!(fabs(cpr) >= 1.0 && fabs(cpr) < HG_PARAM_MAX_ABS && floor(cpr) == cpr))
        refuse(r, k, HG_SF_COUNTS_PER_REV, "must be a whole number of counts, at least 1 in magnitude (negative: "
                                           "the encoder counts down as the axis moves +)");
    if (!failed(r, k, HG_SF_BACKLASH) && !failed(r, k, HG_SF_K_AXIAL) && a[HG_SF_BACKLASH] > 0.0 &&
        !(a[HG_SF_K_AXIAL] > 0.0))
        refuse(r, k, HG_SF_BACKLASH, "needs the flexible drive train: set k_axial > 0 (k_axial 0 is the rigid "
                                     "train, without lost motion)");
    if (!failed(r, k, HG_SF_BACKLASH) && !failed(r, k, HG_SF_STOP_MIN) && !failed(r, k, HG_SF_STOP_MAX) &&
        !(a[HG_SF_BACKLASH] < a[HG_SF_STOP_MAX] - a[HG_SF_STOP_MIN]))
        refuse(r, k, HG_SF_BACKLASH, "must be shorter than the stroke between the hard stops");
    if (!failed(r, k, HG_SF_K_AXIAL) && !failed(r, k, HG_SF_J_ROTOR) && a[HG_SF_K_AXIAL] > 0.0 &&
        !(a[HG_SF_J_ROTOR] >= HG_PARAM_MIN_POSITIVE))
        refuse(r, k, HG_SF_J_ROTOR, "must be positive behind a flexible train (k_axial > 0): the rotor is a body "
                                    "of its own");
    /* the bus must drive, at standstill, the current that holds the load's weight */
    if (!rot && !failed(r, k, HG_SF_V_BUS) && !failed(r, k, HG_SF_R_WINDING) && !failed(r, k, HG_SF_KT) &&
        !failed(r, k, HG_SF_LEAD) && !failed(r, k, HG_SF_MASS) && !failed(r, k, HG_SF_G) &&
        !failed(r, k, HG_SF_COUNTERBALANCE) &&
        !(a[HG_SF_V_BUS] > a[HG_SF_R_WINDING] * fabs(a[HG_SF_MASS] * a[HG_SF_G] - a[HG_SF_COUNTERBALANCE]) /
                               (a[HG_SF_KT] * 2.0 * HG_PI / lead_of(var, v, k))))
        refuse(r, k, HG_SF_V_BUS, "must exceed r_winding times the current that holds the load (|mass g - "
                                  "counterbalance| / (kt 2 pi / lead)): the drive could not hold it");
}

/* Every rule of every axis: 0 or HG_ERR_BAD_PARAM. */
static int check_rules(int variant, const hg_plant_params *v, rules *r)
{
    int k;
    for (k = 0; k < axes_of(variant); k++)
        axis_rules(r, v, k);
    return r->first >= 0 ? HG_ERR_BAD_PARAM : HG_OK;
}

/* hg_plant.check: every axis's rules, each bad field named. */
static int check(int variant, const hg_plant_params *v, hg_bitset *bad, const char *why[HG_PLANT_PARAMS_MAX])
{
    hg_bitset s;
    rules r;
    int i;
    hg_bitset_clear(&s);
    for (i = 0; why && i < nparams(variant); i++)
        why[i] = 0;
    r.variant = variant;
    r.first = -1;
    r.first_why = 0;
    r.bad = bad ? bad : &s;
    r.why = why;
    if (bad)
        hg_bitset_clear(bad);
    return check_rules(variant, v, &r);
}

/* ---- model and data ---- */

typedef struct {
    hg_plant_params p;                /* the block it was built from */
    int variant, n;                   /* axes */
    unsigned rotary, flexible;        /* bit k: axis k rotary; its train has a spring */
    int integrator;
    hg_drive_channel drive[AXES_MAX];
    hg_friction_channel fric[AXES_MAX];
    hg_drivetrain_channel train[AXES_MAX];
    double mass[AXES_MAX], rotor[AXES_MAX], rigid[AXES_MAX]; /* load, reflected rotor, both */
    double weight[AXES_MAX];          /* mass g - counterbalance: the constant force toward - */
    double c_visc[AXES_MAX], k_stop[AXES_MAX], c_stop[AXES_MAX], stop_min[AXES_MAX], stop_max[AXES_MAX];
    double limit_min[AXES_MAX], limit_max[AXES_MAX], home[AXES_MAX];
    double lead[AXES_MAX];            /* travel per motor revolution (m or rad) */
    double cpr[AXES_MAX];             /* encoder counts per motor revolution, signed */
    double through[AXES_MAX];         /* beyond a stop by this much: through it */
} serial_model;

typedef struct {
    double t_s;
    double x[AXES_MAX], v[AXES_MAX];  /* the loads */
    double xr[AXES_MAX], vr[AXES_MAX]; /* the rotors as load positions (= x, v behind a rigid train) */
    double current_a[AXES_MAX], vloop_int[AXES_MAX];
    double fric_n[AXES_MAX];          /* sliding or static friction over the last step (mean) */
    double force_n[AXES_MAX];         /* net force on the load over the last step but the weight and
                                         the counterbalance (drive or train, friction, stops) */
    unsigned stuck;                   /* bit k: static friction holds load k */
    hg_drive_memo memo;               /* scratch: a cache valid in any copy */
} serial_data;

#define STATE_BYTES offsetof(serial_data, memo)

typedef char hg_serial_fits[(sizeof(serial_model) <= sizeof(hg_plant_model) &&
                             sizeof(serial_data) <= sizeof(hg_plant_data) && AXES_MAX <= HG_CHANNELS_MAX &&
                             AXES_MAX <= HG_DRIVE_MAX && AXES_MAX <= HG_STAB_AXES_MAX) ? 1 : -1];

/* The model and data laid over the board's storage. */
static const serial_model *model_of(const hg_plant_model *m) { return (const serial_model *)m->store; }
static serial_data *data_of(hg_plant_data *d) { return (serial_data *)d->store; }
static const serial_data *cdata_of(const hg_plant_data *d) { return (const serial_data *)d->store; }

/* The drive of axis k of v. */
static void drive_params(int variant, const hg_plant_params *v, int k, hg_drive_params *dp)
{
    dp->kt_nm_per_a = get(variant, v, k, HG_SF_KT);
    dp->lead_m = lead_of(variant, v, k);
    dp->r_winding_ohm = get(variant, v, k, HG_SF_R_WINDING);
    dp->l_winding_h = get(variant, v, k, HG_SF_L_WINDING);
    dp->amp_mode = get(variant, v, k, HG_SF_AMP_MODE);
    dp->ka_a_per_v = get(variant, v, k, HG_SF_KA);
    dp->i_max_a = get(variant, v, k, HG_SF_I_MAX);
    dp->v_bus_v = get(variant, v, k, HG_SF_V_BUS);
    dp->v_rated_mps = get(variant, v, k, HG_SF_V_RATED);
    dp->kp_vel_as_per_m = get(variant, v, k, HG_SF_KP_VEL);
    dp->ki_vel_a_per_m = get(variant, v, k, HG_SF_KI_VEL);
}

/* hg_plant.build: per axis the drive, the train, the friction and the stops of the set, and the scheme. */
static int build(hg_plant_model *pm, const hg_plant_params *v, int variant, int integrator, const char **field,
                 const char **why)
{
    serial_model *m = (serial_model *)pm->store;
    hg_bitset bad;
    rules r;
    int k;
    r.variant = variant;
    r.first = -1;
    r.first_why = 0;
    r.bad = &bad;
    r.why = 0;
    hg_bitset_clear(&bad);
    if (!axes_of(variant)) {
        *field = "model";
        *why = "not an axes string (1 to 8 letters of XYZABCUVW)";
        return HG_ERR_BAD_PARAM;
    }
    if (check_rules(variant, v, &r)) {
        hg_param_info e;
        param(variant, r.first, &e);
        *field = e.name;
        *why = r.first_why;
        return HG_ERR_BAD_PARAM;
    }
    if (integrator < 0 || integrator >= HG_INTEGRATOR_COUNT) {
        *field = "integrator";
        *why = "must be 0 (improved-euler), 1 (heun) or 2 (rk4)";
        return HG_ERR_BAD_PARAM;
    }
    memset(m, 0, sizeof *m);
    m->p = *v;
    m->variant = variant;
    m->n = axes_of(variant);
    m->integrator = integrator;
    for (k = 0; k < m->n; k++) {
        hg_drive_params dp;
        double k_screw;
        drive_params(variant, v, k, &dp);
        hg_drive_init(&m->drive[k], &dp);
        m->rotary |= (unsigned)rotary_axis(variant, k) << k;
        m->fric[k].f_static_n = get(variant, v, k, HG_SF_F_STATIC);
        m->fric[k].f_coulomb_n = get(variant, v, k, HG_SF_F_COULOMB);
        m->fric[k].v_stribeck_mps = get(variant, v, k, HG_SF_V_STRIBECK);
        m->train[k].k_axial = get(variant, v, k, HG_SF_K_AXIAL);
        m->train[k].c_axial = get(variant, v, k, HG_SF_C_AXIAL);
        m->train[k].backlash = get(variant, v, k, HG_SF_BACKLASH);
        m->flexible |= (unsigned)!hg_drivetrain_rigid(&m->train[k]) << k;
        m->lead[k] = dp.lead_m;
        k_screw = 2.0 * HG_PI / m->lead[k];
        m->mass[k] = get(variant, v, k, HG_SF_MASS);
        m->rotor[k] = get(variant, v, k, HG_SF_J_ROTOR) * k_screw * k_screw;
        m->rigid[k] = m->mass[k] + m->rotor[k];
        m->weight[k] = m->mass[k] * get(variant, v, k, HG_SF_G) - get(variant, v, k, HG_SF_COUNTERBALANCE);
        m->c_visc[k] = get(variant, v, k, HG_SF_C_VISC);
        m->k_stop[k] = get(variant, v, k, HG_SF_K_STOP);
        m->c_stop[k] = get(variant, v, k, HG_SF_C_STOP);
        m->stop_min[k] = get(variant, v, k, HG_SF_STOP_MIN);
        m->stop_max[k] = get(variant, v, k, HG_SF_STOP_MAX);
        m->limit_min[k] = get(variant, v, k, HG_SF_LIMIT_MIN);
        m->limit_max[k] = get(variant, v, k, HG_SF_LIMIT_MAX);
        m->home[k] = get(variant, v, k, HG_SF_HOME_SWITCH);
        m->cpr[k] = get(variant, v, k, HG_SF_COUNTS_PER_REV);
        m->through[k] = rotary_axis(variant, k) ? HG_SERIAL_THROUGH_STOP_RAD : HG_THROUGH_STOP_M;
    }
    return HG_OK;
}

/* hg_plant.params_of: the set the model was built from. */
static void params_of(const hg_plant_model *m, hg_plant_params *v)
{
    *v = model_of(m)->p;
}

/* hg_plant.reset: every axis at rest at its zero, static friction holding it. */
static int reset(const hg_plant_model *pm, hg_plant_data *pd)
{
    const serial_model *m = model_of(pm);
    serial_data *d = data_of(pd);
    memset(d, 0, sizeof *d);
    d->stuck = (1u << m->n) - 1u;      /* at rest: static friction holds every load */
    return HG_OK;
}

/* A new lead, ratio or encoder rescales the encoders; nothing restarts. */
static unsigned change(int variant, const hg_plant_params *a, const hg_plant_params *b)
{
    int k;
    for (k = 0; k < axes_of(variant); k++)
        if (get(variant, a, k, HG_SF_LEAD) != get(variant, b, k, HG_SF_LEAD) ||
            get(variant, a, k, HG_SF_COUNTS_PER_REV) != get(variant, b, k, HG_SF_COUNTS_PER_REV))
            return HG_PLANT_CHANGE_RESCALE;
    return 0;
}

/* Axis k of v as the stability check's axis. */
static void stability_axis(int variant, const hg_plant_params *v, int k, hg_stability_axis *a)
{
    static const int fields[HG_STAB_NAMES] = {HG_SF_C_VISC, HG_SF_K_STOP, HG_SF_C_STOP, HG_SF_R_WINDING,
                                              HG_SF_KP_VEL, HG_SF_KI_VEL, HG_SF_K_AXIAL, HG_SF_C_AXIAL,
                                              HG_SF_BACKLASH};
    const double ks = 2.0 * HG_PI / lead_of(variant, v, k);
    const int rot = rotary_axis(variant, k);
    int i;
    a->m_load = get(variant, v, k, HG_SF_MASS);
    a->m_rotor = get(variant, v, k, HG_SF_J_ROTOR) * ks * ks;
    a->m_rigid = a->m_load + a->m_rotor;
    a->c_visc = get(variant, v, k, HG_SF_C_VISC);
    a->k_stop = get(variant, v, k, HG_SF_K_STOP);
    a->c_stop = get(variant, v, k, HG_SF_C_STOP);
    a->force_per_amp = get(variant, v, k, HG_SF_KT) * ks;
    a->r_winding = get(variant, v, k, HG_SF_R_WINDING);
    a->l_winding = get(variant, v, k, HG_SF_L_WINDING);
    a->velocity_mode = get(variant, v, k, HG_SF_AMP_MODE) == 1.0;
    a->kp_vel = get(variant, v, k, HG_SF_KP_VEL);
    a->ki_vel = get(variant, v, k, HG_SF_KI_VEL);
    a->k_axial = get(variant, v, k, HG_SF_K_AXIAL);
    a->c_axial = get(variant, v, k, HG_SF_C_AXIAL);
    a->backlash = get(variant, v, k, HG_SF_BACKLASH);
    a->f_max = get(variant, v, k, HG_SF_I_MAX) * a->force_per_amp;
    for (i = 0; i < HG_STAB_NAMES; i++)
        a->name[i] = names[k][fields[i]].spec[rot];
}

/* hg_plant.stability: the substeps the set needs at the period (hg_stability, one test system per axis), naming the limiting parameter. */
static int stability(int variant, const hg_plant_params *v, int integrator, double period_s,
                     unsigned substeps_min, unsigned substeps_max, unsigned *substeps, int *limit,
                     double *dt_max_s)
{
    hg_stability_axis ax[AXES_MAX];
    hg_stability st;
    int k, n = axes_of(variant), rc;
    for (k = 0; k < n; k++)
        stability_axis(variant, v, k, &ax[k]);
    rc = hg_stability_check_axes(ax, n, (hg_integrator)integrator, period_s, substeps_min, substeps_max, &st);
    *substeps = st.substeps;
    *limit = hg_plant_param_find(&hg_plant_serial, variant, st.param);
    *dt_max_s = st.dt_max_s;
    return rc;
}

/* No fault injections of its own (the board's are enough). */
static void inject(const hg_plant_model *m, hg_plant_data *d, const unsigned in[HG_CHANNELS_MAX],
                   unsigned acted[HG_PLANT_INJECT_MAX])
{
    (void)m;
    (void)d;
    (void)in;
    (void)acted;
}

/* ---- one step ---- */

/* Viscous friction and the stops on load k at (x, v). */
static double passive(const serial_model *m, int k, double x, double v)
{
    return -m->c_visc[k] * v + hg_stop_force(x, v, m->stop_min[k], m->stop_max[k], m->k_stop[k], m->c_stop[k]);
}

/* One axis's stage state and its accelerations. */
typedef struct {
    double x, v, xr, vr;              /* load and rotor */
    double a, ar;                     /* their accelerations */
} stage;

/* The accelerations of stage s of axis k: the load under the held force
 * (the drive's when rigid, the friction expected), the passive forces,
 * the weight and (flexible) the train; the rotor under the motor and the
 * train. The train's force at the stage into *train. */
static void accel(const serial_model *m, int k, int flex, double hold, double motor, stage *s, double *train)
{
    double t = flex ? hg_drivetrain_force(&m->train[k], s->xr - s->x, s->vr - s->v) : 0.0;
    s->a = (hold + passive(m, k, s->x, s->v) + t - m->weight[k]) / (flex ? m->mass[k] : m->rigid[k]);
    s->ar = flex ? (motor - t) / m->rotor[k] : s->a;
    *train = t;
}

/* The scheme's step of axis k over dt with the forces held (stage 0 at
 * the start, y0): the state at the end into *y1. */
static void integrate(const serial_model *m, int k, int flex, double hold, double motor, double dt,
                      const stage *y0, stage *y1)
{
    const double *cs, *bs;
    int ns = hg_scheme_tableau((hg_integrator)m->integrator, &cs, &bs), i;
    stage s = *y0;
    double sq, sv, rq, rv, t;
    if (ns == 0) {                     /* improved Euler: q1 = q0 + q0' dt + q0'' dt^2/2, q1' = q0' + q0'' dt */
        y1->x = y0->x + y0->v * dt + 0.5 * y0->a * dt * dt;
        y1->v = y0->v + y0->a * dt;
        y1->xr = y0->xr + y0->vr * dt + 0.5 * y0->ar * dt * dt;
        y1->vr = y0->vr + y0->ar * dt;
        return;
    }
    sq = bs[0] * s.v, sv = bs[0] * s.a, rq = bs[0] * s.vr, rv = bs[0] * s.ar;
    for (i = 1; i < ns; i++) {         /* stage i from y0 + c_i dt k_(i-1) */
        double h = cs[i] * dt;
        s.x = y0->x + h * s.v;
        s.v = y0->v + h * s.a;
        s.xr = y0->xr + h * s.vr;
        s.vr = y0->vr + h * s.ar;
        accel(m, k, flex, hold, motor, &s, &t);
        sq += bs[i] * s.v, sv += bs[i] * s.a, rq += bs[i] * s.vr, rv += bs[i] * s.ar;
    }
    y1->x = y0->x + dt * sq;
    y1->v = y0->v + dt * sv;
    y1->xr = y0->xr + dt * rq;
    y1->vr = y0->vr + dt * rv;
}

/* Axis k over dt with the motor's force: 0, or a code with *r naming what
 * was struck (kind 1: through a linear axis's stop, 3: a rotary axis's,
 * 2: non-finite state). */
static int axis_step(const serial_model *m, serial_data *d, int k, double motor, double dt, hg_plant_report *r)
{
    const int flex = (m->flexible >> k) & 1u, fric = hg_friction_any(&m->fric[k], 1);
    const double est = fric ? d->fric_n[k] : 0.0;     /* the friction the stages hold: the last step's */
    const double hold = flex ? est : motor + est;
    stage y0 = {d->x[k], d->v[k], d->xr[k], d->vr[k], 0.0, 0.0}, y1;
    double t0, f0 = passive(m, k, y0.x, y0.v);
    const unsigned bit = 1u << k, rest = (d->stuck >> k) & 1u;   /* stuck at the start */
    accel(m, k, flex, hold, motor, &y0, &t0);
    integrate(m, k, flex, hold, motor, dt, &y0, &y1);
    d->fric_n[k] = 0.0;
    d->stuck &= ~bit;
    if (fric) {                        /* sliding and static friction at the velocity level */
        const double w = 1.0 / (flex ? m->mass[k] : m->rigid[k]), expected = est * dt;
        double vstar = y1.v - w * expected, e;
        hg_friction_out fo;
        int rc = hg_friction_solve(&m->fric[k], 1, &w, &vstar, &y0.v, rest, dt, &fo);
        if (rc)
            return rc;
        e = fo.impulse[0] - expected;  /* the stages held `expected`: correct by the rest */
        y1.v += w * e;
        y1.x += 0.5 * dt * w * e;
        d->fric_n[k] = fo.impulse[0] / dt;
        if (fo.stuck) {                /* where it stays: where it was, or where it stopped */
            y1.x = y0.x + (rest ? 0.0 : 0.5 * y0.v * fo.stop[0] * dt);
            y1.v = 0.0;
            d->stuck |= bit;
        }
    }
    if (!flex)
        y1.xr = y1.x, y1.vr = y1.v;    /* the rotor moves with its load */
    if (!(isfinite(y1.x) && isfinite(y1.v) && isfinite(y1.xr) && isfinite(y1.vr) && isfinite(d->fric_n[k]))) {
        r->kind = 2, r->channel = k, r->other = -1, r->value = y1.x, r->limit = 0.0;
        return HG_ERR_STATE_NONFINITE;
    }
    if (y1.x < m->stop_min[k] - m->through[k] || y1.x > m->stop_max[k] + m->through[k]) {
        r->kind = (m->rotary >> k) & 1u ? 3 : 1, r->channel = k, r->other = -1, r->value = y1.x;
        r->limit = y1.x < m->stop_min[k] ? m->stop_min[k] : m->stop_max[k];
        return HG_ERR_THROUGH_STOP;
    }
    d->force_n[k] = (flex ? t0 : motor) + f0 + d->fric_n[k];
    d->x[k] = y1.x, d->v[k] = y1.v, d->xr[k] = y1.xr, d->vr[k] = y1.vr;
    return HG_OK;
}

/* hg_plant.step: one (sub)step: the drives' currents under the volts, then each axis (axis_step). */
static int step(const hg_plant_model *pm, hg_plant_data *pd, const double volts[HG_CHANNELS_MAX],
                unsigned enabled, double dt_s, hg_plant_report *rep)
{
    const serial_model *m = model_of(pm);
    serial_data *d = data_of(pd);
    double speed[AXES_MAX], z0[AXES_MAX], z1[AXES_MAX];
    hg_plant_report unused = {0};
    hg_drive_out drv;
    int k, rc;
    hg_plant_report *r = rep ? rep : &unused;
    if (!(isfinite(dt_s) && dt_s > 0.0 && dt_s <= DT_MAX_S))
        return HG_ERR_BAD_DT;
    for (k = 0; k < m->n; k++) {       /* the motors turn at the rotors' speed */
        speed[k] = d->vr[k];
        z0[k] = d->xr[k];
    }
    hg_drive_step(m->drive, m->n, volts, d->current_a, speed, d->vloop_int, enabled, dt_s, &d->memo, &drv);
    for (k = 0; k < m->n; k++) {
        rc = axis_step(m, d, k, drv.i_mean[k] * m->drive[k].force_per_amp_n, dt_s, r);
        if (rc)
            return rc;
        z1[k] = d->xr[k];
    }
    hg_drive_integral(m->drive, m->n, enabled, &drv, z0, z1, dt_s, d->vloop_int);
    memcpy(d->current_a, drv.i_end, (unsigned long)m->n * sizeof(double));
    for (k = 0; k < m->n; k++)         /* the drives' state is state too: no NaN escapes with rc 0 */
        if (!(isfinite(d->current_a[k]) && isfinite(d->vloop_int[k]))) {
            r->kind = 2, r->channel = k, r->other = -1, r->value = d->current_a[k], r->limit = 0.0;
            return HG_ERR_STATE_NONFINITE;
        }
    d->t_s += dt_s;
    return HG_OK;
}

/* Finite x, or 0. */
static double finite_or_zero(double x) { return isfinite(x) ? x : 0.0; }

/* hg_plant.sense: encoders' turns, loads, currents, forces and switches after a step. */
static void sense(const hg_plant_model *pm, const hg_plant_data *pd, hg_plant_sense *s)
{
    const serial_model *m = model_of(pm);
    const serial_data *d = cdata_of(pd);
    int k;
    memset(s, 0, sizeof *s);
    s->channels = m->n;
    s->rotary = m->rotary;
    for (k = 0; k < m->n; k++) {
        s->turns[k] = (m->cpr[k] < 0.0 ? -d->xr[k] : d->xr[k]) / m->lead[k];
        s->turns_per_unit[k] = (m->cpr[k] < 0.0 ? -1.0 : 1.0) / m->lead[k];
        s->counts_per_rev[k] = fabs(m->cpr[k]);
        s->motor_pos[k] = finite_or_zero(d->xr[k]);
        s->pos[k] = finite_or_zero(d->x[k]);
        s->vel[k] = finite_or_zero(d->v[k]);
        s->current_a[k] = finite_or_zero(d->current_a[k]);
        s->force[k] = finite_or_zero(d->force_n[k]);
        s->switches[k] = hg_plant_switches(d->x[k], m->limit_min[k], m->limit_max[k], m->home[k]);
    }
    s->sim_time_s = finite_or_zero(d->t_s);
}

/* The norm of (commanded - load position) over the linear axes: a rotary
 * axis's error is an angle, whose effect on the tool needs the part's
 * radius, which the plant does not know (0 for a machine of rotary axes). */
static double tool_error(const hg_plant_model *pm, const hg_plant_data *pd, const double pos_cmd[HG_CHANNELS_MAX])
{
    const serial_model *m = model_of(pm);
    const serial_data *d = cdata_of(pd);
    double e = 0.0;
    int k;
    for (k = 0; k < m->n; k++)
        if (!((m->rotary >> k) & 1u))
            e += (pos_cmd[k] - d->x[k]) * (pos_cmd[k] - d->x[k]);
    e = sqrt(e);
    return isfinite(e) ? e : -1.0;
}

void hg_serial_energy(const hg_plant_model *pm, const hg_plant_data *pd, double *kinetic_j, double *potential_j)
{
    const serial_model *m = model_of(pm);
    const serial_data *d = cdata_of(pd);
    int k;
    *kinetic_j = *potential_j = 0.0;
    for (k = 0; k < m->n; k++) {
        if ((m->flexible >> k) & 1u) {
            *kinetic_j += 0.5 * (m->mass[k] * d->v[k] * d->v[k] + m->rotor[k] * d->vr[k] * d->vr[k]);
            *potential_j += hg_drivetrain_energy(&m->train[k], d->xr[k] - d->x[k]);
        } else {
            *kinetic_j += 0.5 * m->rigid[k] * d->v[k] * d->v[k];
        }
        *potential_j += m->weight[k] * d->x[k];
    }
}

/* Append v * scale rounded to 3 decimals. */
static void add_num(char *buf, double v, double scale)
{
    double x = v * scale;
    if (isfinite(x) && fabs(x) < 1e12)
        x = floor(x * 1000.0 + 0.5) / 1000.0;
    hg_text_add_value(buf, HG_PLANT_TEXT_LEN, x);
}

/* "joint 2" */
static void add_joint(char *buf, int k)
{
    char d[2] = {(char)('0' + (k >= 0 && k < 10 ? k : 0)), 0};
    hg_text_add(buf, HG_PLANT_TEXT_LEN, "joint ");
    hg_text_add(buf, HG_PLANT_TEXT_LEN, d);
}

/* The report as a sentence; the stop named by HAL name (joint-N.stop-min)
 * or spec name (stop_min_N). */
static void describe(const hg_plant_report *r, int hal, char buf[HG_PLANT_TEXT_LEN])
{
    const unsigned long n = HG_PLANT_TEXT_LEN;
    const int k = r->channel >= 0 && r->channel < AXES_MAX ? r->channel : 0, rot = r->kind == 3;
    const field_names *f = &names[k][r->value < r->limit ? HG_SF_STOP_MIN : HG_SF_STOP_MAX];
    const double scale = rot ? HG_DEG_PER_RAD : HG_MM_PER_M;
    const char *unit = rot ? " deg" : " mm";
    buf[0] = '\0';
    if (r->kind == 2) {
        add_joint(buf, k);
        hg_text_add(buf, n, ": the state is not finite");
    } else if (r->kind == 1 || rot) {
        add_joint(buf, k);
        hg_text_add(buf, n, " at ");
        add_num(buf, r->value, scale);
        hg_text_add(buf, n, unit);
        hg_text_add(buf, n, " went through its hard stop at ");
        add_num(buf, r->limit, scale);
        hg_text_add(buf, n, unit);
        hg_text_add(buf, n, " (");
        hg_text_add(buf, n, hal ? f->hal[rot] : f->spec[rot]);
        hg_text_add(buf, n, rot ? "): the stop holds a load within 5 deg; the model ends there"
                                : "): the stop holds a load within 5 mm; the model ends there");
    }
}

const hg_plant hg_plant_serial = {
    "serial",
    "a serial-axis machine (mill, router, lathe, rotary table): one drive per axis, trivkins",
    "SERIAL",
    0,                               /* [SERIAL]: the integrator's own HAL file reads it (docs/serial.md) */
    0,
    "the axes, 1 to 8 letters of XYZUVW (linear) and ABC (rotary), one per channel, e.g. XYZ (the default), "
    "XZ, XYZA",
    321,
    0,
    0,
    0,
    0,
    sizeof(serial_model),
    sizeof(serial_data),
    STATE_BYTES,
    variant_of,
    variant_name,
    channels,
    nparams,
    param,
    defaults,
    legacy,
    check,
    build,
    params_of,
    reset,
    change,
    stability,
    inject,
    step,
    sense,
    tool_error,
    describe,
};
