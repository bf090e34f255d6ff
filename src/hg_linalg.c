/* hg_linalg.c - bounded LU and Cholesky for n <= HG_LINALG_MAX_N. */
#include <math.h>
#include "hg_linalg.h"
#include "hg_errors.h"

int hg_all_finite(int n, const double *v)
{
    int i;
    for (i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

int hg_lu_factor(int n, double *a, int *piv)
{
    int i, j, k;
    double amax = 0.0;
    if (n < 1 || n > HG_LINALG_MAX_N)
        return HG_ERR_SINGULAR_JACOBIAN;
    for (i = 0; i < n * n; i++) {
        if (!isfinite(a[i]))
            return HG_ERR_SINGULAR_JACOBIAN;
        if (fabs(a[i]) > amax)
            amax = fabs(a[i]);
    }
    if (amax == 0.0)
        return HG_ERR_SINGULAR_JACOBIAN;
    for (i = 0; i < n; i++)
        piv[i] = i;
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
            for (j = k + 1; j < n; j++)
                a[i * n + j] -= f * a[k * n + j];
        }
    }
    return 0;
}

void hg_lu_solve(int n, const double *lu, const int *piv, int nrhs, double *b)
{
    double x[HG_LINALG_MAX_N];
    int i, j, r;
    for (r = 0; r < nrhs; r++) { /* one column at a time: only column r is read and written */
        for (i = 0; i < n; i++)
            x[i] = b[piv[i] * nrhs + r];
        for (i = 1; i < n; i++)
            for (j = 0; j < i; j++)
                x[i] -= lu[i * n + j] * x[j];
        for (i = n - 1; i >= 0; i--) {
            for (j = i + 1; j < n; j++)
                x[i] -= lu[i * n + j] * x[j];
            x[i] /= lu[i * n + i];
        }
        for (i = 0; i < n; i++)
            b[i * nrhs + r] = x[i];
    }
}

int hg_cholesky_factor(int n, double *a)
{
    int i, j, k;
    if (n < 1 || n > HG_LINALG_MAX_N)
        return HG_ERR_SINGULAR_MASS;
    for (j = 0; j < n; j++) {
        double d = a[j * n + j];
        for (k = 0; k < j; k++)
            d -= a[j * n + k] * a[j * n + k];
        if (!(d > 0.0) || !isfinite(d))
            return HG_ERR_SINGULAR_MASS;
        d = sqrt(d);
        a[j * n + j] = d;
        for (i = j + 1; i < n; i++) {
            double s = a[i * n + j];
            for (k = 0; k < j; k++)
                s -= a[i * n + k] * a[j * n + k];
            a[i * n + j] = s / d;
        }
    }
    return 0;
}

void hg_cholesky_solve(int n, const double *l, double *b)
{
    int i, k;
    for (i = 0; i < n; i++) {
        double s = b[i];
        for (k = 0; k < i; k++)
            s -= l[i * n + k] * b[k];
        b[i] = s / l[i * n + i];
    }
    for (i = n - 1; i >= 0; i--) {
        double s = b[i];
        for (k = i + 1; k < n; k++)
            s -= l[k * n + i] * b[k];
        b[i] = s / l[i * n + i];
    }
}
