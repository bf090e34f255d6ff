/* main.c - build/hexaglide: the project's math on the command line.
 *   hexaglide ik X Y Z A B C            pose (mm, deg) -> joints (mm)
 *   hexaglide fk J0..J5 [--guess ...]   joints (mm) -> pose (mm, deg)
 *   hexaglide sim [options]             offline simulation of the virtual board (CSV)
 *   hexaglide soak [--hours H]          hours of LinuxCNC's closed loop, health report
 *   hexaglide replay FILE [options]     re-run a recorded LinuxCNC run, compare (docs/replay.md)
 *   hexaglide tune [--trajectory FILE]  PID gains tuned against the model (docs/tuning.md)
 *   hexaglide identify RECORD...        dynamic parameters from recorded runs (docs/identification.md)
 *   hexaglide excite [--output FILE]    an excitation program to record them with
 *   hexaglide config [--ini FILE]       the config as these commands read it (for tune and excite)
 * `hexaglide CMD --help` prints CMD's usage. */
#include <stdio.h>
#include <string.h>
#include "cli.h"

static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *usage;
} commands[] = {
    {"ik", cmd_ik, cli_usage_ik},
    {"fk", cmd_fk, cli_usage_fk},
    {"sim", cmd_sim, cli_usage_sim},
    {"soak", cmd_soak, cli_usage_soak},
    {"replay", cmd_replay, cli_usage_replay},
    {"tune", cmd_tune, cli_usage_tune},
    {"identify", cmd_identify, cli_usage_identify},
    {"excite", cmd_excite, cli_usage_excite},
    {"config", cmd_config, cli_usage_config},
};
#define N_COMMANDS (int)(sizeof commands / sizeof commands[0])

/* Every subcommand's first usage line, then where the rest is. */
static void usage(FILE *f)
{
    int i;
    for (i = 0; i < N_COMMANDS; i++) {
        const char *u = commands[i].usage + (i ? 7 : 0), *nl = strchr(u, '\n');   /* "usage: " once */
        fprintf(f, "%s%.*s\n", i ? "       " : "", (int)(nl ? nl - u : (long)strlen(u)), u);
    }
    fprintf(f, "'hexaglide CMD --help' prints CMD's options. Units: X Y Z and joints in mm, A B C in\n"
               "degrees (README.md); every option takes '--opt value' and '--opt=value'.\n");
}

int main(int argc, char **argv)
{
    int i;
    cli_stdout_init();
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    for (i = 0; i < N_COMMANDS; i++)
        if (strcmp(argv[1], commands[i].name) == 0) {
            int rc = commands[i].run(argc - 2, argv + 2);
            return cli_stdout_flush(commands[i].name) && rc == 0 ? 1 : rc;  /* a result lost is a failure */
        }
    if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        usage(stdout);
        return cli_stdout_flush("--help") ? 1 : 0;
    }
    fprintf(stderr, "hexaglide: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
