/* hg_params.h - the Hexaglide parameter set: geometry, masses, drives,
 * friction and strokes, all in SI units (the unit is in each field name).
 * Defaults are the numbers of docs/model.md. Every field can be
 * read and set by its spec name ("l", "m_head", "c_visc", ...), so the CLI
 * (--set name=value) and the HAL driver share one table.
 * Pure C, no LinuxCNC dependency, no malloc, no stdio. */
#ifndef HG_PARAMS_H
#define HG_PARAMS_H

/* Geometry: everything the kinematics needs, the joints' ranges included.
 * The carriage height above the head joints at HOME is not stored: it
 * follows from l, lb, lp (hg_home_height). */
typedef struct {
    double l_m;      /* bar length, joint centre to joint centre */
    double lb_m;     /* machine axis to a post's guide plane */
    double e_m;      /* half spacing of a post's two guides (and head joints) */
    double lp_m;     /* head joint radius along the post direction */
    double cone_carriage_rad; /* largest angle of a bar in its carriage (spherical) joint,
                                 measured from the bar's direction at HOME */
    double cone_head_rad;     /* the same in its head (universal) joint, in head axes */
    double d_bar_m;  /* bar diameter: two bar axes closer than this means the bars touch */
} hg_geometry;

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
} hg_params;

/* hg_params_check refuses any field at or above this magnitude (SI). */
#define HG_PARAM_MAX_ABS 1e9
/* ... and any must-be-positive field below this one (1/x would overflow). */
#define HG_PARAM_MIN_POSITIVE 1e-9

/* One entry of the by-name table. */
typedef struct {
    const char *name;      /* spec name, e.g. "m_head" */
    const char *unit;      /* SI unit, e.g. "kg" */
    const char *what;      /* one-line description */
    unsigned long offset;  /* offsetof(hg_params, field) */
    const char *hal_name;  /* HAL parameter name: the spec name with _ -> -, e.g. "m-head" */
    const char *hal_unit;  /* unit on HAL: mm for lengths (LinuxCNC machine units), deg for
                              angles, else the SI unit */
    double hal_scale;      /* HAL value = SI value * hal_scale (1000 for lengths, 180/pi for
                              angles, else 1) */
    const char *ini_key;   /* key of the INI file's [HEXAGLIDE] section (value in the HAL
                              unit, as hexaglide.hal copies it), or 0: set it by setp */
} hg_param_info;

/* Upper bound of the table's length (bit masks over the table fit in 64 bits). */
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

/* A fingerprint of the geometry (FNV-1a over its fields' bits, never 0):
 * two components that must simulate one machine (hexaglidekins and the
 * board) compare it to find a mismatch. */
unsigned hg_geometry_fingerprint(const hg_geometry *g);

/* Calls a fingerprint mismatch must last before it is reported (about
 * 0.1 s of servo periods): a geometry set on both components in one HAL
 * file reaches the board a period after the kinematics. */
#define HG_GEOMETRY_MISMATCH_CALLS 200

/* One comparison of the board's fingerprint (0: not connected) with our
 * own; *calls counts consecutive mismatches (0 at load). 1 exactly on the
 * HG_GEOMETRY_MISMATCH_CALLS-th of them, the call to report it on (again
 * after the two matched), else 0. */
int hg_geometry_mismatch(unsigned board_fp, unsigned own_fp, int *calls);

/* Check the whole set (geometry, positive masses, ordered strokes, ...). */
int hg_params_check(const hg_params *p, const char **bad_field, const char **why);

/* Check the whole set and report EVERY invalid field: 0, or
 * HG_ERR_BAD_PARAM with bit i of *mask (may be 0) set for each invalid
 * table entry i and why[i] (may be 0; HG_PARAMS_MAX entries, 0 for valid
 * ones) its reason. A rule that depends on an invalid field is skipped
 * (e.g. "l > lb - lp" when lb is invalid). The first failure is the one
 * hg_params_check reports. */
int hg_params_check_all(const hg_params *p, unsigned long long *mask, const char *why[HG_PARAMS_MAX]);

/* Motor current that holds the machine at HOME: W / 6 / (kt 2 pi / lead)
 * (A), W the weight of head, bars and carriages. */
double hg_hold_current(const hg_params *p);

/* HAL name of the parameter with spec name `name` ("cone_head" -> "cone-head"),
 * or name itself when there is none. */
const char *hg_params_hal_name(const char *name);

/* 1 if table entry i is a field of hg_geometry (what hexaglidekins takes). */
int hg_param_is_geometry(int i);

/* Carriage height above the head joints at HOME, the height that puts the
 * head at pose 0 when all carriages are at 0: sqrt(l^2 - (lb - lp)^2)
 * (NaN for a geometry without a HOME, l <= lb - lp). */
double hg_home_height(const hg_geometry *g);

#endif
