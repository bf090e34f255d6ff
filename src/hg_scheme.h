/* hg_scheme.h - the time integration schemes every plant's step offers
 * (hg_integrate.h runs them on the Hexaglide's state), their names, their
 * tableaux and the default. Pure C. */
#ifndef HG_SCHEME_H
#define HG_SCHEME_H

/* Time integration scheme of one step (hg_integrate.[ch] holds the schemes). */
typedef enum {
    HG_INTEGRATOR_IMPROVED_EULER = 0, /* the paper's: q += qd dt + qdd dt^2/2, qd += qdd dt */
    HG_INTEGRATOR_HEUN = 1,           /* second order (RK2), then the same stabilization (default) */
    HG_INTEGRATOR_RK4 = 2,            /* classical fourth order, then the same stabilization */
    HG_INTEGRATOR_COUNT = 3
} hg_integrator;

/* The scheme of hg_model_init and of the board at load: Heun, within 1 um
 * of the converged answer at the 1 ms servo period (tests/unit/test_integrate). */
#define HG_INTEGRATOR_DEFAULT HG_INTEGRATOR_HEUN

/* Name of a scheme ("improved-euler", "heun", "rk4"); 0 for an invalid one. */
const char *hg_integrator_name(hg_integrator which);

/* HG_INTEGRATOR_DEFAULT, for bindings that cannot read a macro (Python). */
int hg_integrator_default(void);

/* Scheme for a name, or -1 when the name is unknown. */
int hg_integrator_from_name(const char *name);

/* Stage offsets c_i and weights b_i of an explicit Runge-Kutta scheme
 * whose stage i starts from y0 + c_i dt k_(i-1) (Heun's and classical
 * RK4's tableaux, every plant's; improved Euler has none): the number of
 * stages, 0 for improved Euler or an unknown scheme. */
int hg_scheme_tableau(hg_integrator scheme, const double **c, const double **b);

#endif
