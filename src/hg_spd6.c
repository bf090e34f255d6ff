/* hg_spd6.c - 6x6 LDL^T solve for the reduced mass matrices. */
#include "hg_math.h"
#include "hg_spd6.h"
#include "hg_errors.h"
#include "hg_compiler.h"
#include "hg_linalg.h"


#define HG_SPD6_MIN_PIVOT 1e-13   /* relative to the diagonal entry */

int hg_spd6_factor(double M[36], double inv_d[6])
{
    int i, j, k;
    HG_UNROLL
    for (j = 0; j < 6; j++) {
        double d = M[6 * j + j];
        HG_UNROLL
        for (k = 0; k < j; k++)
            d -= M[6 * j + k] * M[6 * j + k] * M[6 * k + k];
        if (!(d > HG_SPD6_MIN_PIVOT * M[6 * j + j]) || !isfinite(d))
            return HG_ERR_SINGULAR_MASS;
        M[6 * j + j] = d;
        inv_d[j] = 1.0 / d;
        HG_UNROLL
        for (i = j + 1; i < 6; i++) {   /* L(i,j) = (M(i,j) - sum L(i,k) D(k) L(j,k)) / D(j) */
            double s = M[6 * i + j];
            HG_UNROLL
            for (k = 0; k < j; k++)
                s -= M[6 * i + k] * M[6 * k + k] * M[6 * j + k];
            M[6 * i + j] = s * inv_d[j];
        }
    }
    return 0;
}

void hg_spd6_apply(const double M[36], const double inv_d[6], double b[6])
{
    int i, k;
    HG_UNROLL
    for (i = 0; i < 6; i++)            /* L y = b */
        HG_UNROLL
        for (k = 0; k < i; k++)
            b[i] -= M[6 * i + k] * b[k];
    HG_UNROLL
    for (i = 0; i < 6; i++)            /* D z = y */
        b[i] *= inv_d[i];
    HG_UNROLL
    for (i = 5; i >= 0; i--)           /* L^T x = z */
        HG_UNROLL
        for (k = i + 1; k < 6; k++)
            b[i] -= M[6 * k + i] * b[k];
}

void hg_spd6_apply6(const double M[36], const double inv_d[6], double B[36])
{
    hg_v2 b[6][3];
    int i, k, c;
    HG_UNROLL
    for (i = 0; i < 6; i++)
        HG_UNROLL
        for (c = 0; c < 3; c++)
            b[i][c] = hg_v2_load(B + 6 * i + 2 * c);
    HG_UNROLL
    for (i = 0; i < 6; i++)            /* L y = b */
        HG_UNROLL
        for (k = 0; k < i; k++)
            HG_UNROLL
            for (c = 0; c < 3; c++)
                b[i][c] = hg_v2_sub(b[i][c], hg_v2_mul(hg_v2_dup(M[6 * i + k]), b[k][c]));
    HG_UNROLL
    for (i = 0; i < 6; i++)            /* D z = y */
        HG_UNROLL
        for (c = 0; c < 3; c++)
            b[i][c] = hg_v2_mul(b[i][c], hg_v2_dup(inv_d[i]));
    HG_UNROLL
    for (i = 5; i >= 0; i--)           /* L^T x = z */
        HG_UNROLL
        for (k = i + 1; k < 6; k++)
            HG_UNROLL
            for (c = 0; c < 3; c++)
                b[i][c] = hg_v2_sub(b[i][c], hg_v2_mul(hg_v2_dup(M[6 * k + i]), b[k][c]));
    HG_UNROLL
    for (i = 0; i < 6; i++)
        HG_UNROLL
        for (c = 0; c < 3; c++)
            hg_v2_store(B + 6 * i + 2 * c, b[i][c]);
}

int hg_spd6_solve(double M[36], double b[6])
{
    double id[6];      /* 1 / D */
    int rc = hg_spd6_factor(M, id);
    if (rc)
        return rc;
    hg_spd6_apply(M, id, b);
    return 0;
}
