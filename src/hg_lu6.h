/* hg_lu6.h - 6x6 LU factorization with partial pivoting and a solve for
 * several right-hand sides, fixed size and unrolled: the Reduced Joints
 * step factors the 6x6 Phi_c twice per step. */
#ifndef HG_LU6_H
#define HG_LU6_H

/* Factor a (row-major 6x6) in place, row order in piv. 0, or
 * HG_ERR_SINGULAR_JACOBIAN when a pivot is below 1e-13 of the largest
 * entry or not finite. */
int hg_lu6_factor(double a[36], int piv[6]);

/* Solve (L U) X = P B in place for B (6 x nrhs, row-major), nrhs <= 8. */
void hg_lu6_solve(const double lu[36], const int piv[6], int nrhs, double *b);

#endif
