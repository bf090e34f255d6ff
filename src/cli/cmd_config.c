/* cmd_config.c - the config subcommand: a LinuxCNC INI as build/hexaglide
 * reads it (cli_ini.c: LinuxCNC's reading, with what LinuxCNC resolves
 * silently refused), printed one value a line for the Python tools (tune,
 * excite: tools/hg_config.py), so that they take the machine, the servo
 * loops and the limits from the same reader as sim and soak:
 *   param NAME VALUE       every model parameter of the Hexaglide (spec name, SI,
 *                          %.17g: the double itself) after the defaults, [HEXAGLIDE]
 *                          and --set, checked as soak checks them
 *   joint N KEY VALUE      [JOINT_N]: with --loop the servo loop's keys as soak reads and
 *                          checks them (cli_ini_servo_loops: the loop's rules, SERVO_PERIOD
 *                          at most the board's 10 ms; FERROR and MIN_FERROR too); MIN_LIMIT
 *                          MAX_LIMIT MAX_VELOCITY MAX_ACCELERATION where given
 *   axis A KEY VALUE       [AXIS_A] MIN_LIMIT MAX_LIMIT MAX_VELOCITY MAX_ACCELERATION
 *                          where given
 *   servo_period_ns N      [EMCMOT]SERVO_PERIOD where given
 * A limit pair must have MIN_LIMIT < MAX_LIMIT, a MAX_VELOCITY and a
 * MAX_ACCELERATION must be > 0: the key, file and line of a refused value
 * named, exit 2, nothing on stdout. */
#include <stdio.h>
#include <string.h>
#include "cli.h"

const char cli_usage_config[] =
    "usage: hexaglide config [--plant NAME] [--model M] [--ini FILE] [--set name=value]... [--loop]\n"
    "  the config as build/hexaglide reads it (src/cli/cli_ini.c), one value a line, as tune and\n"
    "  excite take it (tools/hg_config.py): 'param NAME VALUE' for every model parameter (spec\n"
    "  name, SI) after the defaults, [HEXAGLIDE] (each key hexaglide.hal reads required) and\n"
    "  --set, checked as soak checks them;\n"
    "  'joint N KEY VALUE' and 'axis A KEY VALUE' for the limits MIN_LIMIT MAX_LIMIT\n"
    "  MAX_VELOCITY MAX_ACCELERATION where given; 'servo_period_ns N'.\n"
    "  --loop      also [JOINT_0..5]'s servo loops as soak reads them (P I D FF0 FF1 FF2 FF3\n"
    "              BIAS DEADBAND MAX_OUTPUT MAX_ERROR_I INPUT_SCALE OUTPUT_SCALE OUTPUT_OFFSET,\n"
    "              every key configs/hexaglide.hal sets required; FERROR MIN_FERROR MAX_VELOCITY)\n"
    "              as 'joint N KEY VALUE' lines, checked as soak checks them (the same function:\n"
    "              a gain beyond 1e9, a negative DEADBAND, MAX_OUTPUT or MAX_ERROR_I, a\n"
    "              SERVO_PERIOD above the board's 10 ms refused)\n"
    "  Default --ini: configs/hexaglide.ini of the source tree this hexaglide was built in.\n"
    "  A value that is not a finite number, a key given twice, MIN_LIMIT >= MAX_LIMIT or a\n"
    "  MAX_VELOCITY or MAX_ACCELERATION <= 0: named with its line, exit 2.\n"
    "  --plant NAME, --model M  another plant's parameters (its INI section, e.g. [SERIAL] of\n"
    "              plant serial, the model's axes; docs/serial.md) and its joints' limits; with\n"
    "              --loop its joints' servo-loop keys where given (its HAL file is not ours: none\n"
    "              required). Default: the hexaglide.\n"
    CLI_USAGE_MODEL;

enum { OPT_INI, OPT_SET, OPT_LOOP, OPT_PLANT, OPT_MODEL };
static const cli_opt config_opts[] = {{"--ini", 1}, {"--set", CLI_REPEAT}, {"--loop", 0}, {"--plant", 1}, {"--model", 1},
                                      {0, 0}};

static const char *const limit_keys[] = {"MIN_LIMIT", "MAX_LIMIT", "MAX_VELOCITY", "MAX_ACCELERATION"};

/* The limits of [sec] printed as "what id KEY VALUE" lines into out (held until every
 * check passed); 0 or -1 after naming each bad value. */
static int limits(const cli_ini *ini, const char *sec, const char *what, const char *id, FILE *out)
{
    double v[4];
    int line[4], got[4], k, bad = 0, n = 4;
    for (k = 0; k < n; k++) {
        int rc = cli_ini_optional("config", ini, sec, limit_keys[k], &v[k], &line[k]);
        got[k] = rc == 0;
        bad |= rc < 0;
    }
    if (bad)
        return -1;
    if (got[0] && got[1] && !(v[0] < v[1])) {
        char lo[CLI_NUM_LEN], hi[CLI_NUM_LEN];
        fprintf(stderr, "hexaglide config: %s: [%s] MIN_LIMIT = %s (line %d) is not below MAX_LIMIT = %s (line %d): "
                "the range is empty; give MIN_LIMIT < MAX_LIMIT\n", ini->path, sec, cli_num(v[0], lo), line[0],
                cli_num(v[1], hi), line[1]);
        bad = 1;
    }
    for (k = 2; k < n; k++)
        if (got[k] && !(v[k] > 0)) {
            fprintf(stderr, "hexaglide config: %s line %d: [%s]%s = %g must be > 0\n", ini->path, line[k], sec,
                    limit_keys[k], v[k]);
            bad = 1;
        }
    for (k = 0; k < n && !bad; k++)
        if (got[k])
            fprintf(out, "%s %s %s %.17g\n", what, id, limit_keys[k], v[k]);
    return bad ? -1 : 0;
}

int cmd_config(int argc, char **argv)
{
    cli_args a;
    cli_ini ini;
    hg_plant_params p;
    hg_board_params bp;
    hg_loop_config c;
    cli_ferror_rule rule[HG_LOOP_JOINTS];
    char default_ini[4096], *sets[argc > 0 ? argc : 1], buf[1 << 15];
    const char *path = 0, *v, *model = 0;
    int plant = 0, variant, joints;
    int o, nset = 0, loop = 0, loop_bad = 0, bad = 0, stiff = 0, i, j, n;
    long servo_ns;
    FILE *out;
    cli_args_init(&a, "config", cli_usage_config, config_opts, argc, argv);
    while ((o = cli_next(&a, &v)) != CLI_DONE) {
        if (o == CLI_HELP)
            return 0;
        if (o == CLI_BAD)
            return 2;
        if (o == CLI_ARG) {
            fprintf(stderr, "hexaglide config: unexpected argument '%s' ('hexaglide config --help' lists the "
                    "options)\n", v);
            return 2;
        }
        if (o == OPT_INI)
            path = v;                  /* (once: cli_next refuses a second) */
        if (o == OPT_SET)
            sets[nset++] = (char *)v;
        if (o == OPT_LOOP)
            loop = 1;
        if (o == OPT_PLANT && (plant = cli_plant("config", v)) < 0)
            return 2;
        if (o == OPT_MODEL)
            model = v;
    }
    if ((variant = cli_variant("config", plant, model)) < 0)
        return 2;
    joints = hg_plant_at(plant)->channels(variant);
    if (!path) {
        if (cli_tree_path("configs/hexaglide.ini", default_ini, sizeof default_ini)) {
            fprintf(stderr, "hexaglide config: no config beside this program (../configs/hexaglide.ini): give "
                    "--ini FILE\n");
            return 2;
        }
        path = default_ini;
    }
    if (cli_params_build("config", plant, variant, path, sets, nset, &p) ||
        cli_params_check_from("config", plant, variant, &p, path, sets, nset))
        return 2;
    if (cli_ini_read("config", path, &ini))
        return 2;
    out = fmemopen(buf, sizeof buf, "w");   /* nothing on stdout unless every check passed */
    if (!out) {
        cli_ini_free(&ini);
        fprintf(stderr, "hexaglide config: out of memory\n");
        return 1;
    }
    n = hg_plant_at(plant)->nparams(variant);
    for (i = 0; i < n; i++) {
        hg_param_info e;
        hg_plant_param_at(plant, variant, i, &e);
        fprintf(out, "param %s %.17g\n", e.name, p.v[i]);
    }
    if (loop && plant != 0) {          /* another plant's loops: the keys given, each read as LinuxCNC reads it */
        static const char *const rule_keys[] = {"FERROR", "MIN_FERROR", "MAX_VELOCITY"};
        for (j = 0; j < joints; j++) {
            char sec[24];
            double x;
            snprintf(sec, sizeof sec, "JOINT_%d", j);
            if (!cli_ini_has_section(&ini, sec)) {
                fprintf(stderr, "hexaglide config: %s has no [%s] section (joint %d of model %s: its servo "
                        "loop's gains and scales)\n", path, sec, j, model ? model : "(default)");
                bad = 1;
                continue;
            }
            for (i = 0; cli_ini_joint_key(i); i++) {
                int rc = cli_ini_optional("config", &ini, sec, cli_ini_joint_key(i), &x, 0);
                bad |= rc < 0;
                if (rc == 0)
                    fprintf(out, "joint %d %s %.17g\n", j, cli_ini_joint_key(i), x);
            }
            for (i = 0; i < 2; i++) {  /* (MAX_VELOCITY: a limit, printed below) */
                int rc = cli_ini_optional("config", &ini, sec, rule_keys[i], &x, 0);
                bad |= rc < 0;
                if (rc == 0)
                    fprintf(out, "joint %d %s %.17g\n", j, rule_keys[i], x);
            }
        }
    } else if (loop) {                 /* the servo loops as soak reads and checks them */
        hg_loop_config_default(&c);
        c.variant = variant;
        if (cli_ini_servo_loops("config", &ini, 0, 0, &c, rule))
            bad = loop_bad = 1;        /* (SERVO_PERIOD read and named there: not again below) */
        for (j = 0; j < 6 && !bad; j++) {
            char sec[16];
            snprintf(sec, sizeof sec, "JOINT_%d", j);
            for (i = 0; cli_ini_joint_key(i); i++) {
                double x;
                if (cli_ini_optional("config", &ini, sec, cli_ini_joint_key(i), &x, 0) == 0)
                    fprintf(out, "joint %d %s %.17g\n", j, cli_ini_joint_key(i), x);
            }
            fprintf(out, "joint %d FERROR %.17g\njoint %d MIN_FERROR %.17g\n", j, rule[j].ferror, j,
                    rule[j].min_ferror);
        }
    }
    for (j = 0; j < joints && !bad; j++) {  /* (after a refused loop: its keys are named already) */
        char sec[24], id[12];
        snprintf(sec, sizeof sec, "JOINT_%d", j);
        snprintf(id, sizeof id, "%d", j);
        bad |= limits(&ini, sec, "joint", id, out) != 0;
    }
    for (j = 0; j < 6; j++) {
        char sec[16], id[2] = {"XYZABC"[j], 0};
        snprintf(sec, sizeof sec, "AXIS_%c", "XYZABC"[j]);
        bad |= limits(&ini, sec, "axis", id, out) != 0;
    }
    i = loop_bad ? -1 : cli_ini_servo_period("config", &ini, &servo_ns, 0);
    bad |= i < 0;
    if (i == 0)
        fprintf(out, "servo_period_ns %ld\n", servo_ns);
    cli_board_defaults(plant, variant, &bp);   /* the machine as the board integrates it at the config's period */
    bp.plant = p;
    if (i >= 0 && !bad)                /* the machine, from the INI's [HEXAGLIDE] and the --set values */
        stiff = cli_board_integrable("config", plant, variant, &bp, i == 0 ? servo_ns : 1000000L, sets, nset);
    cli_ini_free(&ini);
    if (fclose(out) || strlen(buf) >= sizeof buf - 1) {
        fprintf(stderr, "hexaglide config: the output does not fit %zu bytes\n", sizeof buf);
        return 1;
    }
    if (bad)
        fprintf(stderr, "hexaglide config: fix %s (or give another with --ini)\n", path);
    if (bad || stiff)
        return 2;
    fputs(buf, stdout);
    return 0;
}
