/* hg_drivetrain.h - the axial drive train of one axis, between the motor
 * (the rotor with the screw: the encoder's side) and the load (the
 * carriage or the axis: the tool's side): a coupling, the screw, the nut
 * and the bearings as one axial spring k_axial with a damper c_axial, and
 * a backlash (the total lost motion of the nut and the coupling) inside
 * which the train carries no force at all. Everything is in the load's
 * coordinate: the rotor's angle as the load position it would give
 * (theta lead / 2 pi for a screw), so the rotor's inertia is the
 * reflected mass j_rotor (2 pi / lead)^2. k_axial = 0 is the rigid train:
 * motor and load one body, as every model before the drive train.
 * Shared by every plant (hg_plant.h). Pure C, no malloc. */
#ifndef HG_DRIVETRAIN_H
#define HG_DRIVETRAIN_H

/* One axis's train (SI: N/m, N s/m, m; N m/rad ... for a rotary axis). */
typedef struct {
    double k_axial;              /* stiffness; 0: rigid */
    double c_axial;              /* damping while in contact */
    double backlash;             /* total lost motion: +-backlash/2 of free play about the middle */
} hg_drivetrain_channel;

/* 1 when the train is rigid (k_axial = 0). */
int hg_drivetrain_rigid(const hg_drivetrain_channel *c);

/* The train's potential energy (J) at deflection d: k (|d| - backlash/2)^2 / 2 in contact. */
double hg_drivetrain_energy(const hg_drivetrain_channel *c, double d);

/* The spring's compression beyond the free play (0 inside it). */
static inline double hg_drivetrain_engaged(const hg_drivetrain_channel *c, double d)
{
    double half = 0.5 * c->backlash;
    return d > half ? d - half : d < -half ? d + half : 0.0;
}

/* The force (N) the train puts on the load, toward the motor's side
 * positive, at deflection d = motor - load (m) and its rate dd (m/s):
 * k (d -+ backlash/2) + c dd while the flanks touch (|d| > backlash/2),
 * 0 in the free play; with backlash the flanks only push (the damper
 * cannot pull them apart: the force stops at 0). (The motor gets the
 * opposite.) Inline: every stage of every substep calls it six times. */
static inline double hg_drivetrain_force(const hg_drivetrain_channel *c, double d, double dd)
{
    double e = hg_drivetrain_engaged(c, d), f;
    if (e == 0.0)
        return 0.0;
    f = c->k_axial * e + c->c_axial * dd;
    if (c->backlash > 0.0)             /* flanks in contact push, never pull: the damper stops at 0 */
        return e > 0.0 ? (f > 0.0 ? f : 0.0) : (f < 0.0 ? f : 0.0);
    return f;
}

#endif
