/* fuzz_input.h - turn fuzzer bytes into numbers that matter: each double is
 * either one of a table of extremes (NaN, inf, denormals, huge, zero, -0)
 * or a value scaled into a range, or the raw 8 bytes. */
#ifndef FUZZ_INPUT_H
#define FUZZ_INPUT_H
#include <math.h>
#include <stdint.h>
#include <string.h>

typedef struct {
    const uint8_t *data;
    size_t size, pos;
} fuzz_input;

/* next byte, 0 once the input is used up */
static inline uint8_t fuzz_byte(fuzz_input *in)
{
    return in->pos < in->size ? in->data[in->pos++] : 0;
}

/* a double near [lo, hi], sometimes extreme */
static inline double fuzz_double(fuzz_input *in, double lo, double hi)
{
    static const double extremes[] = {
        NAN, INFINITY, -INFINITY, 0.0, -0.0, 4.9e-324, -4.9e-324, 2.2250738585072009e-308,
        1e300, -1e300, 1.7976931348623157e308, 1e-300, 1e30, -1e30, 1e6, -1e6,
    };
    uint8_t sel = fuzz_byte(in);
    uint64_t bits = 0;
    unsigned k;
    if (sel < 16)
        return extremes[sel];
    if (sel < 24) { /* raw bit pattern */
        for (k = 0; k < 8; k++)
            bits = (bits << 8) | fuzz_byte(in);
        {
            double v;
            memcpy(&v, &bits, sizeof v);
            return v;
        }
    }
    bits = ((uint64_t)fuzz_byte(in) << 8) | fuzz_byte(in);
    return lo + (hi - lo) * (double)bits / 65535.0;
}
#endif
