/* hg_linalg.c - bounded LU for n <= HG_LINALG_MAX_N. */
#include "hg_math.h"
#include "hg_linalg.h"
#include "hg_errors.h"
#include "hg_compiler.h"

/* hg_lu_factor's body; inlined with n known where the caller's is fixed. */
static HG_ALWAYS_INLINE int lu_factor(int n, double *a, int *piv)
{
    int i, j, k;
    double amax = 0.0, nonfinite = 0.0;
    if (n < 1 || n > HG_LINALG_MAX_N)
        return HG_ERR_SINGULAR_JACOBIAN;
    HG_UNROLL
    for (i = 0; i < n * n; i++) {     /* without a branch per entry */
        double v = fabs(a[i]);
        nonfinite += v - v;           /* NaN once an entry is Inf or NaN, else exactly 0 */
        amax = v > amax ? v : amax;
    }
    if (!(nonfinite == 0.0) || amax == 0.0)
        return HG_ERR_SINGULAR_JACOBIAN;
    for (i = 0; i < n; i++)
        piv[i] = i;
    HG_UNROLL
    for (k = 0; k < n; k++) {
        int p = k;
        double best = fabs(a[k * n + k]);
        for (i = k + 1; i < n; i++)
            if (fabs(a[i * n + k]) > best) {
                best = fabs(a[i * n + k]);
                p = i;
            }
        if (best <= 1e-13 * amax)
            return HG_ERR_SINGULAR_JACOBIAN;
        if (p != k) {
            int t = piv[k];
            piv[k] = piv[p];
            piv[p] = t;
            for (j = 0; j < n; j++) {
                double s = a[k * n + j];
                a[k * n + j] = a[p * n + j];
                a[p * n + j] = s;
            }
        }
        for (i = k + 1; i < n; i++) {
            double f = a[i * n + k] / a[k * n + k];
            a[i * n + k] = f;
            HG_UNROLL
            for (j = k + 1; j < n; j++)
                a[i * n + j] -= f * a[k * n + j];
        }
    }
    return 0;
}

int hg_lu_factor(int n, double *a, int *piv)
{
    /* the 6x6 (forward kinematics, the stick sets) with constant bounds: the same operations */
    return n == 6 ? lu_factor(6, a, piv) : lu_factor(n, a, piv);
}

/* hg_lu_solve's body; inlined with n known where the caller's is fixed. */
static HG_ALWAYS_INLINE void lu_solve(int n, const double *lu, const int *piv, int nrhs, double *b)
{
    double x[HG_LINALG_MAX_N];
    int i, j, r;
    for (r = 0; r < nrhs; r++) { /* one column at a time: only column r is read and written */
        HG_UNROLL
        for (i = 0; i < n; i++)
            x[i] = b[piv[i] * nrhs + r];
        HG_UNROLL
        for (i = 1; i < n; i++)
            HG_UNROLL
            for (j = 0; j < i; j++)
                x[i] -= lu[i * n + j] * x[j];
        HG_UNROLL
        for (i = n - 1; i >= 0; i--) {
            HG_UNROLL
            for (j = i + 1; j < n; j++)
                x[i] -= lu[i * n + j] * x[j];
            x[i] /= lu[i * n + i];
        }
        HG_UNROLL
        for (i = 0; i < n; i++)
            b[i * nrhs + r] = x[i];
    }
}

void hg_lu_solve(int n, const double *lu, const int *piv, int nrhs, double *b)
{
    if (n == 6)                       /* as hg_lu_factor: the same operations, constant bounds */
        lu_solve(6, lu, piv, nrhs, b);
    else
        lu_solve(n, lu, piv, nrhs, b);
}
