/* hg_drivetrain.c - spring, damper and lost motion of an axis's drive train (hg_drivetrain.h). */
#include "hg_drivetrain.h"

int hg_drivetrain_rigid(const hg_drivetrain_channel *c)
{
    return !(c->k_axial > 0.0);
}

double hg_drivetrain_energy(const hg_drivetrain_channel *c, double d)
{
    double e = hg_drivetrain_engaged(c, d);
    return 0.5 * c->k_axial * e * e;
}
