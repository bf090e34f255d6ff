/* cmd_sim.c - placeholder until the offline simulator lands. */
#include <stdio.h>
#include "cli.h"

int cmd_sim(int argc, char **argv)
{
    (void)argc; (void)argv;
    fprintf(stderr, "hexaglide sim: not implemented yet\n");
    return 2;
}
