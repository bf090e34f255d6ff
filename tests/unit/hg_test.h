/* hg_test.h - minimal TAP-style checks for the host C unit tests.
 * CHECK(cond, fmt, ...) prints "ok - ..." or "not ok - ..."; the exit code
 * of main should be hg_test_exit(). */
#ifndef HG_TEST_H
#define HG_TEST_H
#include <stdio.h>

static int hg_test_failures;

#define CHECK(cond, ...) do { \
        int ok_ = (cond) ? 1 : 0; \
        printf("%s - ", ok_ ? "ok" : "not ok"); \
        printf(__VA_ARGS__); \
        if (!ok_) { printf("   [%s:%d: %s]", __FILE__, __LINE__, #cond); hg_test_failures++; } \
        printf("\n"); \
    } while (0)

static inline int hg_test_exit(void) { return hg_test_failures ? 1 : 0; }

/* deterministic uniform random numbers for tests (xorshift64*) */
static unsigned long long hg_test_rng_state = 0x9E3779B97F4A7C15ull;
static inline double hg_test_uniform(double lo, double hi)
{
    unsigned long long x = hg_test_rng_state;
    x ^= x >> 12; x ^= x << 25; x ^= x >> 27;
    hg_test_rng_state = x;
    return lo + (hi - lo) * ((double)((x * 2685821657736338717ull) >> 11) / 9007199254740992.0);
}
#endif
