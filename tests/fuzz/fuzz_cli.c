/* fuzz_cli.c - the command-line tool's argument handling (ik, fk, sim)
 * with argument lists built from a vocabulary of options, parameter names
 * and tricky numbers. --csv is never generated (no files are written) and
 * --time/--dt only take values that keep a run short.
 * Properties: no crash, no sanitizer report, an exit code in {0, 1, 2}.
 * tools/fuzz.sh runs it with -close_fd_mask=3: the tool's own messages on
 * stdout/stderr are dropped, libFuzzer's report is kept. */
#include <stdio.h>
#include <stdlib.h>
#include "fuzz_input.h"
#include "cli.h"

static const char *const words[] = {
    "--model", "standard", "reduced-joints", "reduced-cartesian", "fused-cartesian", "bogus",
    "--volts", "--set", "--guess", "--tool-offset", "--list-params", "--help", "-h", "m_head=7", "m_head=-1",
    "l=0.3", "c_visc=0", "lead=nan", "i_bar=0.1", "nosuch=1", "=3", "m_head=", "k_stop=1e30",
    "1,2,3,4,5,6", "1,2,3", "1,2,3,4,5,6,7", "nan,0,0,0,0,0", ",,,,,", "10,-10,1e300,0,0,0",
    "0", "-0", "1", "-1", "2.5", "1e-320", "1e308", "1e999", "nan", "inf", "-inf", "0x10",
    "12abc", "", " ", "--", "-", "900", "89", "45",
};
static const char *const times[] = {"0", "0.002", "0.004", "-1", "nan", "abc", "1e999", "1e9"};
static const char *const dts[] = {"0.001", "0.002", "0", "-0.001", "0.5", "nan", "1e-12"};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in = {data, size, 0};
    char *argv[16];
    int argc, i, rc;
    uint8_t cmd = fuzz_byte(&in) % 3;
    argc = fuzz_byte(&in) % 15;
    for (i = 0; i < argc; i++) {
        const char *w = words[fuzz_byte(&in) % (sizeof words / sizeof words[0])];
        if (i > 0 && strcmp(argv[i - 1], "--time") == 0)
            w = times[fuzz_byte(&in) % (sizeof times / sizeof times[0])];
        else if (i > 0 && strcmp(argv[i - 1], "--dt") == 0)
            w = dts[fuzz_byte(&in) % (sizeof dts / sizeof dts[0])];
        else if (cmd == 2 && (fuzz_byte(&in) & 7) == 0)
            w = (fuzz_byte(&in) & 1) ? "--time" : "--dt";
        argv[i] = (char *)w;
    }
    /* a sim run with no --time lasts 1 s of simulation: make sure it is short (a second
     * --time is refused, and 0.002 s is a whole number of the periods in dts) */
    for (i = 0; i < argc && strcmp(argv[i], "--time") != 0; i++)
        ;
    if (cmd == 2 && i == argc && argc + 2 <= 15) {
        argv[argc++] = "--time";
        argv[argc++] = "0.002";
    }
    argv[argc] = 0;
    rc = cmd == 0 ? cmd_ik(argc, argv) : cmd == 1 ? cmd_fk(argc, argv) : cmd_sim(argc, argv);
    fflush(stdout);
    if (rc < 0 || rc > 2)
        abort();
    return 0;
}
