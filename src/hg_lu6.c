/* hg_lu6.c - unrolled 6x6 LU with partial pivoting. */
#include "hg_math.h"
#include "hg_lu6.h"
#include "hg_errors.h"
#include "hg_compiler.h"

#define HG_LU6_TINY 1e-13
#define HG_LU6_MAX_RHS 8

int hg_lu6_factor(double a[36], int piv[6])
{
    double amax = 0.0;
    int i, j, k;
    HG_UNROLL
    for (i = 0; i < 36; i++)
        if (fabs(a[i]) > amax)
            amax = fabs(a[i]);
    if (!(amax > 0.0) || !isfinite(amax))
        return HG_ERR_SINGULAR_JACOBIAN;
    HG_UNROLL
    for (k = 0; k < 6; k++) {
        int p = k;
        double best = fabs(a[6 * k + k]), inv;
        for (i = k + 1; i < 6; i++)
            if (fabs(a[6 * i + k]) > best) {
                best = fabs(a[6 * i + k]);
                p = i;
            }
        if (!(best > HG_LU6_TINY * amax))
            return HG_ERR_SINGULAR_JACOBIAN;
        piv[k] = p;
        if (p != k)
            HG_UNROLL
            for (j = 0; j < 6; j++) {
                double t = a[6 * k + j];
                a[6 * k + j] = a[6 * p + j];
                a[6 * p + j] = t;
            }
        inv = 1.0 / a[6 * k + k];
        for (i = k + 1; i < 6; i++) {
            double f = a[6 * i + k] * inv;
            a[6 * i + k] = f;
            for (j = k + 1; j < 6; j++)
                a[6 * i + j] -= f * a[6 * k + j];
        }
    }
    return 0;
}

/* The solve with nrhs known at compile time where it is inlined. */
static HG_ALWAYS_INLINE void solve(const double lu[36], const int piv[6], const int nrhs, double *b)
{
    int i, k, r;
    HG_UNROLL
    for (k = 0; k < 6; k++) {          /* apply the row swaps in factor order */
        if (piv[k] != k)
            for (r = 0; r < nrhs; r++) {
                double t = b[k * nrhs + r];
                b[k * nrhs + r] = b[piv[k] * nrhs + r];
                b[piv[k] * nrhs + r] = t;
            }
    }
    HG_UNROLL
    for (i = 1; i < 6; i++)            /* L y = b, unit diagonal */
        for (k = 0; k < i; k++) {
            double l = lu[6 * i + k];
            for (r = 0; r < nrhs; r++)
                b[i * nrhs + r] -= l * b[k * nrhs + r];
        }
    HG_UNROLL
    for (i = 5; i >= 0; i--) {         /* U x = y */
        double inv = 1.0 / lu[6 * i + i];
        for (k = i + 1; k < 6; k++) {
            double u = lu[6 * i + k];
            for (r = 0; r < nrhs; r++)
                b[i * nrhs + r] -= u * b[k * nrhs + r];
        }
        for (r = 0; r < nrhs; r++)
            b[i * nrhs + r] *= inv;
    }
}

void hg_lu6_solve(const double lu[36], const int piv[6], int nrhs, double *b)
{
    if (nrhs == 7)          /* [Phi_z | v]: the Reduced Joints step */
        solve(lu, piv, 7, b);
    else if (nrhs == 1)
        solve(lu, piv, 1, b);
    else if (nrhs >= 1 && nrhs <= HG_LU6_MAX_RHS)
        solve(lu, piv, nrhs, b);
}
