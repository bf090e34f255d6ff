/* hg_compiler.h - what the core asks of its compiler beyond ISO C99, and
 * the ISO C it falls back to elsewhere (MSVC, TinyCC, ...), with the same
 * answers: GCC and Clang get always_inline, unrolled loops, printf format
 * checks and two-double vectors (hg_linalg.h's hg_v2); any other compiler, or any
 * build with -DHG_PORTABLE_C, plain inline functions and a two-double
 * struct. Each vector lane rounds as the scalar expression, so both give
 * the same bits (tests/fmu/test_fmu_sources builds the FMU's sources both
 * ways and compares). Pure C, no machine. */
#ifndef HG_COMPILER_H
#define HG_COMPILER_H

#if (defined(__GNUC__) || defined(__clang__)) && !defined(__TINYC__) && !defined(HG_PORTABLE_C)
#define HG_GNU_C 1
#define HG_ALWAYS_INLINE inline __attribute__((always_inline)) /* static HG_ALWAYS_INLINE f(...) */
#define HG_PRINTF_LIKE(fmt, first) __attribute__((format(printf, fmt, first)))
/* before a loop with a fixed trip count: unroll it by six, completely for
 * the 6-long loops over the 6x6 blocks of the dynamics, in chunks of six
 * for longer ones */
#define HG_UNROLL _Pragma("GCC unroll 6")
#elif defined(_MSC_VER)
#define HG_GNU_C 0
#define HG_ALWAYS_INLINE __forceinline
#define HG_PRINTF_LIKE(fmt, first)
#define HG_UNROLL
#else
#define HG_GNU_C 0
#define HG_ALWAYS_INLINE inline
#define HG_PRINTF_LIKE(fmt, first)
#define HG_UNROLL
#endif

/* An array of 3-vectors (double a[n][3]) as the read-only rows a function
 * with a const double [][3] parameter takes: ISO C before C2X does not
 * convert double (*)[3] to const double (*)[3] by itself (-Wpedantic). */
#define HG_CONST_ROWS3(a) ((const double (*)[3])(a))

#endif
