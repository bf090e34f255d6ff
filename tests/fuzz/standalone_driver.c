/* standalone_driver.c - runs a LLVMFuzzerTestOneInput target without
 * libFuzzer (e.g. with gcc): a seeded random byte source and a fixed
 * number of inputs. Usage: target [-runs=N] [-seed=S] */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv)
{
    long runs = 1000000, i;
    unsigned long long s = 0x2545F4914F6CDD1Dull;
    uint8_t buf[512];
    struct timespec t0, t1;
    double secs;
    int a;
    for (a = 1; a < argc; a++) {
        if (strncmp(argv[a], "-runs=", 6) == 0)
            runs = atol(argv[a] + 6);
        else if (strncmp(argv[a], "-seed=", 6) == 0)
            s = strtoull(argv[a] + 6, 0, 10) | 1;
    }
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (i = 0; i < runs; i++) {
        size_t n, k;
        s ^= s >> 12; s ^= s << 25; s ^= s >> 27;
        n = (size_t)((s * 2685821657736338717ull) >> 55); /* 0..511 bytes */
        for (k = 0; k < n; k++) {
            s ^= s >> 12; s ^= s << 25; s ^= s >> 27;
            buf[k] = (uint8_t)((s * 2685821657736338717ull) >> 56);
        }
        LLVMFuzzerTestOneInput(buf, n);
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    secs = (t1.tv_sec - t0.tv_sec) + (t1.tv_nsec - t0.tv_nsec) * 1e-9;
    printf("Done %ld runs in %.1f second(s), %.0f exec/s\n", runs, secs, runs / (secs > 0 ? secs : 1));
    return 0;
}
