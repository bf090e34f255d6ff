/* hg_errors.h - the project's return codes: 0 is success, each cause of
 * failure has its own negative code, and hg_strerror() names it.
 * Pure C, no LinuxCNC dependency; safe in realtime code. */
#ifndef HG_ERRORS_H
#define HG_ERRORS_H

enum hg_error {
    HG_OK = 0,
    HG_ERR_NONFINITE_INPUT = -1,   /* an input was NaN or inf */
    HG_ERR_UNREACHABLE = -2,       /* a bar cannot reach its guide (IK radicand < 0) */
    HG_ERR_EULER_SINGULAR = -3,    /* |B| beyond 85 deg (HG_MAX_ABS_B_RAD): 3-2-1 Euler angles are singular at 90 */
    HG_ERR_NO_CONVERGENCE = -4,    /* Newton-Raphson used all its iterations */
    HG_ERR_WRONG_BRANCH = -5,      /* converged to an assembly with a carriage below its head joint */
    HG_ERR_SINGULAR_JACOBIAN = -6, /* a constraint Jacobian could not be factored */
    HG_ERR_BAD_PARAM = -7,         /* a parameter set failed validation */
    HG_ERR_STATE_NONFINITE = -8,   /* the integrated state went NaN or inf */
    HG_ERR_STABILIZATION = -9,     /* constraint stabilization diverged */
    HG_ERR_BAD_DT = -10,           /* time step not positive, not finite or too large */
    HG_ERR_SINGULAR_MASS = -11,    /* the reduced mass matrix is not positive definite */
    HG_ERR_DIVERGED = -12,         /* Newton-Raphson step grew instead of shrinking */
    HG_ERR_OUT_OF_VOLUME = -13,    /* a broken machine fell out of the region the model represents */
    HG_ERR_JOINT_RANGE = -14,      /* a bar left the angular range of its carriage or head joint */
    HG_ERR_BAR_CLEARANCE = -15,    /* two bars came closer than the bar diameter */
    HG_ERR_STIFF = -16,            /* parameters too stiff for the step at this period, even with the most substeps */
    HG_ERR_THROUGH_STOP = -17,     /* an axis went through its hard stop (beyond what the stop's spring represents) */
    HG_ERR_NO_MEMORY = -18,        /* host only: memory for a batch of runs could not be had */
    HG_ERR_OUT_OF_RANGE = -19,     /* a finite input beyond the range the computation takes (a servo
                                      command above HG_PID_MAX_ABS in magnitude: it would overflow) */
    HG_ERR_LAST = HG_ERR_OUT_OF_RANGE /* the most negative code: keep it the last */
};

/* A short English description of an hg_error code (static string). */
const char *hg_strerror(int code);

#endif
