/* cli.h - subcommands of the host tool build/hexaglide. Each returns the
 * process exit code: 0 on success (and for --help / -h, usage on stdout),
 * 1 on a refused or failed computation, 2 on a usage error. Messages go
 * to stderr, results to stdout. Every option takes "--opt value" and
 * "--opt=value", once unless CLI_REPEAT (--set) (cli_next). */
#ifndef HG_CLI_H
#define HG_CLI_H

#include <stddef.h>
#include <stdio.h>
#include "hg_board.h"
#include "hg_loop.h"
#include "hg_params.h"

int cmd_ik(int argc, char **argv);   /* ik X Y Z A B C */
int cmd_fk(int argc, char **argv);   /* fk J0..J5 [--guess X,Y,Z,A,B,C] */
int cmd_sim(int argc, char **argv);  /* sim --model ... (offline simulator) */
int cmd_soak(int argc, char **argv); /* soak [--hours H] (long closed-loop run) */
int cmd_replay(int argc, char **argv); /* replay FILE ... */
int cmd_tune(int argc, char **argv); /* tune [--trajectory FILE] (runs tools/hexaglide_tune.py) */
int cmd_identify(int argc, char **argv); /* identify RECORD... (runs tools/hexaglide_identify.py) */
int cmd_excite(int argc, char **argv);   /* excite [--output FILE] (runs tools/hexaglide_excite.py) */
int cmd_config(int argc, char **argv);   /* config [--ini FILE] (the config as cli_ini.c reads it) */

/* Run tools/SCRIPT ARGS... of the source tree this binary was built in
 * under the first Python 3 that imports `modules` (cli_find_python; `why`
 * says what they are for), with HEXAGLIDE_LIB naming the library beside
 * it (unless set) and HEXAGLIDE_CLI this executable (the INI reader the
 * scripts use: `hexaglide config`, tools/hg_config.py); returns only on failure (1, after a message naming cmd), or 0 for a
 * --help it could not pass on (after printing `usage`). */
int cli_run_python(const char *cmd, const char *script_name, const char *modules, const char *why,
                   const char *usage, int argc, char **argv);

/* Each subcommand's usage text (what --help prints). */
extern const char cli_usage_ik[], cli_usage_fk[], cli_usage_sim[], cli_usage_soak[], cli_usage_replay[],
    cli_usage_tune[], cli_usage_identify[], cli_usage_excite[], cli_usage_config[];

/* The usage lines of --ini and --set, shared by ik, fk, sim and soak. */
#define CLI_USAGE_MODEL                                                                            \
    "  --ini FILE          geometry from the config's [HEXAGLIDE] section (keys L LB E LP in mm,\n" \
    "                      CONE_CARRIAGE CONE_HEAD in degrees, D_BAR in mm, as configs/hexaglide.ini;\n" \
    "                      each required, as configs/hexaglide.hal reads each)\n" \
    "  --set name=value    a model parameter by spec name in SI units (hexaglide sim --list-params);\n" \
    "                      repeatable. Order: defaults, then --ini, then --set; HOME stays at pose 0\n" \
    "                      for any l, lb, lp (h follows from them)\n"

/* ---- options (cli_parse.c) ---- */

/* One option of a subcommand: "--name", and whether it takes a value: 0 (a flag),
 * 1 (a value, given at most once: a second is refused naming both) or
 * CLI_REPEAT (a value that may be given again, each one kept: --set). */
#define CLI_REPEAT 2
typedef struct {
    const char *name;
    int has_value;
} cli_opt;

#define CLI_MAX_OPTS 32    /* options of one subcommand */

/* The scanner over a subcommand's arguments. */
typedef struct {
    const char *cmd;       /* "sim": for messages */
    const char *usage;     /* printed on stdout for --help / -h */
    const cli_opt *opts;   /* ends with {0, 0} */
    int argc;
    char **argv;
    int i;                 /* next argument */
    int only_positional;   /* after "--" */
    const char *given[CLI_MAX_OPTS]; /* each once-only option's value so far, 0 if not given */
    unsigned char seen[CLI_MAX_OPTS]; /* 1: the option was given (any kind) */
} cli_args;

#define CLI_DONE (-1)      /* no arguments left */
#define CLI_ARG (-2)       /* a positional argument, in *value */
#define CLI_HELP (-3)      /* usage printed on stdout: exit 0 */
#define CLI_BAD (-4)       /* message printed on stderr: exit 2 */

void cli_args_init(cli_args *a, const char *cmd, const char *usage, const cli_opt *opts, int argc,
                   char **argv);

/* Next argument: the index of the option in opts (its value in *value, 0
 * for a flag), or CLI_DONE, CLI_ARG, CLI_HELP, CLI_BAD. Options are
 * "--name" (value from "--name=v" or the next argument, whatever it looks
 * like) and -h; "-5" is a positional value; after "--" everything is. A
 * value option that is not CLI_REPEAT given a second time is CLI_BAD,
 * naming both values (nothing is silently the last one). */
int cli_next(cli_args *a, const char **value);

/* After the scan, for a listing option (--list-params) that runs nothing:
 * 0 when no option was given besides list_opt and those named in keep
 * (0-ended; the options the listing reads), else 2 after a message naming
 * the first other one (nothing given is silently left unused). */
int cli_list_only(const cli_args *a, const char *list_opt, const char *const keep[]);

/* text as a finite double: 0, 1 (not a number: empty, trailing text), 2 (not
 * finite: nan, inf, infinity, overflow) or 3 (a C99 hexadecimal float, "0x1p3":
 * refused as tools/hg_csv.py refuses it); *out set only on 0. No message. The
 * syntax is hg_text_is_decimal's (src/hg_text.h), the records' too. */
int cli_strtod(const char *text, double *out);

/* What to add to "is not a number" for cli_strtod's code rc ("" or a hint). */
const char *cli_strtod_hint(int rc);

/* Parse a finite double; 0 on success, -1 (and a message "hexaglide CMD: WHAT: ...") otherwise. */
int cli_parse_double(const char *cmd, const char *text, const char *what, double *out);

/* v as %g writes it, with more significant digits where %g's 6 do not read back as v (a
 * message's number: 10.0000001, not %g's 10 beside a bound of 10); buf of CLI_NUM_LEN chars,
 * returned. */
#define CLI_NUM_LEN 32
const char *cli_num(double v, char buf[CLI_NUM_LEN]);

/* Parse exactly n comma-separated finite numbers ("1,-2,3") for option opt,
 * element k named names[k] in messages; 0 or -1 with a message. */
int cli_parse_list(const char *cmd, const char *opt, const char *text, const char *const names[], int n,
                   double *out);

/* Apply "name=value" (spec name of plant's table, SI unit) to v: the
 * table entry set, or -1 with a message "hexaglide CMD: --set: ..."
 * naming the problem. */
int cli_parse_set(const char *cmd, const char *text, int plant, int variant, hg_plant_params *v);

/* ---- the machine (cli_board.c) ---- */

/* The plant called name (0: the Hexaglide): its registry index, or -1
 * after a message naming the plants there are. */
int cli_plant(const char *cmd, const char *name);

/* The model variant called name of plant (0: its default): the variant,
 * or -1 after a message naming the variants there are. */
int cli_variant(const char *cmd, int plant, const char *name);

/* The name of plant's model variant in buf (HG_PLANT_TEXT_LEN), "?" for
 * one without a name; returns buf (for messages). */
const char *cli_variant_name(int plant, int variant, char *buf);

/* The model parameters of plant with model variant: the spec's defaults, then the plant's
 * section of the INI file ini (0: none; [HEXAGLIDE] for the Hexaglide),
 * then each of the nset "name=value" in sets (HOME is at pose 0 for any
 * Hexaglide geometry: h follows l, lb, lp). Not checked (the board or
 * cli_params_check_from do). 0, or 2 after a message. */
int cli_params_build(const char *cmd, int plant, int variant, const char *ini, char *const *sets, int nset,
                     hg_plant_params *v);

/* The same for the Hexaglide as its own parameter set (ik, fk), checked
 * as kinematics need it: every refused geometry field, and every refused
 * field given another value than its default (the kinematics use nothing
 * else, as hexaglidekins; the default i_bar against a new l is not theirs
 * to refuse). 0, or 2 after one message per such field. */
int cli_hexaglide_params(const char *cmd, const char *ini, char *const *sets, int nset, hg_params *p);

/* Channel k's machine unit per SI unit, LinuxCNC's: deg per rad for a
 * rotary channel (bit k of rotary, hg_board_outputs.rotary), else mm per m. */
double cli_machine_unit(unsigned rotary, int k);

/* Its name as the CSV columns end: "deg" or "mm". */
const char *cli_machine_unit_name(unsigned rotary, int k);

/* The board's parameter block of plant as HAL loads it (spec defaults, substeps, integrator). */
void cli_board_defaults(int plant, int variant, hg_board_params *bp);

/* A board fault in one line for sim's and soak's messages: for parameters
 * the step cannot integrate (HG_FAULT_STIFF), the parameter and its bound,
 * the error, and what to change (a softer value, another --integrator or a
 * shorter --dt; the mode's damping when no step is short enough); for any
 * other fault, the error and the plant's report of what struck. */
void cli_fault_text(const hg_board *b, const hg_board_outputs *o, long period_ns,
                    char buf[HG_PLANT_TEXT_LEN + 2 * HG_BOARD_TEXT_LEN]);

/* 0 if v is a valid machine of plant, else 1 after one message per invalid
 * field saying where its value came from (the last of the nset "name=value"
 * in sets that sets it, the INI file ini's key with its value and line, or
 * the default) and, for a field --set did not change, what --set changed
 * (a rule between parameters: v_bus against m_head). */
int cli_params_check_from(const char *cmd, int plant, int variant, const hg_plant_params *v, const char *ini,
                          char *const *sets, int nset);

/* A board (malloc'd; free() it) of plant with model variant and block p (0: the plant's defaults),
 * or 0 after a message on stderr naming every invalid field (spec names,
 * SI units). */
hg_board *cli_board_new(const char *cmd, int plant, int variant, const hg_board_params *p);

/* 0 if the board can integrate block p (0: the plant's defaults) at period_ns, else 1 after a message
 * naming the bound (the stability check the board makes at its first period, src/hg_board.c: made on
 * a board of its own before a command writes anything), and what the nset --set values changed when
 * they did not set the parameter it names (kt=100 is refused naming r_winding: the back-EMF's system). */
int cli_board_integrable(const char *cmd, int plant, int variant, const hg_board_params *p, long period_ns,
                         char *const *sets, int nset);

/* A warning on stderr for each of the n joints whose scale[k] (INPUT_SCALE,
 * counts per machine unit) is not board b's encoder's (hg_board_enc_scale_fits):
 * what the encoder gives and how the counts read; the run goes on with it, as
 * LinuxCNC would. what names the value's origin ("[JOINT_%d]INPUT_SCALE"). */
void cli_enc_scale_notes(const char *cmd, const hg_board *b, const double *scale, int n, const char *what);

/* 1 if x is a whole number within the rounding of the decimal it came from and a few
 * operations on it (CLI_WHOLE_ULPS of x's magnitude: 1e-3 s * 1e9 is 1000000 ns), its value
 * in *n (the nearest whole number either way). */
#define CLI_WHOLE_ULPS 8.0
int cli_whole(double x, double *n);

/* --dt seconds -> the board's period in whole ns; 0, or -1 with a message (out of range, or
 * not a whole number of ns: the nearest valid periods named; nothing is rounded). */
int cli_parse_period(const char *cmd, double dt, long *period_ns);

/* Option opt's value (value in unit, unit_s seconds each: --time 1 "s", --hours 3600 "h")
 * as a whole number of periods of period_ns in min..max into *n; 0, or -1 after a message
 * naming the value and the nearest valid ones (not a whole number), or the limit. */
int cli_whole_periods(const char *cmd, const char *opt, double value, double unit_s, const char *unit,
                      long period_ns, long min, long max, long *n);

/* ---- LinuxCNC INI files (cli_ini.c) ---- */

/* One "KEY = VALUE" line (key 0: the "[section]" header line itself). */
typedef struct {
    const char *section;   /* without brackets, "" before the first section */
    const char *key;
    const char *value;     /* 0 if the line has no '=' */
    int line;              /* 1-based, first physical line */
    int section_line;      /* line of the header this entry is under */
} cli_ini_entry;

typedef struct {
    const char *path;
    char *text;            /* the file, cut in place */
    cli_ini_entry *e;
    int n;
} cli_ini;

/* Read path; 0, or -1 after a message naming the file (and line). */
int cli_ini_read(const char *cmd, const char *path, cli_ini *ini);
void cli_ini_free(cli_ini *ini);

/* 1 if the file has a [section] header. */
int cli_ini_has_section(const cli_ini *ini, const char *section);
/* A plant other than plant whose section ini has while it lacks plant's
 * ([SERIAL] read as the Hexaglide's config), or 0. */
const hg_plant *cli_ini_other_plant(const cli_ini *ini, int plant);

/* 0, or -1 after a message if ini is another plant's config (cli_ini_other_plant) given to
 * command cmd, which runs plant only (ik, fk, soak: the Hexaglide): it names that plant and
 * what to run instead (sim --plant NAME). */
int cli_ini_plant_only(const char *cmd, const cli_ini *ini, int plant);

/* [section]key: 0 and *out, 1 if absent, -1 (message) if given twice or in
 * a repeated section (LinuxCNC would silently take the first). */
int cli_ini_get(const char *cmd, const cli_ini *ini, const char *section, const char *key,
                const cli_ini_entry **out);

/* The entry's value as a finite number; 0, or -1 naming key, file, line. */
int cli_ini_number(const char *cmd, const cli_ini *ini, const cli_ini_entry *e, double *v);

/* The plant's section ([HEXAGLIDE] for the Hexaglide) onto v (keys in
 * their HAL unit, mm for lengths); every unknown key, repeated key and
 * non-number is named. 0, -1 (the section's keys named), or -2 when the
 * file has no such section (named, with what to give: another plant's
 * config -> --plant NAME, which sim and config take). */
int cli_ini_apply_plant(const char *cmd, const cli_ini *ini, int plant, int variant, hg_plant_params *v);

/* [JOINT_0]..[JOINT_{joints-1}] gains and scales onto c, as
 * configs/hexaglide.hal wires them: every key the HAL file sets must be
 * there (halcmd stops at a setp of a missing key), FF3 (not wired) may be
 * absent and keeps c's value; each section must exist. 0, or -1 after
 * naming every problem. */
int cli_ini_apply_joints(const char *cmd, const cli_ini *ini, int joints, hg_loop_config *c);

/* The keys cli_ini_apply_joints reads, by index (0 past the last). */
const char *cli_ini_joint_key(int i);

/* [JOINT_joint]key as a number (required); 0 or -1 with a message. */
int cli_ini_joint_number(const char *cmd, const cli_ini *ini, int joint, const char *key, double *v);

/* [section]key as a number if it is there: 0 (*v, and its line in *line if
 * line is not 0), 1 if absent, -1 after a message (not a finite number,
 * given twice, in a second section). */
int cli_ini_optional(const char *cmd, const cli_ini *ini, const char *section, const char *key, double *v,
                     int *line);

/* [EMCMOT]SERVO_PERIOD in ns if it is there: 0 (*ns; its line in *line if line is not 0),
 * 1 if absent, -1 after a message naming file and line (not a finite number, not a whole
 * number of ns >= 1: LinuxCNC's servo_period_nsec is an integer, nothing is rounded). */
int cli_ini_servo_period(const char *cmd, const cli_ini *ini, long *ns, int *line);

/* LinuxCNC's following-error rule of a joint (control.c: the limit is
 * max(FERROR |v| / MAX_VELOCITY, MIN_FERROR)), mm and mm/s. */
typedef struct {
    double ferror, min_ferror, max_velocity;
} cli_ferror_rule;

/* The servo loops of [JOINT_0..joints-1] as LinuxCNC runs them: c from
 * cli_ini_apply_joints (c initialised by the caller) and each joint's
 * following-error rule (FERROR, MIN_FERROR, MAX_VELOCITY: required), then
 * checked: INPUT_SCALE != 0, MAX_VELOCITY > 0, FERROR >= 0 and
 * MIN_FERROR >= 0, a failing key named with its line (the part of
 * cli_ini_servo_loops below that reads the INI). 0 or -1. */
int cli_ini_loop(const char *cmd, const cli_ini *ini, int joints, hg_loop_config *c, cli_ferror_rule *r);

/* The Hexaglide's six servo loops as soak runs them, the one check of soak and `hexaglide
 * config --loop` (tune): cli_ini_loop (c initialised by the caller, its plant and variant set),
 * [EMCMOT]SERVO_PERIOD (1 ms when absent; read and checked even when replaced), the period
 * (period_ns > 0: given by the command's option period_opt, which replaces SERVO_PERIOD; else
 * SERVO_PERIOD, at most the board's HG_PERIOD_MAX_NS: a longer one is named with its line and
 * period_opt, when not 0, as the way around) into c->period_ns, then hg_loop_config_check (a
 * refused setting named as "FILE: [JOINT_N]KEY = VALUE: rule"). 0, or -1 after the messages. */
int cli_ini_servo_loops(const char *cmd, const cli_ini *ini, long period_ns, const char *period_opt, hg_loop_config *c,
                        cli_ferror_rule *r);

/* ---- the source tree and Python (cli_tree.c) ---- */

/* rel (e.g. "configs/hexaglide.ini") in the source tree this executable
 * was built in: the parent of its directory (build/hexaglide) or the one
 * above (build/asan/hexaglide), whichever holds rel. 0, or -1 if neither
 * does (out then names the first place looked) or out is too short. */
int cli_tree_path(const char *rel, char *out, size_t len);

/* name in this executable's own directory (build/libhexaglide.so); 0 or -1. */
int cli_beside_path(const char *name, char *out, size_t len);

/* A Python 3 interpreter that imports every module of the space-separated
 * list modules: $HEXAGLIDE_PYTHON if set (then only it), else each
 * `python3` on $PATH in order. 0 and its path in out, or -1 after a
 * message naming what was tried, why each failed, and `why` (what the
 * modules are needed for). */
int cli_find_python(const char *cmd, const char *modules, const char *why, char *out, size_t len);

/* The whole regular file path (at most max bytes) into a NUL-terminated
 * malloc'd *buf (free() it), its length in *len; 0, or -1 after a message
 * naming the file and, for the wrong kind of file, `what` to give. */
int cli_read_file(const char *cmd, const char *path, const char *what, long long max, char **buf, size_t *len);

/* An output file (stdout when the path is 0). A path naming a symlink is
 * its target's (the link stays); a regular file or a new one is written to
 * a temporary beside it and renamed onto it when complete (never a half
 * file); a FIFO, device or socket is written straight into; a directory or
 * a missing directory is an error. Every write error is one (close). */
typedef struct {
    FILE *f;
    const char *path;      /* 0: stdout */
    char target[4096];     /* path, symlinks followed */
    char tmp[4096];        /* target.tmp-PID while writing; "" when written straight */
} cli_out;

/* 1 if output path is standard output: 0 (a command's default) or "-" (the Unix idiom: no
 * command writes a file named "-"; ./- names one). */
int cli_out_is_stdout(const char *path);

/* 0, or -1 after a message saying why, if the value of output option opt is "-" where a
 * command cannot write that output to standard output (why: "the plot reads the CSV
 * from a file"). */
int cli_out_need_file(const char *cmd, const char *opt, const char *path, const char *why);

/* 0, or -1 after a message saying why, if output option opt's path cannot be a file that a
 * program other than this one writes (the plot: Python) by a temporary and a rename: a
 * directory, a device or FIFO, or a directory that takes no new file (checked now, before the
 * work, by making and removing one); why names the file ("the plot is a PNG file"). */
int cli_out_need_regular(const char *cmd, const char *opt, const char *path, const char *why);

/* Open path's temporary file, the path itself (not a regular file) or
 * stdout (cli_out_is_stdout); 0, or -1 after a message. */
int cli_out_open(const char *cmd, const char *path, cli_out *o);

/* Close; keep: rename onto the target, else remove. 0, or -1 after a
 * message naming the path and the cause (a write, flush, sync or rename
 * failed; no temporary left, a regular file as it was). */
int cli_out_close(const char *cmd, cli_out *o, int keep);

/* Flush stdout: 0, or -1 after a message (once per process) naming the cause of a failed
 * write (a full disk, a closed pipe): main checks it after every command, so no result is
 * lost silently. */
int cli_stdout_flush(const char *cmd);
/* stdout through a writer that keeps the first failed write's cause for cli_stdout_flush
 * (main, before any output). */
void cli_stdout_init(void);

/* 1 if outputs a and b would write the same file (symlinks followed), or both standard output. */
int cli_out_same(const char *a, const char *b);

/* 1, after saying so, if output out (of option opt) would overwrite the input in (of option
 * in_opt, "" for a positional file) the command reads; 0 otherwise or when either is 0. */
int cli_out_is_input(const char *cmd, const char *opt, const char *out, const char *in_opt, const char *in);

#endif
