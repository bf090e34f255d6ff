/* hg_dynamics.h - forward dynamics of the whole Hexaglide (head, six bars,
 * six carriages, six drives), one integration step per call, after
 * Ros et al., Multibody Dynamics 2011 (docs/model.md cites it).
 *
 * MuJoCo-style split (types in hg_model.h): hg_model is constant after
 * hg_model_init; hg_data is the mutable state and scratch.
 *
 * Units: SI and radians. z = carriage heights relative to HOME (m, up),
 * pose = X Y Z (m) A B C (rad) of the head reference point, as in
 * hg_kinematics.h. Volts are the DAC commands of joints 0..5.
 *
 * Pure C and rtapi_math's functions (hg_math.h): no LinuxCNC dependency;
 * hg_step has no malloc, no stdio, bounded loops and stack frames under
 * 2560 bytes, and never leaves a non-finite number in hg_data's state. */
#ifndef HG_DYNAMICS_H
#define HG_DYNAMICS_H

#include "hg_model.h"
#include "hg_kinematics.h"

/* The names of the kinds, in hg_model_kind's order (hg_model_name). */
extern const char *const hg_model_names[HG_MODEL_COUNT];

/* Name used on the command line and in HAL ("standard", "reduced-joints",
 * "reduced-cartesian", "fused-cartesian"); 0 for an invalid kind. */
const char *hg_model_name(hg_model_kind kind);

/* Kind for a name, or -1 when the name is unknown. */
int hg_model_from_name(const char *name);

/* Check p and build the model: 0, or HG_ERR_BAD_PARAM with *bad_field and
 * *why naming the cause (static strings), or another negative code. */
int hg_model_init(hg_model *m, const hg_params *p, hg_model_kind kind,
                  const char **bad_field, const char **why);

/* Use scheme `which` from now on: 0, or HG_ERR_BAD_PARAM (m unchanged)
 * when which is not in [0, HG_INTEGRATOR_COUNT). */
int hg_model_set_integrator(hg_model *m, int which);

/* Put the machine at HOME at rest (z = 0, z' = 0), solving the dependent
 * coordinates and velocities with full Newton-Raphson. 0 or a negative code. */
int hg_data_reset(const hg_model *m, hg_data *d);

/* Integrate one step of dt_s seconds with the given DAC volts (clamped to
 * +-10 V, non-finite volts count as 0; held over the step) with the scheme
 * m->integrator (hg_integrate.h: Heun by default; the paper's improved
 * Euler on request).
 * 0, or a negative code (BAD_DT, STATE_NONFINITE, STABILIZATION,
 * SINGULAR_MASS, ...) in which case d's state (the first
 * HG_DATA_STATE_BYTES) is left exactly as it was before the call except
 * last_error and guard; d->work is scratch. Every new state passes
 * hg_guard_check (the joints' ranges, the bars' clearance): a step that
 * would cross a limit fails with JOINT_RANGE or BAR_CLEARANCE and d->guard
 * names the bar(s), the value and the limit (the machine has struck).
 * With any bit of d->broken_bars set, every kind takes the broken-bar step
 * (lumped bars in q = [z, c], only the intact bars' constraints, see
 * hg_step_broken.h; standard: bar angles follow the geometry,
 * their rates are 0); the guard then checks only the intact bars, and the
 * step also fails with OUT_OF_VOLUME (head Z below HG_BROKEN_HEAD_Z_MIN_M,
 * |X|, |Y| or a |z_k| above HG_BROKEN_REACH_M, a head angle beyond
 * HG_BROKEN_ROT_MAX_RAD, hg_guard.h), SINGULAR_JACOBIAN or DIVERGED.
 * Clearing bits again needs hg_data_reset (the broken bar's length is
 * not restored). Substeps: call it n times with dt_s / n. */
int hg_step(const hg_model *m, hg_data *d, const double volts[6], double dt_s);

/* The longest step hg_step takes, HG_DT_MAX_S (s): for callers that cannot
 * read the header's constant (tools/hexaglide.py names it in its message). */
double hg_step_dt_max_s(void);

/* The friction channel of a carriage of p (every carriage alike). */
void hg_friction_channel_of(const hg_params *p, hg_friction_channel *c);

/* The Stribeck shape exp(-(v / v_stribeck)^2) of p's carriages
 * (hg_friction_shape of their channel). */
double hg_friction_stribeck(const hg_params *p, double v);

/* Kinetic energy (J, rotor included) and potential energy (J, gravity,
 * zero at HOME) of the state in d (of the lumped-bar model when a bar is
 * broken). */
void hg_energy(const hg_model *m, const hg_data *d, double *kinetic_j, double *potential_j);

#endif
