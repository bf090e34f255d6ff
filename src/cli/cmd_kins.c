/* cmd_kins.c - the ik and fk subcommands (mm and degrees at the interface). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "hg_errors.h"
#include "hg_kinematics.h"
#include "hg_units.h"

static const char *const pose_names[6] = {"X", "Y", "Z", "A", "B", "C"};
static const char *const joint_names[6] = {"J0", "J1", "J2", "J3", "J4", "J5"};

/* Parse six numbers into v; 0 on success, 2 (usage error) otherwise. */
static int parse_six(char **argv, const char *const names[6], double v[6])
{
    int i;
    for (i = 0; i < 6; i++)
        if (cli_parse_double(argv[i], names[i], &v[i]))
            return 2;
    return 0;
}

int cmd_ik(int argc, char **argv)
{
    hg_params p;
    hg_guard_report guard = {0, -1, -1, 0, 0};
    double user[6], pose[6], z[6];
    int rc, k;
    if (argc != 6) {
        fprintf(stderr, "hexaglide ik: need 6 numbers X Y Z (mm) A B C (deg), got %d\n", argc);
        return 2;
    }
    if (parse_six(argv, pose_names, user))
        return 2;
    hg_params_default(&p);
    hg_pose_from_user(user, pose);
    rc = hg_inverse_kinematics(&p.geo, pose, z);
    if (rc == 0)                      /* joints exist; can the machine take the pose? */
        rc = hg_guard_check(&p.geo, z, pose, 0, &guard);
    if (rc) {
        char what[HG_GUARD_TEXT_LEN];
        hg_guard_describe(&guard, 0, what);
        fprintf(stderr, "hexaglide ik: %s (code %d)%s%s\n", hg_strerror(rc), rc, what[0] ? ": " : "", what);
        return 1;
    }
    for (k = 0; k < 6; k++)
        printf("%.17g%c", z[k] * HG_MM_PER_M, k < 5 ? ' ' : '\n');
    return 0;
}

int cmd_fk(int argc, char **argv)
{
    hg_params p;
    hg_fk_report rep;
    double user[6], z[6], pose[6] = {0, 0, 0, 0, 0, 0};
    int rc, k;
    if (argc != 6 && !(argc == 13 && strcmp(argv[6], "--guess") == 0)) {
        fprintf(stderr, "hexaglide fk: need 6 joint positions J0..J5 (mm), optionally followed by "
                        "--guess X Y Z (mm) A B C (deg); got %d arguments\n", argc);
        return 2;
    }
    if (parse_six(argv, joint_names, user))
        return 2;
    for (k = 0; k < 6; k++)
        z[k] = user[k] / HG_MM_PER_M;
    if (argc == 13) {
        if (parse_six(argv + 7, pose_names, user))
            return 2;
        hg_pose_from_user(user, pose);
    }
    hg_params_default(&p);
    rc = hg_forward_kinematics(&p.geo, z, pose, 0, &rep);
    if (rc) {
        char what[HG_GUARD_TEXT_LEN];
        hg_guard_describe(&rep.guard, 0, what);
        fprintf(stderr, "hexaglide fk: %s (code %d, %d iterations, residual %.3g mm)%s%s\n",
                hg_strerror(rc), rc, rep.iterations, rep.residual_m * HG_MM_PER_M, what[0] ? ": " : "", what);
        return 1;
    }
    hg_pose_to_user(pose, user);
    for (k = 0; k < 6; k++)
        printf("%.17g%c", user[k], k < 5 ? ' ' : '\n');
    return 0;
}
