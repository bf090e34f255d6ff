/* cmd_kins.c - the ik and fk subcommands (mm and degrees at the interface),
 * on the geometry of the defaults, a config (--ini) and --set. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "hg_errors.h"
#include "hg_kinematics.h"
#include "hg_guard.h"
#include "hg_guard_text.h"
#include "hg_units.h"

static const char *const pose_names[6] = {"X", "Y", "Z", "A", "B", "C"};
static const char *const joint_names[6] = {"J0", "J1", "J2", "J3", "J4", "J5"};
static const char *const guess_names[6] = {"--guess X", "--guess Y", "--guess Z", "--guess A", "--guess B", "--guess C"};

#define USAGE_TOOL_OFFSET \
    "  --tool-offset MM    G43's tool length, added to Z as LinuxCNC does: the pose is the tool's tip\n" \
    "                      plus MM in Z, the tip on the head's axis at any tilt (RTCP, as\n" \
    "                      hexaglidekins.tool-offset; default 0: the pose of Op)\n"

const char cli_usage_ik[] =
    "usage: hexaglide ik [--tool-offset MM] [--ini FILE] [--set name=value]... X Y Z A B C\n"
    "  prints the joints J0..J5 (mm) of the pose X Y Z (mm) A B C (degrees, |A|, |B|, |C| at most 360),\n"
    "  one line, full precision\n" USAGE_TOOL_OFFSET CLI_USAGE_MODEL;

const char cli_usage_fk[] =
    "usage: hexaglide fk [--guess X,Y,Z,A,B,C] [--tool-offset MM] [--ini FILE] [--set name=value]...\n"
    "                    J0 J1 J2 J3 J4 J5\n"
    "  prints the pose X Y Z (mm) A B C (degrees) of the joints J0..J5 (mm), one line\n"
    "  --guess X,Y,Z,A,B,C  where Newton-Raphson starts (default HOME, 0,0,0,0,0,0); six\n"
    "                       separate numbers (--guess X Y Z A B C) are taken too; |X|, |Y|, |Z| at most\n"
    "                       ten bar lengths, |A|, |B|, |C| at most 360 (with --tool-offset: of the tip)\n"
    USAGE_TOOL_OFFSET CLI_USAGE_MODEL;

enum { OPT_INI, OPT_SET, OPT_TOOL, OPT_GUESS };
static const cli_opt ik_opts[] = {{"--ini", 1}, {"--set", CLI_REPEAT}, {"--tool-offset", 1}, {0, 0}};
static const cli_opt fk_opts[] = {{"--ini", 1}, {"--set", CLI_REPEAT}, {"--tool-offset", 1}, {"--guess", 1}, {0, 0}};

/* What ik and fk share: the parsed command line. */
typedef struct {
    const char *ini;
    char **sets;               /* points into argv: at most argc entries */
    int nset, npos, guessed, nguess; /* nguess: numbers of a space-separated --guess read */
    double pos[6];             /* the six positional numbers */
    double guess[6];           /* user units */
    double tool_offset_m;      /* --tool-offset (hg_pose_offset_to_op) */
    hg_params p;
} kins_cmd;

/* 1 after a message if the --guess is beyond where Newton-Raphson can start: X Y Z farther than
 * GUESS_REACH bar lengths (1e308 mm gave a NaN residual), A B C beyond a turn. */
#define GUESS_REACH 10.0
static int guess_beyond(const char *cmd, const kins_cmd *c)
{
    double reach_mm = GUESS_REACH * c->p.geo.l_m * HG_MM_PER_M;
    int k;
    for (k = 0; k < 6; k++) {
        double bound = k < 3 ? reach_mm : 360.0;
        char v[CLI_NUM_LEN], b[CLI_NUM_LEN];
        if (fabs(c->guess[k]) <= bound)
            continue;
        fprintf(stderr, "hexaglide %s: --guess %s = %s %s is beyond where the solve can start (|%s| <= %s %s%s); "
                "give a guess near the pose\n", cmd, pose_names[k], cli_num(c->guess[k], v), k < 3 ? "mm" : "deg",
                pose_names[k], cli_num(bound, b), k < 3 ? "mm" : "deg", k < 3 ? ": ten bar lengths" : ": a turn");
        return 1;
    }
    return 0;
}

/* Parse the arguments and build the geometry; 0, or the exit code (0 for
 * --help after printing it: *done set). */
static int kins_parse(const char *cmd, const char *usage, const cli_opt *opts, const char *const names[6],
                      const char *what, int argc, char **argv, kins_cmd *c, char **sets, int *done)
{
    cli_args a;
    const char *v;
    int o;
    *done = 0;
    memset(c, 0, sizeof *c);
    c->sets = sets;
    cli_args_init(&a, cmd, usage, opts, argc, argv);
    while ((o = cli_next(&a, &v)) != CLI_DONE) {
        if (o == CLI_HELP) {
            *done = 1;
            return 0;
        }
        if (o == CLI_BAD)
            return 2;
        if (o == CLI_ARG && c->guessed && c->nguess < 6) {   /* --guess X Y Z A B C */
            if (cli_parse_double(cmd, v, guess_names[c->nguess], &c->guess[c->nguess]))
                return 2;
            c->nguess++;
        } else if (o == CLI_ARG) {
            if (c->npos == 6) {
                fprintf(stderr, "hexaglide %s: need 6 numbers %s, got more ('%s')%s\n", cmd, what, v,
                        opts == fk_opts ? "; --guess takes X,Y,Z,A,B,C as one comma-separated argument" : "");
                return 2;
            }
            if (cli_parse_double(cmd, v, names[c->npos], &c->pos[c->npos]))
                return 2;
            c->npos++;
        } else if (o == OPT_INI) {
            c->ini = v;                /* (once: cli_next refuses a second) */
        } else if (o == OPT_SET) {
            c->sets[c->nset++] = (char *)v;
        } else if (o == OPT_TOOL) {
            if (cli_parse_double(cmd, v, "--tool-offset", &c->tool_offset_m))
                return 2;
            c->tool_offset_m /= HG_MM_PER_M;
        } else if (strchr(v, ',')) {  /* OPT_GUESS (only in fk_opts): X,Y,Z,A,B,C */
            if (cli_parse_list(cmd, "--guess", v, pose_names, 6, c->guess))
                return 2;
            c->guessed = 1;
            c->nguess = 6;
        } else {                       /* OPT_GUESS X, the other five follow */
            if (cli_parse_double(cmd, v, guess_names[0], &c->guess[0]))
                return 2;
            c->guessed = 1;
            c->nguess = 1;
        }
    }
    if (c->guessed && c->nguess != 6) {
        fprintf(stderr, "hexaglide %s: --guess needs 6 numbers X Y Z (mm) A B C (deg), got %d\n", cmd, c->nguess);
        return 2;
    }
    if (c->npos != 6) {
        fprintf(stderr, "hexaglide %s: need 6 numbers %s, got %d\n", cmd, what, c->npos);
        return 2;
    }
    if (cli_hexaglide_params(cmd, c->ini, c->sets, c->nset, &c->p))
        return 2;
    if (hg_tool_offset_check(&c->p.geo, c->tool_offset_m) != HG_OK) {
        char v[CLI_NUM_LEN], b[CLI_NUM_LEN];
        fprintf(stderr, "hexaglide %s: --tool-offset %s mm is not a tool length: at most %s mm either way "
                "(%.0f bar lengths)\n", cmd, cli_num(c->tool_offset_m * HG_MM_PER_M, v),
                cli_num(HG_MAX_ABS_POSITION_BARS * c->p.geo.l_m * HG_MM_PER_M, b), HG_MAX_ABS_POSITION_BARS);
        return 2;
    }
    return c->guessed && guess_beyond(cmd, c) ? 2 : 0;
}

int cmd_ik(int argc, char **argv)
{
    kins_cmd c;
    char *sets[argc > 0 ? argc : 1];
    hg_guard_report guard;
    double commanded[6], pose[6], z[6];
    int rc, k, done;
    rc = kins_parse("ik", cli_usage_ik, ik_opts, pose_names, "X Y Z (mm) A B C (deg)", argc, argv, &c, sets, &done);
    if (rc || done)
        return rc;
    for (k = 3; k < 6; k++)           /* beyond a turn, deg to rad loses whole degrees (1e17 deg is not 280) */
        if (fabs(c.pos[k]) > 360.0) {
            char v[CLI_NUM_LEN];
            fprintf(stderr, "hexaglide ik: %s = %s deg is beyond a turn (|%s| <= 360 deg); give the angle within "
                    "a turn\n", pose_names[k], cli_num(c.pos[k], v), pose_names[k]);
            return 2;
        }
    hg_pose_from_user(c.pos, commanded);
    hg_pose_offset_to_op(commanded, c.tool_offset_m, pose);
    rc = hg_inverse_kinematics_guarded(&c.p.geo, pose, z, &guard);
    if (rc) {
        char what[HG_GUARD_TEXT_LEN], b[CLI_NUM_LEN];
        hg_guard_describe(&guard, 0, what);
        if (rc == HG_ERR_EULER_SINGULAR)   /* the value refused */
            snprintf(what, sizeof what, "B = %s deg; give |B| <= %.0f", cli_num(c.pos[4], b),
                     HG_MAX_ABS_B_RAD * HG_DEG_PER_RAD);
        if (rc == HG_ERR_UNREACHABLE)
            snprintf(what, sizeof what, "the pose lies outside the working volume; give one nearer HOME "
                     "(0 0 0 0 0 0), or longer bars (--set l)");
        fprintf(stderr, "hexaglide ik: %s (code %d)%s%s\n", hg_strerror(rc), rc, what[0] ? ": " : "", what);
        return 1;
    }
    for (k = 0; k < 6; k++)
        printf("%.17g%c", z[k] * HG_MM_PER_M, k < 5 ? ' ' : '\n');
    return 0;
}

int cmd_fk(int argc, char **argv)
{
    kins_cmd c;
    char *sets[argc > 0 ? argc : 1];
    hg_fk_report rep;
    double user[6], z[6], guess[6] = {0, 0, 0, 0, 0, 0}, pose[6];
    int rc, k, done;
    rc = kins_parse("fk", cli_usage_fk, fk_opts, joint_names, "J0..J5 (mm)", argc, argv, &c, sets, &done);
    if (rc || done)
        return rc;
    for (k = 0; k < 6; k++)
        z[k] = c.pos[k] / HG_MM_PER_M;
    if (c.guessed)
        hg_pose_from_user(c.guess, guess);
    hg_pose_offset_to_op(guess, c.tool_offset_m, pose);
    rc = hg_forward_kinematics(&c.p.geo, z, pose, 0, &rep);
    if (rc) {
        char what[HG_GUARD_TEXT_LEN];
        hg_guard_describe(&rep.guard, 0, what);
        char res[48] = "residual not finite";   /* (no NaN in a message) */
        if (isfinite(rep.residual_m))
            snprintf(res, sizeof res, "residual %.3g mm", rep.residual_m * HG_MM_PER_M);
        if (!what[0] && rc != HG_ERR_NONFINITE_INPUT && rc != HG_ERR_OUT_OF_RANGE) /* the solve's own failure */
            snprintf(what, sizeof what, "these joints are no pose of the machine, or the solve started too far "
                     "from it; give --guess X Y Z (mm) A B C (deg) near the pose (the default guess is HOME)");
        fprintf(stderr, "hexaglide fk: %s (code %d, %d iterations, %s)%s%s\n", hg_strerror(rc), rc, rep.iterations,
                res, what[0] ? ": " : "", what);
        return 1;
    }
    hg_pose_op_to_offset(pose, c.tool_offset_m, guess);
    hg_pose_to_user(guess, user);
    for (k = 0; k < 6; k++)
        printf("%.17g%c", user[k], k < 5 ? ' ' : '\n');
    return 0;
}
