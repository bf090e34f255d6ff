/* hg_drivetrain.c - spring, damper and lost motion of an axis's drive train (hg_drivetrain.h). */
#include "hg_drivetrain.h"

int hg_drivetrain_rigid(const hg_drivetrain_channel *c)
{
    return !(c->k_axial > 0.0);
}

/* The spring's compression beyond the free play (0 inside it). */
static double engaged(const hg_drivetrain_channel *c, double d)
{
    double half = 0.5 * c->backlash;
    return d > half ? d - half : d < -half ? d + half : 0.0;
}

double hg_drivetrain_force(const hg_drivetrain_channel *c, double d, double dd)
{
    double e = engaged(c, d), f;
    if (e == 0.0)
        return 0.0;
    f = c->k_axial * e + c->c_axial * dd;
    if (c->backlash > 0.0)             /* flanks in contact push, never pull: the damper stops at 0 */
        return e > 0.0 ? (f > 0.0 ? f : 0.0) : (f < 0.0 ? f : 0.0);
    return f;
}

double hg_drivetrain_energy(const hg_drivetrain_channel *c, double d)
{
    double e = engaged(c, d);
    return 0.5 * c->k_axial * e * e;
}
