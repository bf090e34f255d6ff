/* hg_test.h - minimal TAP-style checks for the host C unit tests.
 * CHECK(cond, fmt, ...) prints "ok - ..." or "not ok - ..."; the exit code
 * of main should be hg_test_exit(); hg_test_uniform, hg_test_frictionless
 * and hg_test_solve are a deterministic random source, a machine without
 * dissipation and a plain dense solver; hg_test_bar_angles the standard
 * model's bar angles of a pose. */
#ifndef HG_TEST_H
#define HG_TEST_H
#include <math.h>
#include <stdio.h>
#include "hg_kinematics.h"
#include <stdlib.h>
#include <string.h>
#include "hg_params.h"
#include "hg_board.h"

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
/* The spec's defaults with the rigid drive train (k_axial = 0: the rotors
 * move with their carriages), the machine the mechanism's closed forms
 * describe; the flexible train has tests of its own (test_drivetrain.c). */
static inline void hg_test_rigid_defaults(hg_params *p)
{
    hg_params_default(p);
    p->k_axial_n_per_m = 0.0;
}

/* Zero every dissipation of p by name (viscous and Coulomb friction, the
 * hard-stop damper, and breakaway friction where the table has it), the
 * rest unchanged: 0, or -1 when a name that must exist is missing. */
static inline int hg_test_frictionless(hg_params *p)
{
    static const char *const required[] = {"c_visc", "f_coulomb", "c_stop"};
    static const char *const optional[] = {"f_static"};
    unsigned i;
    for (i = 0; i < sizeof required / sizeof required[0]; i++)
        if (hg_params_set(p, required[i], 0.0))
            return -1;
    for (i = 0; i < sizeof optional / sizeof optional[0]; i++)
        if (hg_params_field(p, optional[i]))
            hg_params_set(p, optional[i], 0.0);
    return 0;
}

/* Solve the n x n system a x = b (row-major) by Gaussian elimination with
 * partial pivoting: a is overwritten, b receives x (a second, plain solver
 * beside the project's LU and LDL^T ones). */
static inline void hg_test_solve(int n, double *a, double *b)
{
    int i, j, k;
    for (k = 0; k < n; k++) {
        int p = k;
        for (i = k + 1; i < n; i++)
            if (fabs(a[i * n + k]) > fabs(a[p * n + k]))
                p = i;
        for (j = 0; j < n; j++) {
            double t = a[k * n + j];
            a[k * n + j] = a[p * n + j];
            a[p * n + j] = t;
        }
        { double t = b[k]; b[k] = b[p]; b[p] = t; }
        for (i = k + 1; i < n; i++) {
            double f = a[i * n + k] / a[k * n + k];
            for (j = k; j < n; j++)
                a[i * n + j] -= f * a[k * n + j];
            b[i] -= f * b[k];
        }
    }
    for (k = n - 1; k >= 0; k--) {
        for (j = k + 1; j < n; j++)
            b[k] -= a[k * n + j] * b[j];
        b[k] /= a[k * n + k];
    }
}
/* The standard model's two angles of each bar for carriage heights z and
 * head pose: a[2k] = atan2(u_y, -u_z), a[2k+1] = asin(-u_x) of bar k's unit
 * vector u from its carriage joint to its head joint. */
static inline void hg_test_bar_angles(const hg_params *p, const double z[6], const double pose[6],
                                      double a[12])
{
    double B[6][3], A[6][3];
    int k;
    hg_joint_points(&p->geo, z, pose, B, A);
    for (k = 0; k < 6; k++) {
        double u[3] = {(A[k][0] - B[k][0]) / p->geo.l_m, (A[k][1] - B[k][1]) / p->geo.l_m,
                       (A[k][2] - B[k][2]) / p->geo.l_m};
        a[2 * k] = atan2(u[1], -u[2]);
        a[2 * k + 1] = asin(-u[0]);
    }
}

/* The Hexaglide's parameters as the board's block (entry i of the table
 * at v[i]), with substeps and integrator. */
static inline void hg_test_block(hg_board_params *bp, const hg_params *p, unsigned substeps, unsigned integrator)
{
    int i, n;
    memset(bp, 0, sizeof *bp);
    hg_params_table(&n);
    for (i = 0; i < n; i++)
        bp->plant.v[i] = hg_params_get(p, i);
    bp->substeps = substeps;
    bp->integrator = integrator;
}

/* The entry of the Hexaglide's parameter `name` in a board block (aborts
 * the test run on an unknown name: a test must not write nowhere). */
static inline double *hg_test_pv(hg_board_params *bp, const char *name)
{
    int n;
    const hg_param_info *t = hg_params_table(&n);
    int i = hg_param_find(t, n, name);
    if (i < 0) {
        printf("not ok - internal: no parameter %s\n", name);
        exit(1);
    }
    return &bp->plant.v[i];
}

#endif
