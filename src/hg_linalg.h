/* hg_linalg.h - small dense linear algebra for realtime use: fixed upper
 * bound on size, no allocation, loops bounded by n, row-major storage.
 * Pure C and libm. */
#ifndef HG_LINALG_H
#define HG_LINALG_H

#include "hg_compiler.h"
#include "hg_string.h"

#define HG_LINALG_MAX_N 18

/* LU factorization with partial pivoting in place: a (n x n) becomes L\U,
 * piv[n] the row order. 0, or HG_ERR_SINGULAR_JACOBIAN when a pivot is
 * below tiny (relative to the largest entry) or not finite. */
int hg_lu_factor(int n, double *a, int *piv);

/* Solve (L U) x = P b for nrhs right-hand sides stored as columns of
 * b (n x nrhs, row-major), in place. */
void hg_lu_solve(int n, const double *lu, const int *piv, int nrhs, double *b);

/* 1 when every one of the n values is finite. x - x is 0 for finite x and
 * NaN for inf or NaN, and a sum of zeros stays exactly 0: one branch for the
 * whole array (inline: it guards every hg_step). Two sums over pairs, which
 * the compiler turns into packed subtractions and additions. */
static inline int hg_all_finite(int n, const double *v)
{
    double s0 = 0.0, s1 = 0.0;
    int i;
    for (i = 0; i + 1 < n; i += 2) {
        s0 += v[i] - v[i];
        s1 += v[i + 1] - v[i + 1];
    }
    if (i < n)
        s0 += v[i] - v[i];
    return s0 + s1 == 0.0;
}

/* Two doubles in one vector register (GCC's and Clang's vector extension:
 * SSE2 on x86-64), or a struct of two elsewhere (hg_compiler.h). Each lane
 * rounds as the scalar expression would (no contraction into fused
 * multiply-adds: -ffp-contract=off), so a loop over pairs of columns gives
 * the bits of the scalar loop at half the instructions. Loads and stores
 * through memcpy: no alignment needed. */
#if HG_GNU_C
typedef double hg_v2 __attribute__((vector_size(16)));

/* a, b */
static inline hg_v2 hg_v2_set(double a, double b)
{
    hg_v2 v = {a, b};
    return v;
}

/* a + b, lane by lane */
static inline hg_v2 hg_v2_add(hg_v2 a, hg_v2 b)
{
    return a + b;
}

/* a - b, lane by lane */
static inline hg_v2 hg_v2_sub(hg_v2 a, hg_v2 b)
{
    return a - b;
}

/* a * b, lane by lane */
static inline hg_v2 hg_v2_mul(hg_v2 a, hg_v2 b)
{
    return a * b;
}
#else
typedef struct {
    double lane[2];
} hg_v2;

/* a, b */
static inline hg_v2 hg_v2_set(double a, double b)
{
    hg_v2 v;
    v.lane[0] = a;
    v.lane[1] = b;
    return v;
}

/* a + b, lane by lane */
static inline hg_v2 hg_v2_add(hg_v2 a, hg_v2 b)
{
    return hg_v2_set(a.lane[0] + b.lane[0], a.lane[1] + b.lane[1]);
}

/* a - b, lane by lane */
static inline hg_v2 hg_v2_sub(hg_v2 a, hg_v2 b)
{
    return hg_v2_set(a.lane[0] - b.lane[0], a.lane[1] - b.lane[1]);
}

/* a * b, lane by lane */
static inline hg_v2 hg_v2_mul(hg_v2 a, hg_v2 b)
{
    return hg_v2_set(a.lane[0] * b.lane[0], a.lane[1] * b.lane[1]);
}
#endif

/* p[0], p[1] */
static inline hg_v2 hg_v2_load(const double *p)
{
    hg_v2 v;
    memcpy(&v, p, sizeof v);
    return v;
}

/* p[0], p[1] = v */
static inline void hg_v2_store(double *p, hg_v2 v)
{
    memcpy(p, &v, sizeof v);
}

/* x in both lanes */
static inline hg_v2 hg_v2_dup(double x)
{
    return hg_v2_set(x, x);
}

#endif
