// Tests of the platform joints' height above a hexapod's base plane
// (pkm/kinematics/hexapod_clearance.hpp): the plane and its orientation, the height against a
// direct computation, the singular plane and the mirror pose beyond it.
#include "pkm/kinematics/hexapod_clearance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;

constexpr double kTol = 1e-12;  // length unit; sums of a few inches

TEST(HexapodClearance, BasePlaneOfTheLinuxcncSimIsZ0PointingUp) {
  const kin::HexapodModel m = pkm::test::linuxcncSimModel();
  const kin::BasePlane plane = kin::basePlane(m);
  EXPECT_NEAR(plane.world_p_centre.z(), 0.0, kTol);
  EXPECT_NEAR(plane.world_n.z(), 1.0, kTol);  // towards the platform at home (z = 20)
}

TEST(HexapodClearance, PlatformJointsFlatAtZ) {
  // The sim's platform joints lie in the platform's z = 0 plane: level, the clearance is z.
  const kin::HexapodModel m = pkm::test::linuxcncSimModel();
  const kin::BasePlane plane = kin::basePlane(m);
  for (const double z : {20.0, 3.0, 0.0, -3.0}) {
    kin::PoseRpy pose = m.home;
    pose.position.z() = z;
    EXPECT_NEAR(kin::platformClearance(m, plane, pose), z, kTol) << z;
  }
}

TEST(HexapodClearance, TiltedPlatformLowestJointCounts) {
  const kin::HexapodModel m = pkm::test::linuxcncSimModel();
  const kin::BasePlane plane = kin::basePlane(m);
  kin::PoseRpy pose = m.home;
  pose.rpy.x() = pkm::degToRad(30.0);
  kin::HexapodData data(m);
  kin::inverseKinematics(m, data, pose);
  double lowest = 1e300;
  for (int i = 0; i < kin::kStruts; ++i)
    lowest = std::min(lowest, (data.world_R_platform * m.effectivePlatform(i) + pose.position).z());
  EXPECT_NEAR(kin::platformClearance(m, plane, pose), lowest, kTol);
  EXPECT_LT(lowest, 20.0 - 1.0);  // the tilt lowers a joint by sin 30° × 11.5 in
}

TEST(HexapodClearance, TheMirrorPoseHasTheSameStrutsAndANegativeClearance) {
  // The reflection of the home assembly about z = 0: the same strut lengths (joints cannot tell
  // them apart), the clearance negated.
  const kin::HexapodModel m = pkm::test::linuxcncSimModel();
  const kin::BasePlane plane = kin::basePlane(m);
  kin::PoseRpy up = m.home, down = m.home;
  up.position.z() = 3.0;
  down.position.z() = -3.0;
  kin::HexapodData a(m), b(m);
  kin::inverseKinematics(m, a, up);
  kin::inverseKinematics(m, b, down);
  for (int i = 0; i < kin::kStruts; ++i)
    EXPECT_NEAR(a.joint_distance[i], b.joint_distance[i], kTol) << i;
  EXPECT_GT(kin::platformClearance(m, plane, up), 0.0);
  EXPECT_LT(kin::platformClearance(m, plane, down), 0.0);
}

TEST(HexapodClearance, NormalFollowsTheHomeSide) {
  // A machine hanging below its base (home z < 0): the normal points down.
  kin::HexapodModel m = pkm::test::linuxcncSimModel();
  m.home.position.z() = -20.0;
  const kin::BasePlane plane = kin::basePlane(m);
  EXPECT_NEAR(plane.world_n.z(), -1.0, kTol);
  EXPECT_NEAR(kin::platformClearance(m, plane, m.home), 20.0, kTol);
}

TEST(HexapodClearance, AssemblyBranchFlipsAtTheMirrorAndBeyondATiltedSingularity) {
  // Home and a small move share a branch; the mirror pose and the sim's corner (X11.09 Y-11.09
  // Z10.95 A43.24 B-43.24 C43.19), which pkmhexkins refused in LinuxCNC (its sign is not home's),
  // do not; in the base plane the Jacobian is singular (0).
  const kin::HexapodModel m = pkm::test::linuxcncSimModel();
  kin::HexapodData data(m);
  const int home = kin::assemblyBranch(m, data, m.home);
  EXPECT_NE(home, 0);
  kin::PoseRpy near = m.home, mirror = m.home, flat = m.home, corner;
  near.position = {1.0, -2.0, 18.0};
  near.rpy = {0.1, -0.05, 0.2};
  mirror.position.z() = -20.0;
  flat.position.z() = 0.0;
  corner.position = {11.09, -11.09, 10.95};
  corner.rpy = {pkm::degToRad(43.24), pkm::degToRad(-43.24), pkm::degToRad(43.19)};
  EXPECT_EQ(kin::assemblyBranch(m, data, near), home);
  EXPECT_EQ(kin::assemblyBranch(m, data, mirror), -home);
  EXPECT_EQ(kin::assemblyBranch(m, data, flat), 0);
  EXPECT_EQ(kin::assemblyBranch(m, data, corner), -home);
}

}  // namespace PKM_TEST_NS
