/* fuzz_kinematics.c - inverse and forward kinematics on random, extreme,
 * NaN, inf, denormal and unreachable poses, joints and guesses, and tool
 * offsets (RTCP). Properties: no crash; results finite; a success satisfies
 * the bar equations; a failure is one of the documented codes and leaves the
 * outputs untouched; the iteration count stays within its bound; an
 * offset the check takes keeps a finite pose finite and comes back off,
 * one it refuses never comes into force. */
#include <stdio.h>
#include <stdlib.h>
#include "fuzz_input.h"
#include "hg_errors.h"
#include "hg_guard.h"
#include "hg_kinematics.h"
#include "hg_params.h"

static void fail(const char *what)
{
    fprintf(stderr, "fuzz_kinematics: property violated: %s\n", what);
    abort();
}

static int known_code(int rc)
{
    return rc == HG_OK || rc == HG_ERR_NONFINITE_INPUT || rc == HG_ERR_UNREACHABLE ||
           rc == HG_ERR_EULER_SINGULAR || rc == HG_ERR_NO_CONVERGENCE ||
           rc == HG_ERR_WRONG_BRANCH || rc == HG_ERR_SINGULAR_JACOBIAN || rc == HG_ERR_DIVERGED;
}

/* forward also refuses an answer outside the joints' ranges or with bars touching */
static int known_forward_code(int rc)
{
    return known_code(rc) || rc == HG_ERR_JOINT_RANGE || rc == HG_ERR_BAR_CLEARANCE || rc == HG_ERR_BAD_PARAM;
}

/* largest |phi| / (2 l): bar-length error in metres to first order */
static double worst_phi(const hg_geometry *g, const double z[6], const double pose[6])
{
    double phi[6], w = 0;
    int k;
    hg_constraints(g, z, pose, phi);
    for (k = 0; k < 6; k++)
        if (!(fabs(phi[k]) / (2 * g->l_m) <= w))
            w = fabs(phi[k]) / (2 * g->l_m);
    return w;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_input in = {data, size, 0};
    hg_params p;
    hg_fk_options o;
    hg_fk_report rep;
    double pose[6], z[6], guess[6], before[6];
    int k, rc;
    hg_params_default(&p);
    hg_fk_options_default(&o);
    for (k = 0; k < 6; k++)
        pose[k] = fuzz_double(&in, k < 3 ? -0.6 : -1.7, k < 3 ? 0.6 : 1.7);
    for (k = 0; k < 6; k++)
        z[k] = before[k] = 12345.0;
    rc = hg_inverse_kinematics(&p.geo, pose, z);
    if (!known_code(rc))
        fail("inverse returned an unknown code");
    if (rc == HG_OK) {
        for (k = 0; k < 6; k++)
            if (!isfinite(z[k]))
                fail("inverse returned a non-finite joint");
        if (worst_phi(&p.geo, z, pose) > 1e-9)
            fail("inverse answer does not satisfy the bar equations");
    } else if (memcmp(z, before, sizeof z) != 0) {
        fail("failed inverse touched its output");
    }
    /* forward: joints from the fuzzer (or the inverse's answer), any guess */
    if (fuzz_byte(&in) & 1)
        for (k = 0; k < 6; k++)
            z[k] = fuzz_double(&in, -0.4, 0.4);
    for (k = 0; k < 6; k++)
        guess[k] = before[k] = fuzz_double(&in, k < 3 ? -0.6 : -1.7, k < 3 ? 0.6 : 1.7);
    o.max_iterations = (int)(fuzz_byte(&in) % 140) - 10; /* also zero, negative, above the cap */
    o.tolerance_m = fuzz_double(&in, 0, 1e-6);
    rc = hg_forward_kinematics(&p.geo, z, guess, &o, &rep);
    if (!known_forward_code(rc))
        fail("forward returned an unknown code");
    if ((rc == HG_ERR_BAD_PARAM) != (hg_fk_options_check(&o, 0, 0) != 0))
        fail("forward refused settings the check accepts, or used settings it refuses");
    if (rep.iterations < 0 || rep.iterations > 100)
        fail("forward iterations out of bounds");
    if (rc == HG_OK) {
        for (k = 0; k < 6; k++)
            if (!isfinite(guess[k]))
                fail("forward returned a non-finite pose");
        if (worst_phi(&p.geo, z, guess) > 1e-6 + 1e3 * o.tolerance_m)
            fail("forward answer does not satisfy the bar equations");
        if (hg_guard_check(&p.geo, z, guess, 0, 0) != 0)
            fail("forward answer outside the joints' ranges or with bars touching");
    } else if (memcmp(guess, before, sizeof guess) != 0) {
        fail("failed forward touched its output");
    }
    {
        hg_tool_offset_setting t;
        double d = fuzz_double(&in, -200.0, 200.0), op[6], back[6];
        int finite = 1;
        hg_tool_offset_init(&t);
        for (k = 0; k < 6; k++)
            finite &= isfinite(pose[k]) && isfinite(t.last_inverse[k] = pose[k]);
        hg_tool_offset_take(&t, &p.geo, d, 1);
        if (!isfinite(t.in_force_m) || (t.refusing != (hg_tool_offset_check(&p.geo, d) != HG_OK)) ||
            (!t.refusing && t.in_force_m != d) || (t.refusing && t.in_force_m != 0.0))
            fail("tool offset: a refused value in force, or a valid one not taken");
        if (!t.refusing && finite) {
            hg_pose_offset_to_op(pose, d, op);
            hg_pose_op_to_offset(op, d, back);
            for (k = 0; k < 6; k++)
                if (!isfinite(op[k]) || !(fabs(back[k] - pose[k]) <= 1e-12 * (1.0 + fabs(d) + fabs(pose[k]))))
                    fail("tool offset: a finite pose made non-finite, or not undone");
        }
    }
    return 0;
}
