/* main.c - build/hexaglide: the project's math on the command line.
 *   hexaglide ik X Y Z A B C            pose (mm, deg) -> joints (mm)
 *   hexaglide fk J0..J5 [--guess ...]   joints (mm) -> pose (mm, deg)
 *   hexaglide sim [options]             offline simulation of the virtual board (CSV)
 *   hexaglide soak [--hours H]          hours of closed-loop motion, health report
 *   hexaglide replay FILE [options]     re-run a recorded LinuxCNC run, compare (docs/replay.md)
 *   hexaglide tune [--trajectory FILE]  PID gains tuned against the model (docs/tuning.md)
 *   hexaglide identify RECORD...        dynamic parameters from recorded runs (docs/identification.md)
 *   hexaglide excite [--output FILE]    an excitation program to record them with */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: hexaglide ik X Y Z A B C\n"
            "       hexaglide fk J0 J1 J2 J3 J4 J5 [--guess X Y Z A B C]\n"
            "       hexaglide sim [--model standard|reduced-joints|reduced-cartesian|fused-cartesian]\n"
            "                     [--time S] [--dt S] [--volts V0,..,V5] [--substeps N]\n"
            "                     [--integrator improved-euler|heun|rk4] [--set name=value]... [--csv FILE]\n"
            "       hexaglide soak [--hours H] [--model NAME] [--seed N] [--dt S]\n"
            "       hexaglide replay FILE [--csv OUT] [--plot PNG] [--set name=value]...\n"
            "                        [--model NAME] [--substeps N] [--integrator NAME]\n"
            "       hexaglide tune [--trajectory FILE] [--output FILE] [--plots DIR] [--help]\n"
            "       hexaglide identify RECORD... [--validate RECORD] [--output FILE] [--plots DIR] [--help]\n"
            "       hexaglide excite [--output FILE] [--ini FILE] [--help]\n"
            "units: X Y Z and joints in mm, A B C in degrees (see README.md)\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (strcmp(argv[1], "ik") == 0)
        return cmd_ik(argc - 2, argv + 2);
    if (strcmp(argv[1], "fk") == 0)
        return cmd_fk(argc - 2, argv + 2);
    if (strcmp(argv[1], "sim") == 0)
        return cmd_sim(argc - 2, argv + 2);
    if (strcmp(argv[1], "soak") == 0)
        return cmd_soak(argc - 2, argv + 2);
    if (strcmp(argv[1], "replay") == 0)
        return cmd_replay(argc - 2, argv + 2, argv[0]);
    if (strcmp(argv[1], "tune") == 0)
        return cmd_tune(argc - 2, argv + 2);
    if (strcmp(argv[1], "identify") == 0)
        return cmd_identify(argc - 2, argv + 2);
    if (strcmp(argv[1], "excite") == 0)
        return cmd_excite(argc - 2, argv + 2);
    if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        usage(stdout);
        return 0;
    }
    fprintf(stderr, "hexaglide: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
