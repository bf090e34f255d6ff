/* hg_friction.h - sliding and static friction of a plant's n <= 8
 * sliding axes (the Hexaglide's six carriages), resolved once per step at
 * the velocity level (Moreau's time stepping): stick holds exactly, with
 * no creep, and the step is stable at any period with every integrator.
 * Plant agnostic: each axis (channel) has its own parameters.
 *
 * Per axis: a breakaway force f_static; once sliding, a friction
 * force opposite the motion that falls from f_static to f_coulomb with
 * the speed (Stribeck): F(v) = f_coulomb + (f_static - f_coulomb)
 * exp(-(v / v_stribeck)^2), taken at the speed of the step's start.
 * Viscous friction is smooth and lies with the plant's forces (hg_forces.h).
 *
 * Over a step the friction impulses p (N s) act on the axis speeds
 * predicted without them, v*: v = v* + W p, where W is the axes'
 * inverse inertia (the axis-space response of the whole machine).
 * An axis at rest sticks (v_k = 0 exactly) while the impulse that keeps
 * it there is at most f_static dt, else it breaks away. A moving one
 * slides with p_k = -F dt against its motion (F the Stribeck curve's mean
 * over the step's speeds), unless that would reverse it: then it stops
 * within the step (at the fraction of the step a constant deceleration
 * gives) and sticks. The coupled set is solved by active sets: every
 * sticking set exactly (a small SPD system), at most HG_FRICTION_MAX_ITER
 * changes.
 *
 * Pure C (hg_linalg), no malloc, bounded loops. */
#ifndef HG_FRICTION_H
#define HG_FRICTION_H

#define HG_FRICTION_MAX_ITER 24      /* active-set changes at most */
#define HG_FRICTION_MAX_N 8          /* axes of one solve */

/* One axis's friction parameters (the Hexaglide's: hg_params' f_static,
 * f_coulomb, v_stribeck, every carriage alike). */
typedef struct {
    double f_static_n;      /* breakaway force, >= f_coulomb */
    double f_coulomb_n;     /* sliding force beyond the Stribeck speeds */
    double v_stribeck_mps;  /* Stribeck speed: sliding friction falls from f_static to f_coulomb */
} hg_friction_channel;

typedef struct {
    double impulse[HG_FRICTION_MAX_N]; /* friction impulse on each axis over the step (N s, + up) */
    unsigned stuck;         /* bit k: axis k sticks (its speed at the step's end is 0) */
    double stop[HG_FRICTION_MAX_N]; /* moving axes that stuck: the fraction of the step at which
                                       they stopped (1 for the others) */
    int iterations;         /* active-set changes used */
} hg_friction_out;

/* 1 when one of the n channels has sliding or static friction (f_coulomb
 * or f_static > 0). */
int hg_friction_any(const hg_friction_channel *c, int n);

/* Sliding friction force (N, >= 0) of channel c at speed v (m/s): the
 * Stribeck curve, f_coulomb + (f_static - f_coulomb) hg_friction_shape(c, v). */
double hg_friction_curve(const hg_friction_channel *c, double v);

/* The Stribeck curve's shape exp(-(v / v_stribeck)^2): 1 at rest, 0 fast. */
double hg_friction_shape(const hg_friction_channel *c, double v);

/* The step's friction impulses of n axes with channels c[n]: W (n x n,
 * row-major, symmetric positive definite, m/s per N s), vstar the axis
 * speeds at the step's end without sliding or static friction, v0 those at
 * its start, at_rest the axes stuck at the start (bit k; a zero v0 counts
 * as at rest too). 0, or HG_ERR_SINGULAR_MASS when a sticking set's W
 * cannot be factored (HG_ERR_BAD_PARAM for n outside 1..HG_FRICTION_MAX_N). */
int hg_friction_solve(const hg_friction_channel *c, int n, const double *W, const double *vstar,
                      const double *v0, unsigned at_rest, double dt, hg_friction_out *o);

/* The common case without W: when every axis slides, at the start and at
 * the end of the step, on the flat of its Stribeck curve (beyond 6
 * v_stribeck, where it is f_coulomb to the last bit) in the direction it
 * moves, hg_friction_solve gives impulse_k = -sign(v0_k) f_coulomb dt and
 * sticks nothing. vpred: the end speeds with the expected impulses est
 * (N s); m_min: a lower bound of every axis's effective mass (kg), so the
 * correction W (impulse - est) moves no speed by more than
 * |impulse - est| / m_min. 1 and o filled when that holds, else 0. */
int hg_friction_all_sliding(const hg_friction_channel *c, int n, const double *vpred,
                            const double *v0, unsigned at_rest, const double *est, double m_min,
                            double dt, hg_friction_out *o);

#endif
