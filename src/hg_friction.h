/* hg_friction.h - sliding and static friction of the six carriages,
 * resolved once per step at the velocity level (Moreau's time stepping):
 * stick holds exactly, with no creep, and the step is stable at any
 * period with every integrator.
 *
 * Per carriage: a breakaway force f_static; once sliding, a friction
 * force opposite the motion that falls from f_static to f_coulomb with
 * the speed (Stribeck): F(v) = f_coulomb + (f_static - f_coulomb)
 * exp(-(v / v_stribeck)^2), taken at the speed of the step's start.
 * Viscous friction c_visc is smooth and lies in hg_forces.h.
 *
 * Over a step the friction impulses p (N s) act on the carriage speeds
 * predicted without them, v*: v = v* + W p, where W is the carriages'
 * inverse inertia (the carriage-space response of the whole machine).
 * A carriage at rest sticks (v_k = 0 exactly) while the impulse that keeps
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

#include "hg_params.h"

#define HG_FRICTION_MAX_ITER 24      /* active-set changes at most */

typedef struct {
    double impulse[6];      /* friction impulse on each carriage over the step (N s, +z up) */
    unsigned stuck;         /* bit k: carriage k sticks (its speed at the step's end is 0) */
    double stop[6];         /* moving carriages that stuck: the fraction of the step at which
                               they stopped (1 for the others) */
    int iterations;         /* active-set changes used */
} hg_friction_out;

/* 1 when p has sliding or static friction (f_coulomb or f_static > 0). */
int hg_friction_on(const hg_params *p);

/* Sliding friction force (N, >= 0) at speed v (m/s): the Stribeck curve,
 * f_coulomb + (f_static - f_coulomb) hg_friction_stribeck(p, v). */
double hg_friction_sliding(const hg_params *p, double v);

/* The Stribeck curve's shape exp(-(v / v_stribeck)^2): 1 at rest, 0 fast. */
double hg_friction_stribeck(const hg_params *p, double v);

/* The step's friction impulses: W (6x6, row-major, symmetric positive
 * definite, m/s per N s), vstar the carriage speeds at the step's end
 * without sliding or static friction, v0 those at its start, at_rest the
 * carriages stuck at the start (bit k; a zero v0 counts as at rest too).
 * 0, or HG_ERR_SINGULAR_MASS when a sticking set's W cannot be factored. */
int hg_friction_solve(const hg_params *p, const double W[36], const double vstar[6],
                      const double v0[6], unsigned at_rest, double dt, hg_friction_out *o);

/* The common case without W: when every carriage slides, at the start and
 * at the end of the step, on the flat of the Stribeck curve (beyond 6
 * v_stribeck, where it is f_coulomb to the last bit) in the direction it
 * moves, hg_friction_solve gives impulse_k = -sign(v0_k) f_coulomb dt and
 * sticks nothing. vpred: the end speeds with the expected impulses est
 * (N s); m_min: a lower bound of every carriage's effective mass (kg), so
 * the correction W (impulse - est) moves no speed by more than
 * |impulse - est| / m_min. 1 and o filled when that holds, else 0. */
int hg_friction_all_sliding(const hg_params *p, const double vpred[6], const double v0[6],
                            unsigned at_rest, const double est[6], double m_min, double dt,
                            hg_friction_out *o);

#endif
