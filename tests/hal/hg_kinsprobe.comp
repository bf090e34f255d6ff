// hg_kinsprobe - test probe for tests/hal/test_hexaglidekins: calls the
// loaded kinematics module's kinematicsInverse of pose-0..5 (X Y Z A B C,
// machine units and degrees), then its kinematicsForward of those joints
// from the world home (0) as the guess, as motion would (or of pose-0..5
// themselves as joints, forward-of-pose); kins-type switches the module's
// kinematics type as motion.switchkins-type does; built and installed by
// the test (halcompile --install), removed after it.
component hg_kinsprobe "test probe: the kinematics module's inverse of a pose, then its forward of those joints";
pin in float pose-#[6] "world pose given (X Y Z A B C)";
pin out float joint-#[6] "kinematicsInverse of the pose";
pin out float fwd-#[6] "kinematicsForward of those joints, from the world home (0) as the guess";
pin out s32 ik-rc "kinematicsInverse's return";
pin out s32 fk-rc "kinematicsForward's return";
pin in bit forward-of-pose "TRUE: kinematicsForward of pose-0..5 as the joints";
pin in s32 kins-type "the kinematics type asked for (kinematicsSwitch when it changes)";
pin out s32 switch-rc "kinematicsSwitch's return at the last change";
variable int type_in_force;
function _;
license "GPL";
;;
#include "kinematics.h"
FUNCTION(_) {
    EmcPose p, q;
    double jj[9] = {0};
    KINEMATICS_FORWARD_FLAGS ff = 0;
    KINEMATICS_INVERSE_FLAGS fi = 0;
    int k;
    memset(&p, 0, sizeof p);
    memset(&q, 0, sizeof q);
    p.tran.x = pose(0); p.tran.y = pose(1); p.tran.z = pose(2);
    p.a = pose(3); p.b = pose(4); p.c = pose(5);
    if (kins_type != type_in_force) {
        switch_rc = kinematicsSwitch(kins_type);
        type_in_force = kins_type;
    }
    ik_rc = kinematicsInverse(&p, jj, &fi, &ff);
    for (k = 0; k < 6; k++)
        joint(k) = jj[k];
    if (forward_of_pose)
        for (k = 0; k < 6; k++)
            jj[k] = pose(k);
    fk_rc = kinematicsForward(jj, &q, &ff, &fi);
    fwd(0) = q.tran.x; fwd(1) = q.tran.y; fwd(2) = q.tran.z;
    fwd(3) = q.a; fwd(4) = q.b; fwd(5) = q.c;
}
