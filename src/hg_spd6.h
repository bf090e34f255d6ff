/* hg_spd6.h - solve M x = b for a 6x6 symmetric positive definite M
 * (the reduced mass matrix of every parametrization) by LDL^T with
 * reciprocal pivots: no square roots, six divisions, fixed size. */
#ifndef HG_SPD6_H
#define HG_SPD6_H

/* Factor the lower triangle of M (row-major 6x6, upper triangle ignored)
 * in place: L below the diagonal, D on it, 1/D into inv_d. 0, or
 * HG_ERR_SINGULAR_MASS when a pivot is not positive (relative to the
 * diagonal) or not finite. */
int hg_spd6_factor(double M[36], double inv_d[6]);

/* Solve with a factored M (hg_spd6_factor) for b in place. */
void hg_spd6_apply(const double M[36], const double inv_d[6], double b[6]);

/* hg_spd6_apply on each of the six columns of B (row-major 6x6) in
 * place, two at a time: each column gets hg_spd6_apply's bits. */
void hg_spd6_apply6(const double M[36], const double inv_d[6], double B[36]);

/* Factor M in place and solve for b in place: 0 or HG_ERR_SINGULAR_MASS. */
int hg_spd6_solve(double M[36], double b[6]);

#endif
