/* hg_geometry.h - the Hexaglide's geometry: what the kinematics and the
 * mechanical-limit guard need, the joints' ranges included, and what
 * follows from it alone (the head height at HOME, a fingerprint that two
 * components compare). Its validation rules live with the whole
 * parameter set (hg_params.h). SI units, radians. Pure C. */
#ifndef HG_GEOMETRY_H
#define HG_GEOMETRY_H

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

/* Carriage height above the head joints at HOME, the height that puts the
 * head at pose 0 when all carriages are at 0: sqrt(l^2 - (lb - lp)^2)
 * (NaN for a geometry without a HOME, l <= lb - lp). */
double hg_home_height(const hg_geometry *g);

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

#endif
