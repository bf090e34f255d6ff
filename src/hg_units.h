/* hg_units.h - conversions between the SI/radian core and the project's
 * user units (mm, degrees). One place for the factors; a LinuxCNC machine
 * in other linear units (inch) goes through hg_kinematics.h's
 * hg_pose_from_machine and friends, which with 1 mm per unit round as these. */
#ifndef HG_UNITS_H
#define HG_UNITS_H

#define HG_MM_PER_M 1000.0
#define HG_MM_PER_INCH 25.4           /* LinuxCNC's LINEAR_UNITS inch */
#define HG_DEG_PER_RAD 57.295779513082320877
#define HG_PI 3.14159265358979323846

/* user pose (X Y Z mm, A B C deg) -> core pose (m, rad) */
static inline void hg_pose_from_user(const double user[6], double pose[6])
{
    int k;
    for (k = 0; k < 3; k++) {
        pose[k] = user[k] / HG_MM_PER_M;
        pose[k + 3] = user[k + 3] / HG_DEG_PER_RAD;
    }
}

/* core pose (m, rad) -> user pose (mm, deg) */
static inline void hg_pose_to_user(const double pose[6], double user[6])
{
    int k;
    for (k = 0; k < 3; k++) {
        user[k] = pose[k] * HG_MM_PER_M;
        user[k + 3] = pose[k + 3] * HG_DEG_PER_RAD;
    }
}

#endif
