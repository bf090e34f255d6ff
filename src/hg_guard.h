/* hg_guard.h - the machine's mechanical limits, as a check of one state:
 * the angle of each bar in its carriage (spherical) joint and in its head
 * (universal) joint against the joints' cone half-angles, the clearance
 * between every pair of bars (closest distance of their axes against the
 * bar diameter) and, for a machine with broken bars, the region the model
 * represents. One guard for everything that must not return an impossible
 * state: the intact and the broken-bar dynamics steps (hg_step) and the
 * forward kinematics (hexaglidekins, hexaglide fk).
 *
 * Angles are measured from the bar's direction at HOME: in world axes at
 * the carriage joint (the carriage only translates), in head axes at the
 * head joint (the joint turns with the head). A bar that dips below the
 * head's joint plane is excluded by the head cone (hg_params' rule on
 * cone_head), so the head needs no contact test of its own.
 *
 * Units: SI and radians (hg_kinematics.h conventions). Pure C, no
 * malloc, no stdio, bounded loops. */
#ifndef HG_GUARD_H
#define HG_GUARD_H

#include "hg_geometry.h"
#include "hg_kinematics.h"

/* The region a machine with broken bars may be in: the model has no
 * contacts, and a head swinging further would strike bars and posts that
 * it passes through here (chosen bounds, beyond every pose of the intact
 * machine; docs/dynamics.md). */
#define HG_BROKEN_HEAD_Z_MIN_M (-0.6) /* head Z below this is out of the region */
#define HG_BROKEN_REACH_M 1.0         /* |X|, |Y| or a |z_k| above this is out */
#define HG_BROKEN_ROT_MAX_RAD 0.3490658503988659 /* |A|, |B| or |C| above 20 deg is out */

/* What a failed check found: the first limit crossed. */
typedef enum {
    HG_GUARD_NONE = 0,
    HG_GUARD_CARRIAGE_JOINT = 1,  /* bar `bar` beyond cone_carriage in its carriage joint */
    HG_GUARD_HEAD_JOINT = 2,      /* bar `bar` beyond cone_head in its head joint */
    HG_GUARD_BARS = 3,            /* bars `bar` and `other` closer than d_bar */
    HG_GUARD_REGION = 4,          /* broken machine outside the modelled region (hg_dynamics.h) */
    HG_GUARD_THROUGH_STOP = 5     /* carriage `bar` at `value`, through its hard stop at `limit` (the step's
                                     check, hg_dynamics.c: the stops are parameters, not geometry) */
} hg_guard_kind;

typedef struct {
    int kind;                     /* hg_guard_kind */
    int bar, other;               /* the bar(s) involved (0..5; other -1 unless BARS) */
    double value;                 /* the angle (rad) or distance (m) found */
    double limit;                 /* the limit it crossed (rad or m) */
} hg_guard_report;

/* Check the state (carriage heights z, head pose) against the limits of
 * g; bars whose bit is set in `broken` are left out (region check
 * instead). 0, HG_ERR_JOINT_RANGE, HG_ERR_BAR_CLEARANCE or
 * HG_ERR_OUT_OF_VOLUME with *r (may be 0) describing the first limit
 * crossed; a non-finite state is HG_ERR_OUT_OF_VOLUME. */
int hg_guard_check(const hg_geometry *g, const double z[6], const double pose[6],
                   unsigned broken, hg_guard_report *r);

/* What the check needs of a geometry, computed once (hg_guard_prepare):
 * the dynamics keep it in their model. */
typedef struct {
    hg_geometry g;                /* the geometry */
    hg_frame f;                   /* its fixed points (hg_frame_of) */
    double cos_carriage, cos_head; /* cosines of the cone half-angles */
    double u0[6][3];              /* each bar's direction at HOME, carriage to head joint */
    double head_r[6];             /* |r_k|: each head joint's distance from Op (m) */
} hg_guard_geo;

#define HG_GUARD_PAIRS 15         /* pairs of bars, (0,1) (0,2) .. (4,5) */
/* Safety slack (m) of the clearance bound below: far above the rounding of
 * the distances and displacements (1e-15 m), above the most the segment
 * distance's near-parallel branch can overstate a distance (|d1| 1e-6 = 1 um
 * for 1 m bars), far below any bar diameter. */
#define HG_GUARD_SLACK_M 1e-5
/* Safety slack (rad) of the cone bound below: far above the error of an
 * angle taken by acos from a rounded cosine (sqrt(2 x 4e-16) = 3e-8 rad
 * next to the HOME direction, where acos is steepest), far below any cone. */
#define HG_GUARD_SLACK_RAD 1e-6
/* asin(x) <= HG_GUARD_ASIN_SLOPE x for 0 <= x <= 1/2 (asin(1/2) / (1/2) =
 * 1.0472): a bar whose ends moved by at most x of its length turned by at
 * most this many times x (rad); beyond x = 1/2 the bound is not used. */
#define HG_GUARD_ASIN_SLOPE 1.05

/* The guard's memo of a state that is being stepped: facts about two
 * reference states that passed, which let most checks of a nearby state
 * finish without its joint points (a state that is not cleared is checked
 * in full, by the same code, with the same report).
 *
 * Movement from a reference: a state whose carriages moved by dz_k and
 * whose head moved by dP (Op) and turned through at most theta = |dA| +
 * |dB| + |dC| (the rotation angle between two orientations is at most the
 * sum of their Euler angles' differences: the angle between rotations is a
 * metric that left and right factors keep) has bar k's carriage joint
 * moved by dz_k and its head joint by at most dP + theta |r_k|.
 *
 * Clearance (valid): the joint points of a reference state and the
 * distances between the bar axes there (hg_segment_distance). Points of a
 * segment move by at most the larger of its ends' displacements, so a
 * state whose bars' ends moved by at most m_j, m_k from the reference has
 * the bars j, k at least dist - m_j - m_k apart: a pair with dist - m_j -
 * m_k >= d_bar + HG_GUARD_SLACK_M cannot touch and is not measured.
 *
 * Cones (cones_valid): a reference state's joint angles and bar vectors
 * A - B. A bar whose ends moved by at most e (both ends together) turned
 * by at most asin(e / |A - B|_ref) <= HG_GUARD_ASIN_SLOPE e / |A - B|_ref
 * = alpha_k, so its carriage-joint angle is at most the reference's +
 * alpha_k, and its head-joint angle (in head axes, which turned by theta)
 * the reference's + alpha_k + theta: within both cones by
 * HG_GUARD_SLACK_RAD, the bar is not measured.
 *
 * A fact about the points it holds, valid in any copy; valid and
 * cones_valid 0 = empty (hg_data_reset). */
typedef struct {
    int valid;
    double B[6][3], A[6][3];      /* the clearance reference's joint points */
    double z[6], pose[6];         /* ... its state */
    double dist[HG_GUARD_PAIRS];  /* distances of the bar axes there (NaN: a broken bar's pair) */
    double dist_min;              /* the smallest of them (NaN when one is NaN) */
    int cones_valid;
    double cone_z[6], cone_pose[6]; /* the cones' reference state (an intact machine) */
    double cone_carriage[6], cone_head[6]; /* its bars' angles in their carriage and head joints (rad) */
    double bar_len[6];            /* its |A - B| of each bar (m) */
    unsigned long refreshed;      /* times the clearance reference was (re)written: a measure of its use */
    unsigned long cleared;        /* checks the bounds alone passed (no joint points): a measure too */
} hg_guard_memo;

/* Fill gg for g. */
void hg_guard_prepare(const hg_geometry *g, hg_guard_geo *gg);

/* hg_guard_check with gg prepared, the pose's sin/cos sc given
 * (hg_head_trig of pose: the stabilization has them) and memo (may be 0):
 * the same code, the same report. An intact machine's state that the
 * memo's bounds clear of every cone and pair passes without its joint
 * points; else a pair the memo's bound clears is not measured. When some
 * pair had to be measured and the state passes, the clearance reference
 * becomes this state (with all its distances); when the cones were
 * measured and an intact machine's state passes them, the cones'. */
int hg_guard_check_sc(const hg_guard_geo *gg, const double z[6], const double pose[6],
                      const double sc[6], unsigned broken, hg_guard_memo *memo,
                      hg_guard_report *r);

/* Angles (rad) of every bar in its carriage joint and in its head joint. */
void hg_guard_joint_angles(const hg_geometry *g, const double z[6], const double pose[6],
                           double carriage_rad[6], double head_rad[6]);

/* Closest distance (m) between the segments p1-q1 and p2-q2. */
double hg_segment_distance(const double p1[3], const double q1[3], const double p2[3],
                           const double q2[3]);

/* Smallest distance between two bar axes with the machine at HOME (m). */
double hg_guard_home_clearance(const hg_geometry *g);

/* The kinematics the machine answers with: the solves of hg_kinematics.h,
 * their answers checked by the guard. */
typedef struct {
    int iterations;            /* iterations used by the last call */
    double residual_m;         /* max over bars of ||B-A| - l| at the answer */
    hg_guard_report guard;     /* the limit crossed, when the answer was refused by the guard */
} hg_fk_report;

/* The joints of a pose the machine can take: hg_inverse_kinematics, then
 * hg_guard_check of the answer (the bars' joint ranges and clearance; what
 * `hexaglide ik` and the Python binding's ik report). 0, or the inverse's
 * codes, or HG_ERR_JOINT_RANGE / HG_ERR_BAR_CLEARANCE with *report (may
 * be 0; kind HG_GUARD_NONE when the inverse failed) naming the bar(s),
 * value and limit. z untouched on failure. */
int hg_inverse_kinematics_guarded(const hg_geometry *g, const double pose[6], double z[6],
                                  hg_guard_report *report);

/* The pose of joints z the machine can take: hg_forward_solve from the
 * guess pose (overwritten with the answer on success only), then
 * hg_guard_check of the answer: a bar beyond its joint range or two bars
 * touching is refused (HG_ERR_JOINT_RANGE, HG_ERR_BAR_CLEARANCE,
 * report->guard says which), so a guess far away never yields a crossed
 * assembly. 0, or those, or hg_forward_solve's codes. report may be 0. */
int hg_forward_kinematics(const hg_geometry *g, const double z[6], double pose[6],
                          const hg_fk_options *opt, hg_fk_report *report);

/* One forward call of a kinematics module with a session s (its settings
 * in force): hg_forward_kinematics from the guess in pose; if that fails
 * and s has solved before, once more from s's last solved pose (LinuxCNC's
 * motion passes its world home as the guess after a failed call, which can
 * be far from the machine). On success pose is the answer and becomes s's
 * last pose; on failure pose is s's last solved pose (left as given when
 * there is none), so what the caller shows stays at the last pose solved
 * until a call succeeds. The report is the successful attempt's, else the
 * first one's. 0 or hg_forward_kinematics' codes; counts nothing
 * (hg_fk_session_result does). */
int hg_fk_session_solve(hg_fk_session *s, const hg_geometry *g, const double z[6], double pose[6],
                        hg_fk_report *report);

/* A failed call that never reached the solve (a refused geometry): pose
 * becomes s's last solved pose, left as given when there is none. */
void hg_fk_session_hold(const hg_fk_session *s, double pose[6]);

#endif
