/* cli.h - subcommands of the host tool build/hexaglide. Each returns the
 * process exit code: 0 on success, 1 on a refused or failed computation,
 * 2 on a usage error. Messages go to stderr, results to stdout. */
#ifndef HG_CLI_H
#define HG_CLI_H

#include "hg_params.h"

int cmd_ik(int argc, char **argv);   /* ik X Y Z A B C */
int cmd_fk(int argc, char **argv);   /* fk J0..J5 [--guess X Y Z A B C] */
int cmd_sim(int argc, char **argv);  /* sim --model ... (offline simulator) */
int cmd_soak(int argc, char **argv); /* soak [--hours H] (long closed-loop run) */
int cmd_replay(int argc, char **argv, const char *self); /* replay FILE ... (self: argv[0]) */
int cmd_tune(int argc, char **argv); /* tune [--trajectory FILE] (runs tools/hexaglide_tune.py) */
int cmd_identify(int argc, char **argv); /* identify RECORD... (runs tools/hexaglide_identify.py) */
int cmd_excite(int argc, char **argv);   /* excite [--output FILE] (runs tools/hexaglide_excite.py) */

/* Run /usr/bin/python3 tools/SCRIPT ARGS... of the source tree this binary
 * was built in, with HEXAGLIDE_LIB naming the library beside it; returns
 * only on failure (1, after a message naming cmd). */
int cli_run_python(const char *cmd, const char *script_name, int argc, char **argv);

#include "hg_board.h"

/* A board (malloc'd; free() it) with model kind and block p, or 0 after a
 * message on stderr naming every invalid field (spec names, SI units). */
hg_board *cli_board_new(const char *cmd, int kind, const hg_board_params *p);

/* --dt seconds -> the board's period in whole ns; 0, or -1 with a message. */
int cli_parse_period(const char *cmd, double dt, long *period_ns);

/* Parse a finite double; 0 on success, -1 (and a message naming what) otherwise. */
int cli_parse_double(const char *text, const char *what, double *out);

/* Apply "name=value" (spec name, SI unit) to p; 0, or -1 with a message
 * "hexaglide CMD: --set: ..." naming the problem. */
int cli_parse_set(const char *cmd, const char *text, hg_params *p);

#endif
