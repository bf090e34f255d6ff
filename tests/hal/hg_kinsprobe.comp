// hg_kinsprobe - test probe for tests/hal/test_hexaglidekins: calls the
// loaded kinematics module's kinematicsInverse of pose-0..5 (X Y Z A B C,
// machine units and degrees), then its kinematicsForward of those joints
// from the world home (0) as the guess, as motion would; built and installed
// by the test (halcompile --install), removed after it.
component hg_kinsprobe "test probe: the kinematics module's inverse of a pose, then its forward of those joints";
pin in float pose-#[6] "world pose given (X Y Z A B C)";
pin out float joint-#[6] "kinematicsInverse of the pose";
pin out float fwd-#[6] "kinematicsForward of those joints, from the world home (0) as the guess";
pin out s32 ik-rc "kinematicsInverse's return";
pin out s32 fk-rc "kinematicsForward's return";
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
    ik_rc = kinematicsInverse(&p, jj, &fi, &ff);
    for (k = 0; k < 6; k++)
        joint(k) = jj[k];
    fk_rc = kinematicsForward(jj, &q, &ff, &fi);
    fwd(0) = q.tran.x; fwd(1) = q.tran.y; fwd(2) = q.tran.z;
    fwd(3) = q.a; fwd(4) = q.b; fwd(5) = q.c;
}
