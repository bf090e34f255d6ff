/* hg_errors.c - names of the project's return codes. */
#include "hg_errors.h"

const char *hg_strerror(int code)
{
    switch (code) {
    case HG_OK: return "ok";
    case HG_ERR_NONFINITE_INPUT: return "input is NaN or infinite";
    case HG_ERR_UNREACHABLE: return "pose unreachable: a bar cannot reach its guide";
    case HG_ERR_EULER_SINGULAR: return "tilt B beyond +-85 degrees (the 3-2-1 Euler angles are singular at +-90)";
    case HG_ERR_NO_CONVERGENCE: return "Newton-Raphson did not converge within its iteration limit";
    case HG_ERR_WRONG_BRANCH: return "solution on another assembly branch (a carriage below its head joint)";
    case HG_ERR_SINGULAR_JACOBIAN: return "constraint Jacobian singular";
    case HG_ERR_BAD_PARAM: return "invalid parameter";
    case HG_ERR_STATE_NONFINITE: return "simulated state became NaN or infinite";
    case HG_ERR_STABILIZATION: return "constraint stabilization diverged";
    case HG_ERR_BAD_DT: return "time step not positive, not finite or too large";
    case HG_ERR_SINGULAR_MASS: return "reduced mass matrix not positive definite";
    case HG_ERR_DIVERGED: return "Newton-Raphson diverged";
    case HG_ERR_OUT_OF_VOLUME: return "machine fell out of the volume the model represents (broken bar)";
    case HG_ERR_JOINT_RANGE: return "a bar left the angular range of its carriage or head joint";
    case HG_ERR_BAR_CLEARANCE: return "two bars came closer than the bar diameter (they touch)";
    case HG_ERR_STIFF: return "the parameters are too stiff for the integration step at this period";
    case HG_ERR_THROUGH_STOP: return "an axis went through its hard stop (the machine has crashed)";
    case HG_ERR_NO_MEMORY: return "out of memory for the batch of closed-loop runs";
    case HG_ERR_OUT_OF_RANGE: return "input beyond the range the computation takes (above 1e9 in magnitude)";
    default: return "unknown error";
    }
}
