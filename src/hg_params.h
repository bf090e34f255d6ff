/* hg_params.h - the Hexaglide parameter set: geometry, masses, drives,
 * friction and strokes, all in SI units (the unit is in each field name).
 * Defaults are the numbers of docs/model.md. Every field can be
 * read and set by its spec name ("l", "m_head", "c_visc", ...), so the CLI
 * (--set name=value), the HAL driver and the FMU share one table (the
 * Hexaglide plant's, hg_plant_hexaglide.c). The rules of a valid set live
 * here too, the geometry's included (they need the guard's clearance at
 * HOME, hg_guard.h).
 * Pure C, no LinuxCNC dependency, no malloc, no stdio. */
#ifndef HG_PARAMS_H
#define HG_PARAMS_H

#include "hg_geometry.h"
#include "hg_param_table.h"

/* The whole machine. */
typedef struct {
    hg_geometry geo;
    double tool_d_m;           /* tool tip below Op along the head axis */
    double g_mps2;             /* gravity, along -z */
    /* mass properties */
    double m_head_kg;          /* head with spindle */
    double head_com_m;         /* head COM below Op on the head axis */
    double i_head_xx_kgm2;     /* head inertia about its COM, head axes */
    double i_head_yy_kgm2;
    double i_head_zz_kgm2;
    double m_bar_kg;           /* one bar, COM at mid-length */
    double i_bar_kgm2;         /* bar transverse inertia about the carriage joint */
    double m_carriage_kg;      /* one carriage */
    /* drives: ball screw, motor (back-EMF constant = kt in SI), amplifier */
    double lead_m;             /* ball-screw lead per revolution */
    double j_rotor_kgm2;       /* rotor + screw inertia */
    double kt_nm_per_a;        /* motor torque constant (= back-EMF constant, V s/rad) */
    double r_winding_ohm;      /* motor winding resistance */
    double l_winding_h;        /* motor winding inductance */
    double amp_mode;           /* 0 torque (current) mode, 1 velocity mode */
    double ka_a_per_v;         /* torque mode: amplifier gain, current per command volt */
    double i_max_a;            /* amplifier current limit */
    double v_bus_v;            /* amplifier supply (bus) voltage: the most it can put on the winding */
    double v_rated_mps;        /* velocity mode: carriage speed at +10 V */
    double kp_vel_as_per_m;    /* velocity mode: the amplifier's velocity loop, current per speed error */
    double ki_vel_a_per_m;     /* velocity mode: integral gain, current per integrated speed error */
    /* friction, per carriage */
    double c_visc_ns_per_m;    /* viscous, drive included */
    double f_coulomb_n;        /* sliding (Coulomb) friction */
    double f_static_n;         /* breakaway (static) friction, >= f_coulomb */
    double v_stribeck_mps;     /* Stribeck speed: sliding friction falls from f_static to f_coulomb */
    /* strokes, relative to HOME */
    double stop_min_m;         /* mechanical hard stop, bottom */
    double stop_max_m;         /* mechanical hard stop, top */
    double k_stop_n_per_m;     /* hard-stop spring */
    double c_stop_ns_per_m;    /* hard-stop damper (acts only while in contact) */
    double limit_min_m;        /* limit switch, bottom (trips at or below) */
    double limit_max_m;        /* limit switch, top (trips at or above) */
    double home_switch_m;      /* home switch: on for z >= this (see docs/homing) */
    /* sensors */
    double counts_per_rev;     /* encoder counts per motor revolution */
    /* drive train between the motor (encoder side) and the carriage (hg_drivetrain.h) */
    double k_axial_n_per_m;    /* axial stiffness of coupling, screw, nut and bearings; 0: rigid */
    double c_axial_ns_per_m;   /* its damping */
    double backlash_m;         /* total lost motion (0: a preloaded nut) */
} hg_params;

/* hg_params_check refuses any field at or above HG_PARAM_MAX_ABS in
 * magnitude, and any must-be-positive one below HG_PARAM_MIN_POSITIVE
 * (hg_param_table.h: every plant's bounds). */
#define HG_CONE_MIN_RAD 0.017453292519943295 /* 1 deg: the least cone_carriage, cone_head */
/* head_com is at most this many bar lengths l (its message says 2). */
#define HG_HEAD_COM_MAX_BARS 2.0

/* Upper bound of the table's length. */
#define HG_PARAMS_MAX 48

/* Fill p with the spec's defaults. */
void hg_params_default(hg_params *p);

/* The by-name table and its length. */
const hg_param_info *hg_params_table(int *count);

/* Pointer to the field called name, or 0 if there is none. */
double *hg_params_field(hg_params *p, const char *name);

/* Field of table entry i (0 <= i < table length), or 0 for another i. */
double *hg_params_at(hg_params *p, int i);

/* Value of table entry i, or 0 for an index outside the table. */
double hg_params_get(const hg_params *p, int i);

/* Set field name to value: 0, or HG_ERR_BAD_PARAM for an unknown name or a
 * non-finite value. Does not validate the whole set: call hg_params_check. */
int hg_params_set(hg_params *p, const char *name, double value);

/* Check the geometry alone: 0 or HG_ERR_BAD_PARAM with *bad_field naming
 * the offending field and *why saying what is wrong (static strings). */
int hg_geometry_check(const hg_geometry *g, const char **bad_field, const char **why);

/* The geometry of a kinematics module, set field by field in HAL units
 * (hexaglidekins' parameters): the entries last checked, as given, and the
 * check's answer, so that the module checks a geometry once per change
 * and can say which field was set when another field's rule fails. */
typedef struct {
    double given[HG_PARAMS_MAX]; /* the geometry entries last checked, HAL units, as given */
    int valid;                   /* 0: nothing checked yet */
    int rc;                      /* HG_OK or HG_ERR_BAD_PARAM: the check of given */
    hg_geometry geo;             /* given, in SI units */
    unsigned fingerprint;        /* hg_geometry_fingerprint(&geo) */
} hg_geometry_setting;

/* Nothing checked yet: the next hg_geometry_take checks. */
void hg_geometry_setting_init(hg_geometry_setting *s);

/* Take the geometry entries of hal (table entry i at hal[i], in the
 * table's HAL units; other entries unread) into s, and check them with
 * hg_geometry_check when any differs from those taken before (a NaN kept
 * is no change). 1 when a changed geometry is refused, to be said once:
 * *field and *why name the rule, *set_entry the table entry set since the
 * last check when that is another field than *field (else -1: nothing
 * more to say). 0 otherwise; s->rc is the answer for the geometry given. */
int hg_geometry_take(hg_geometry_setting *s, const double hal[HG_PARAMS_MAX], const char **field, const char **why,
                     int *set_entry);

/* Check the whole set (geometry, positive masses, ordered strokes, ...). */
int hg_params_check(const hg_params *p, const char **bad_field, const char **why);

/* Check the whole set and report EVERY invalid field: 0, or
 * HG_ERR_BAD_PARAM with bit i of *bad (may be 0) set for each invalid
 * table entry i and why[i] (may be 0; HG_PARAMS_MAX entries, 0 for valid
 * ones) its reason. A rule that depends on an invalid field is skipped
 * (e.g. "l > lb - lp" when lb is invalid). The first failure is the one
 * hg_params_check reports. */
int hg_params_check_all(const hg_params *p, hg_bitset *bad, const char *why[HG_PARAMS_MAX]);

/* Check the set as the kinematics use it (hexaglidekins, `hexaglide ik`,
 * the Python binding's ik and fk): hg_params_check_all's refusals of a
 * geometry field, or of a field given another value than its default; a
 * rule of the dynamics failing on a default (the default i_bar against a
 * new l) is not the kinematics' to enforce. 0, or HG_ERR_BAD_PARAM with
 * *bad (may be 0) and why (may be 0) as hg_params_check_all gives them,
 * those fields only. */
int hg_params_check_kinematics(const hg_params *p, hg_bitset *bad, const char *why[HG_PARAMS_MAX]);

/* Motor current that holds the machine at HOME: W / 6 / (kt 2 pi / lead)
 * (A), W the weight of head, bars and carriages. */
double hg_hold_current(const hg_params *p);

/* HAL name of the parameter with spec name `name` ("cone_head" -> "cone-head"),
 * or name itself when there is none. */
const char *hg_params_hal_name(const char *name);

/* 1 if table entry i is a field of hg_geometry (what hexaglidekins takes). */
int hg_param_is_geometry(int i);

#endif
