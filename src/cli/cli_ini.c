/* cli_ini.c - a LinuxCNC INI file read as LinuxCNC's IniFile reads it
 * (src/libnml/inifile/inifile.cc, commit f1270d6ed7): "[SECTION]" lines,
 * "KEY = VALUE" with white space trimmed, a trailing backslash joins the
 * next line, nothing after the value is a comment (so "1000 # mm" is not a
 * number). What LinuxCNC would resolve silently is refused here, naming the
 * file and line: a key given twice (LinuxCNC takes the first), an
 * #INCLUDE (the linuxcnc script expands those into FILE.expanded).
 * Host only (malloc, stdio). Two consumers: a plant's section ([HEXAGLIDE])
 * -> model parameters (ik, fk, sim, soak) and [JOINT_N] -> the servo loops
 * (soak, replay). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"

#define INI_MAX_BYTES (16L << 20)   /* refuse INI files above 16 MiB */

/* Keys of a plant's section that are no model parameter (the parameters'
 * keys are the plant table's ini_key, their values in the HAL unit). */
static const char *const other_keys[] = {
    "RECORD",   /* tools/hg_record.tcl's record file (docs/replay.md) */
};

/* Keys of earlier versions, with what to do instead. */
static const struct {
    const char *section, *key, *instead;
} gone_keys[] = {
    {"HEXAGLIDE", "H", "the carriage height at HOME follows from L, LB and LP now: remove the key"},
};

/* [JOINT_N] keys -> servo-loop settings, as configs/hexaglide.hal wires
 * them. The pid.N settings with an INI key come from src/hg_pid.c's table
 * (hg_pid_setting_at: the key, the pin, the field); the three loop scales
 * below are hg_loop_config's double[6] arrays. The keys tools/hexaglide_tune.py
 * reads (through `hexaglide config --loop`, the same function as soak). A
 * key the HAL file sets must be there (halcmd stops at a setp of a missing
 * key: "Ini variable '[JOINT_0]P' not found"), except those in
 * unwired_keys: hexaglide.hal does not wire pid.N.FF3, so pid.c's 0 stays
 * when it is absent. */
static const struct {
    const char *key;
    size_t offset;             /* offsetof(hg_loop_config, the array) */
    const char *pin;           /* what hexaglide.hal sets from the key ("%02d": the joint's channel) */
} scale_keys[] = {
    {"INPUT_SCALE", offsetof(hg_loop_config, input_scale), "motenc.0.enc-%02d-scale"},
    {"OUTPUT_SCALE", offsetof(hg_loop_config, output_scale), "motenc.0.dac-%02d-gain"},
    {"OUTPUT_OFFSET", offsetof(hg_loop_config, output_offset), "motenc.0.dac-%02d-offset"},
};
static const char *const unwired_keys[] = {"FF3"};

#define N_OF(a) (sizeof(a) / sizeof((a)[0]))

/* Pointer to the first non-blank character of s. */
static char *skip_blank(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    return s;
}

/* Cut trailing blanks (and a CR) off s in place. */
static void trim_end(char *s)
{
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r'))
        s[--n] = '\0';
}

/* The file as text into *text (malloc'd); 0 or -1 with a message. */
static int slurp(const char *cmd, const char *path, char **text)
{
    size_t len;
    if (cli_read_file(cmd, path, "a LinuxCNC INI file", INI_MAX_BYTES, text, &len))
        return -1;
    if (memchr(*text, '\0', len)) {
        fprintf(stderr, "hexaglide %s: %s: holds NUL bytes: not an INI file\n", cmd, path);
        free(*text);
        return -1;
    }
    return 0;
}

/* Append an entry; 0 or -1 (out of memory, message printed). */
static int add_entry(const char *cmd, cli_ini *ini, const char *section, int section_line, char *key,
                     char *value, int line)
{
    if (ini->n % 64 == 0) {
        cli_ini_entry *e = realloc(ini->e, (size_t)(ini->n + 64) * sizeof *e);
        if (!e) {
            fprintf(stderr, "hexaglide %s: --ini %s: out of memory\n", cmd, ini->path);
            return -1;
        }
        ini->e = e;
    }
    ini->e[ini->n].section = section;
    ini->e[ini->n].key = key;
    ini->e[ini->n].value = value;
    ini->e[ini->n].line = line;
    ini->e[ini->n].section_line = section_line;
    ini->n++;
    return 0;
}

int cli_ini_read(const char *cmd, const char *path, cli_ini *ini)
{
    char *p, *section = 0;
    int line = 0, section_line = 0;
    memset(ini, 0, sizeof *ini);
    ini->path = path;
    if (slurp(cmd, path, &ini->text))
        return -1;
    p = ini->text;
    if (strncmp(p, "\xEF\xBB\xBF", 3) == 0) { /* a UTF-8 byte order mark, as some editors write */
        fprintf(stderr, "hexaglide %s: %s starts with a UTF-8 byte order mark: LinuxCNC would not see its "
                "first section; save it without one (sed -i '1s/^\\xEF\\xBB\\xBF//' FILE)\n", cmd, path);
        cli_ini_free(ini);
        return -1;
    }
    if (strchr(p, '\r') && !strchr(p, '\n')) {
        fprintf(stderr, "hexaglide %s: %s has carriage returns and no line feeds (old Mac line ends): "
                "LinuxCNC reads it as one line; convert it (tr '\\r' '\\n' < FILE)\n", cmd, path);
        cli_ini_free(ini);
        return -1;
    }
    while (*p) {
        char *start = p, *s, *eq, *w, *r;
        int first = ++line;
        /* the logical line: physical lines joined where one ends in a backslash */
        for (w = r = p;; ) {
            if (*r == '\n' || *r == '\0') {
                if (r > p && r[-1] == '\\' && *r == '\n') {   /* drop "\\\n", go on */
                    w--;
                    r++;
                    line++;
                    continue;
                }
                p = *r ? r + 1 : r;
                *w = '\0';
                break;
            }
            *w++ = *r++;
        }
        trim_end(start);
        s = skip_blank(start);
        if (*s == '\0')
            continue;
        if (strncmp(s, "#INCLUDE", 8) == 0) {
            fprintf(stderr, "hexaglide %s: %s line %d: #INCLUDE is expanded by the linuxcnc script, not "
                    "here: give the expanded file (linuxcnc writes it as %s.expanded)\n", cmd, path, first, path);
            cli_ini_free(ini);
            return -1;
        }
        if (*s == '#' || *s == ';')
            continue;
        if (*s == '[') {
            char *close = strchr(s, ']');
            if (!close) {
                fprintf(stderr, "hexaglide %s: %s line %d: '%s' opens a section without closing ']'\n", cmd, path,
                        first, s);
                cli_ini_free(ini);
                return -1;
            }
            *close = '\0';
            section = s + 1;
            section_line = first;
            if (add_entry(cmd, ini, section, first, 0, 0, first)) {   /* the header itself */
                cli_ini_free(ini);
                return -1;
            }
            continue;
        }
        eq = strchr(s, '=');
        if (eq) {
            *eq = '\0';
            trim_end(s);
        }
        if (add_entry(cmd, ini, section ? section : "", section_line, s, eq ? skip_blank(eq + 1) : 0, first)) {
            cli_ini_free(ini);
            return -1;
        }
    }
    return 0;
}

void cli_ini_free(cli_ini *ini)
{
    free(ini->e);
    free(ini->text);
    ini->e = 0;
    ini->text = 0;
    ini->n = 0;
}

/* Line of the first "[section]" header, or 0 if there is none. */
static int section_first_line(const cli_ini *ini, const char *section)
{
    int i;
    for (i = 0; i < ini->n; i++)
        if (!ini->e[i].key && strcmp(ini->e[i].section, section) == 0)
            return ini->e[i].line;
    return 0;
}

int cli_ini_has_section(const cli_ini *ini, const char *section)
{
    return section_first_line(ini, section) > 0;
}

const hg_plant *cli_ini_other_plant(const cli_ini *ini, int plant)
{
    const hg_plant *p;
    int i;
    if (!hg_plant_at(plant) || cli_ini_has_section(ini, hg_plant_at(plant)->ini_section))
        return 0;
    for (i = 0; (p = hg_plant_at(i)) != 0; i++)
        if (i != plant && p->ini_section && cli_ini_has_section(ini, p->ini_section))
            return p;
    return 0;
}

int cli_ini_plant_only(const char *cmd, const cli_ini *ini, int plant)
{
    const hg_plant *other = cli_ini_other_plant(ini, plant), *pl = hg_plant_at(plant);
    if (!other)
        return 0;
    fprintf(stderr, "hexaglide %s: %s is a config of plant %s (no [%s] section): %s runs the %s only; run that "
            "machine with sim --plant %s, or give a config of the %s\n", cmd, ini->path, other->name, pl->ini_section,
            cmd, pl->name, other->name, pl->name);
    return -1;
}

int cli_ini_get(const char *cmd, const cli_ini *ini, const char *section, const char *key,
                const cli_ini_entry **out)
{
    int i, head = section_first_line(ini, section);
    *out = 0;
    for (i = 0; i < ini->n; i++) {
        const cli_ini_entry *e = &ini->e[i];
        if (!e->key || strcmp(e->section, section) != 0 || strcmp(e->key, key) != 0)
            continue;
        if (e->section_line != head) {
            fprintf(stderr, "hexaglide %s: [%s]%s (line %d of %s) is in a second [%s] section (line %d); "
                    "LinuxCNC reads only the first one (line %d): merge them\n", cmd, section, key, e->line,
                    ini->path, section, e->section_line, head);
            return -1;
        }
        if (*out) {
            fprintf(stderr, "hexaglide %s: [%s]%s is given twice (lines %d and %d of %s); LinuxCNC would "
                    "use the first: remove one\n", cmd, section, key, (*out)->line, e->line, ini->path);
            return -1;
        }
        *out = e;
    }
    return *out ? 0 : 1;
}

int cli_ini_number(const char *cmd, const cli_ini *ini, const cli_ini_entry *e, double *v)
{
    if (!e->value) {
        fprintf(stderr, "hexaglide %s: %s line %d: [%s]%s has no '= value'\n", cmd, ini->path, e->line,
                e->section, e->key);
        return -1;
    }
    int rc = cli_strtod(e->value, v);
    if (rc) {
        fprintf(stderr, "hexaglide %s: %s line %d: [%s]%s = '%s' is not a finite number%s%s\n", cmd, ini->path,
                e->line, e->section, e->key, e->value, cli_strtod_hint(rc),
                strpbrk(e->value, "#;") ? " (LinuxCNC takes everything after '=' as the value: put comments "
                                          "on their own line)" : "");
        return -1;
    }
    return 0;
}

/* Index of the parameter of table t[0..n) whose key is key, or -1. */
static int param_of_key(const hg_param_info *t, int n, const char *key)
{
    int i;
    for (i = 0; i < n; i++)
        if (t[i].ini_key && strcmp(t[i].ini_key, key) == 0)
            return i;
    return -1;
}

/* 1 if key belongs to the section: a parameter's ini_key or another key. */
static int known_key(const hg_param_info *t, int n, const char *key)
{
    size_t k;
    if (param_of_key(t, n, key) >= 0)
        return 1;
    for (k = 0; k < N_OF(other_keys); k++)
        if (strcmp(other_keys[k], key) == 0)
            return 1;
    return 0;
}

/* The known keys of table t as "L LB ..." into buf. */
static void key_list(const hg_param_info *t, int n, char *buf, size_t len)
{
    int i;
    size_t k, used = 0;
    buf[0] = '\0';
    for (i = 0; i < n && used < len; i++)
        if (t[i].ini_key)
            used += (size_t)snprintf(buf + used, len - used, "%s%s", used ? " " : "", t[i].ini_key);
    for (k = 0; k < N_OF(other_keys) && used < len; k++)
        used += (size_t)snprintf(buf + used, len - used, " %s", other_keys[k]);
}

/* 0 if the INI's [KINS]JOINTS (when given) is the model's channels, one
 * joint each; else -1 with the cause named (a 3-joint INI read for model
 * XYZA would leave A on its defaults, or refuse every key of axis 2 of XY). */
static int joints_match(const char *cmd, const cli_ini *ini, int plant, int variant)
{
    const hg_plant *pl = hg_plant_at(plant);
    const cli_ini_entry *e;
    char name[HG_PLANT_TEXT_LEN];
    double j;
    int rc = cli_ini_get(cmd, ini, "KINS", "JOINTS", &e), n = pl->channels(variant);
    if (rc)
        return rc < 0 ? -1 : 0;
    if (cli_ini_number(cmd, ini, e, &j))
        return -1;
    if (j == n)
        return 0;
    fprintf(stderr, "hexaglide %s: %s line %d: [KINS]JOINTS = %s, but model %s of the %s drives %d channels, one "
            "per joint: give --model with one axis per joint (the INI's [TRAJ]COORDINATES), or fix JOINTS\n",
            cmd, ini->path, e->line, e->value, cli_variant_name(plant, variant, name), pl->name, n);
    return -1;
}

int cli_ini_apply_plant(const char *cmd, const cli_ini *ini, int plant, int variant, hg_plant_params *v)
{
    const hg_plant *pl = hg_plant_at(plant);
    /* a section a shipped HAL file reads in full (hg_plant.ini_hal_file): halcmd stops at the first line
     * that reads a missing key ("Ini variable '[HEXAGLIDE]L' not found"), so a missing key is refused,
     * never left at its default, and so is a missing section */
    const char *sec = pl->ini_section, *hal = pl->ini_hal_file, *pins = pl->ini_hal_pins;
    static hg_param_info t[HG_PLANT_PARAMS_MAX];
    int i, n = pl->nparams(variant), bad = 0, listed = 0;
    char keys[4096];
    for (i = 0; i < n; i++)
        pl->param(variant, i, &t[i]);
    size_t k;
    key_list(t, n, keys, sizeof keys);
    if (!cli_ini_has_section(ini, sec)) {   /* --ini names the file of this plant's parameters */
        const hg_plant *other = cli_ini_other_plant(ini, plant);
        if (other)
            fprintf(stderr, "hexaglide %s: %s has no [%s] section but [%s]: it is a config of plant %s, not of "
                    "the %s: give --plant %s\n", cmd, ini->path, sec, other->ini_section, other->name, pl->name,
                    other->name);
        else if (hal) {
            size_t used = 0;           /* the parameters' keys alone (keys: with the other keys) */
            keys[0] = '\0';
            for (i = 0; i < n && used < sizeof keys; i++)
                if (t[i].ini_key)
                    used += (size_t)snprintf(keys + used, sizeof keys - used, "%s%s", used ? " " : "", t[i].ini_key);
            fprintf(stderr, "hexaglide %s: %s has no [%s] section (the machine's parameters, keys %s: %s reads "
                    "every one, and LinuxCNC stops at the first it lacks): add it (configs/hexaglide.ini has the "
                    "UPNa machine's), or drop --ini\n", cmd, ini->path, sec, keys, hal);
        } else
            fprintf(stderr, "hexaglide %s: %s has no [%s] section (the parameters of plant %s, keys %s ...): add "
                    "it, or drop --ini to run the defaults\n", cmd, ini->path, sec, pl->name,
                    t[0].ini_key ? t[0].ini_key : "");
        return -2;                     /* (not a section to fix: what to do is said) */
    }
    if (joints_match(cmd, ini, plant, variant))
        return -1;
    for (i = 0; i < ini->n; i++) {     /* every key of the section is one of ours */
        const cli_ini_entry *e = &ini->e[i];
        if (!e->key || strcmp(e->section, sec) != 0)
            continue;
        for (k = 0; k < N_OF(gone_keys); k++)
            if (strcmp(gone_keys[k].section, sec) == 0 && strcmp(gone_keys[k].key, e->key) == 0)
                break;
        if (k < N_OF(gone_keys)) {
            fprintf(stderr, "hexaglide %s: %s line %d: [%s]%s: %s\n", cmd, ini->path, e->line, sec,
                    e->key, gone_keys[k].instead);
            bad = 1;
        } else if (!known_key(t, n, e->key)) {   /* the keys it takes listed once, at the first */
            fprintf(stderr, "hexaglide %s: %s line %d: [%s]%s is not a key of this section; %s%s\n",
                    cmd, ini->path, e->line, sec, e->key, listed ? "(the keys it takes: above)" : "it takes ",
                    listed ? "" : keys);
            bad = listed = 1;
        }
    }
    for (k = 0; k < N_OF(other_keys); k++) {   /* keys that are no parameter: given once */
        const cli_ini_entry *e;
        bad |= cli_ini_get(cmd, ini, sec, other_keys[k], &e) < 0;
    }
    for (i = 0; i < n; i++) {          /* the parameters that have a key, in their HAL unit */
        const cli_ini_entry *e;
        double x;
        int rc = t[i].ini_key ? cli_ini_get(cmd, ini, sec, t[i].ini_key, &e) : 1;
        bad |= rc < 0;
        if (rc > 0 && t[i].ini_key && hal) {   /* LinuxCNC would stop at the HAL file's first line that reads it */
            char set[128];
            snprintf(set, sizeof set, pins, t[i].hal_name, t[i].hal_name);
            fprintf(stderr, "hexaglide %s: %s: [%s]%s is missing (the section starts at line %d): %s sets %s from "
                    "it (LinuxCNC stops there: \"Ini variable '[%s]%s' not found\"); add it (%s, %s)\n", cmd,
                    ini->path, sec, t[i].ini_key, section_first_line(ini, sec), hal, set, sec, t[i].ini_key,
                    t[i].what, t[i].hal_unit);
            bad = 1;
        }
        if (rc)
            continue;                  /* absent (a key no HAL file of ours reads: the default), or named */
        if (cli_ini_number(cmd, ini, e, &x)) {
            bad = 1;
            continue;
        }
        v->v[i] = x / t[i].hal_scale;
    }
    return bad ? -1 : 0;
}

/* One [JOINT_N] key: the key, the pin hexaglide.hal sets from it ("": none)
 * and where its double goes: at offset in joint j's hg_pid_gains (in_pid),
 * else in hg_loop_config's double[6] array at offset. */
typedef struct {
    const char *key;
    char pin[48];
    int in_pid;
    size_t offset;
} joint_key;

/* Joint key i (the pid settings with an INI key in hg_pid.c's order, then
 * the scales) for joint j: 1 with *k filled, or 0 past the last. */
static int joint_key_at(int i, int j, joint_key *k)
{
    const hg_pid_setting *s;
    size_t u;
    int n;
    for (n = 0; (s = hg_pid_setting_at(n)) != 0; n++) {
        if (!s->ini_key || s->kind == HG_PID_FLAG || i-- > 0)
            continue;                  /* (a flag is an int: none has a key) */
        k->key = s->ini_key;
        snprintf(k->pin, sizeof k->pin, "pid.%d.%s", j, s->pin);
        for (u = 0; u < N_OF(unwired_keys); u++)
            if (strcmp(s->ini_key, unwired_keys[u]) == 0)
                k->pin[0] = '\0';
        k->in_pid = 1;
        k->offset = s->offset;
        return 1;
    }
    if (i < 0 || (size_t)i >= N_OF(scale_keys))
        return 0;
    k->key = scale_keys[i].key;
    snprintf(k->pin, sizeof k->pin, scale_keys[i].pin, j);
    k->in_pid = 0;
    k->offset = scale_keys[i].offset + (size_t)j * sizeof(double);
    return 1;
}

int cli_ini_apply_joints(const char *cmd, const cli_ini *ini, int joints, hg_loop_config *c)
{
    int i, j, bad = 0;
    joint_key k;
    for (j = 0; j < joints && j < HG_LOOP_JOINTS; j++) {
        char sec[16];
        snprintf(sec, sizeof sec, "JOINT_%d", j);
        if (!cli_ini_has_section(ini, sec)) {
            fprintf(stderr, "hexaglide %s: %s has no [%s] section (the servo loop's gains and scales)\n", cmd,
                    ini->path, sec);
            bad = 1;
            continue;
        }
        for (i = 0; joint_key_at(i, j, &k); i++) {
            const cli_ini_entry *e;
            double v;
            int rc = cli_ini_get(cmd, ini, sec, k.key, &e);
            if (rc > 0 && k.pin[0]) {  /* LinuxCNC would stop at the HAL file's setp */
                fprintf(stderr, "hexaglide %s: %s: [%s]%s is missing: configs/hexaglide.hal sets %s from it "
                        "(LinuxCNC stops there: \"Ini variable '[%s]%s' not found\"); add it\n", cmd, ini->path,
                        sec, k.key, k.pin, sec, k.key);
                bad = 1;
                continue;
            }
            if (rc) {
                bad |= rc < 0;         /* absent FF3: pid.c's load-time 0 stays */
                continue;
            }
            if (cli_ini_number(cmd, ini, e, &v)) {
                bad = 1;
                continue;
            }
            memcpy((k.in_pid ? (char *)&c->pid[j] : (char *)c) + k.offset, &v, sizeof v);   /* a double field */
        }
    }
    return bad ? -1 : 0;
}

int cli_ini_joint_number(const char *cmd, const cli_ini *ini, int joint, const char *key, double *v)
{
    char sec[16];
    const cli_ini_entry *e;
    int rc;
    snprintf(sec, sizeof sec, "JOINT_%d", joint);
    rc = cli_ini_get(cmd, ini, sec, key, &e);
    if (rc > 0)
        fprintf(stderr, "hexaglide %s: %s: [%s]%s is missing\n", cmd, ini->path, sec, key);
    return rc ? -1 : cli_ini_number(cmd, ini, e, v);
}

int cli_ini_optional(const char *cmd, const cli_ini *ini, const char *section, const char *key, double *v,
                     int *line)
{
    const cli_ini_entry *e;
    int rc = cli_ini_get(cmd, ini, section, key, &e);
    if (rc)
        return rc;
    if (cli_ini_number(cmd, ini, e, v))
        return -1;
    if (line)
        *line = e->line;
    return 0;
}

int cli_ini_servo_period(const char *cmd, const cli_ini *ini, long *ns, int *line)
{
    double v;
    int l = 0, rc = cli_ini_optional(cmd, ini, "EMCMOT", "SERVO_PERIOD", &v, &l);
    char num[CLI_NUM_LEN];
    if (rc)
        return rc;
    if (line)
        *line = l;
    if (v >= 1.0 && v <= 9.0e15 && v == floor(v)) {   /* (an integer as LinuxCNC's motmod takes it) */
        *ns = (long)v;
        return 0;
    }
    if (v >= 1.0 && v <= 9.0e15)
        fprintf(stderr, "hexaglide %s: %s line %d: [EMCMOT]SERVO_PERIOD = %s is not a whole number of ns "
                "(LinuxCNC's servo_period_nsec is an integer); give %.0f or %.0f\n", cmd, ini->path, l, cli_num(v, num),
                floor(v), ceil(v));
    else
        fprintf(stderr, "hexaglide %s: %s line %d: [EMCMOT]SERVO_PERIOD = %s is no period: give the servo "
                "thread's period in whole ns (1000000: 1 ms)\n", cmd, ini->path, l, cli_num(v, num));
    return -1;
}

const char *cli_ini_joint_key(int i)
{
    joint_key k;
    return joint_key_at(i, 0, &k) ? k.key : 0;
}

/* [JOINT_j]key's line (0 if absent): for the messages of checks after reading. */
static int joint_line(const cli_ini *ini, int j, const char *key)
{
    char sec[16];
    int i;
    snprintf(sec, sizeof sec, "JOINT_%d", j);
    for (i = 0; i < ini->n; i++)
        if (ini->e[i].key && strcmp(ini->e[i].section, sec) == 0 && strcmp(ini->e[i].key, key) == 0)
            return ini->e[i].line;
    return 0;
}

int cli_ini_loop(const char *cmd, const cli_ini *ini, int joints, hg_loop_config *c, cli_ferror_rule *r)
{
    static const char *const rule_keys[3] = {"FERROR", "MIN_FERROR", "MAX_VELOCITY"};
    int j, k, bad = cli_ini_apply_joints(cmd, ini, joints, c) != 0;
    for (j = 0; j < joints && j < HG_LOOP_JOINTS; j++) {
        for (k = 0; k < 3; k++) {
            double *f = k == 0 ? &r[j].ferror : k == 1 ? &r[j].min_ferror : &r[j].max_velocity;
            char sec[16];
            snprintf(sec, sizeof sec, "JOINT_%d", j);
            if (!cli_ini_has_section(ini, sec))
                continue;              /* named by cli_ini_apply_joints */
            bad |= cli_ini_joint_number(cmd, ini, j, rule_keys[k], f) != 0;
        }
    }
    if (bad)
        return -1;
    for (j = 0; j < joints && j < HG_LOOP_JOINTS; j++) {   /* each rule the loop needs, the failing key named */
        static const struct {
            const char *key, *rule;
        } need[4] = {
            {"INPUT_SCALE", "must not be 0 (counts per mm: the encoder's position is counts / scale)"},
            {"MAX_VELOCITY", "must be > 0 (mm/s: LinuxCNC's following-error limit scales FERROR by speed / it)"},
            {"FERROR", "must be >= 0 (mm)"},
            {"MIN_FERROR", "must be >= 0 (mm)"},
        };
        double val[4];
        val[0] = c->input_scale[j];
        val[1] = r[j].max_velocity;
        val[2] = r[j].ferror;
        val[3] = r[j].min_ferror;
        for (k = 0; k < 4; k++)
            if (!(k == 0 ? val[k] != 0 : k == 1 ? val[k] > 0 : val[k] >= 0)) {
                fprintf(stderr, "hexaglide %s: %s line %d: [JOINT_%d]%s = %g %s\n", cmd, ini->path,
                        joint_line(ini, j, need[k].key), j, need[k].key, val[k], need[k].rule);
                bad = 1;
            }
    }
    return bad ? -1 : 0;
}

int cli_ini_servo_loops(const char *cmd, const cli_ini *ini, long period_ns, const char *period_opt, hg_loop_config *c,
                        cli_ferror_rule *r)
{
    hg_loop_check_report rep;
    long servo_ns = 1000000;           /* LinuxCNC's default servo period */
    int line = 0, bad = cli_ini_loop(cmd, ini, 6, c, r) != 0;   /* the Hexaglide's six, as hexaglide.hal wires them */
    bad |= cli_ini_servo_period(cmd, ini, &servo_ns, &line) < 0;   /* (read even when replaced: a broken value) */
    if (bad)
        return -1;
    if (period_ns <= 0 && servo_ns > HG_PERIOD_MAX_NS) {
        fprintf(stderr, "hexaglide %s: %s line %d: [EMCMOT]SERVO_PERIOD = %ld ns is longer than the board's longest "
                "period, %ld ns; give a shorter one%s%s\n", cmd, ini->path, line, servo_ns, HG_PERIOD_MAX_NS,
                period_opt ? " or " : "", period_opt ? period_opt : "");
        return -1;
    }
    c->period_ns = period_ns > 0 ? period_ns : servo_ns;
    if (hg_loop_config_check(c, &rep) == 0)
        return 0;
    if (rep.ini_key && rep.joint >= 0)
        fprintf(stderr, "hexaglide %s: %s: [JOINT_%d]%s = %.17g: %s\n", cmd, ini->path, rep.joint, rep.ini_key,
                rep.value, rep.why);
    else
        fprintf(stderr, "hexaglide %s: %s: the loop's %s %s (joint %d) = %.17g: %s\n", cmd, ini->path, rep.component,
                rep.field, rep.joint, rep.value, rep.why);
    return -1;
}
