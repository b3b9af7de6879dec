#include "pkm/kinematics/hexapod_checks.hpp"

#include <gtest/gtest.h>

#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

TEST(HexapodChecks, HomeIsOk) {
  const HexapodModel m = test::millingModel();
  HexapodData data(m);
  const HexapodCheckResult r = checkPose(m, data, m.home);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.status(), "ok");
  EXPECT_GT(r.stroke_margin.minCoeff(), 0.0);
  // Cone axes are the home strut directions: zero deflection at home.
  EXPECT_LT(r.base_angle.maxCoeff(), 1e-9);
  EXPECT_LT(r.platform_angle.maxCoeff(), 1e-9);
  EXPECT_GT(r.interference_margin, 0.0);
  EXPECT_EQ(r.unchecked_pairs, 0);
  EXPECT_GT(r.condition_margin, 0.0);
}

TEST(HexapodChecks, StrokeViolationNamesStrutAndMargin) {
  const HexapodModel m = test::millingModel();
  HexapodData data(m);
  PoseRpy p = m.home;
  p.position.z() -= 400;  // struts far too long
  const HexapodCheckResult r = checkPose(m, data, p);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status(), "stroke");
  const LimitViolation& v = r.violations.front();
  EXPECT_EQ(v.limit, 500.0);
  EXPECT_NEAR(v.margin, v.limit - v.value, test::kTolExact);
  EXPECT_LT(v.margin, 0.0);
  EXPECT_EQ(v.item.rfind("strut ", 0), 0u);
}

TEST(HexapodChecks, JointAngleViolation) {
  HexapodModel m = test::millingModel();
  for (auto& s : m.struts) {
    s.min_reading = -1e9;
    s.max_reading = 1e9;
  }
  HexapodData data(m);
  PoseRpy p = m.home;
  p.position.x() += 700;  // large sideways move tilts the struts beyond 40 deg
  const HexapodCheckResult r = checkPose(m, data, p);
  bool found = false;
  for (const auto& v : r.violations)
    if (v.kind == LimitKind::kJointAngle) {
      found = true;
      EXPECT_GT(v.value, v.limit);
    }
  EXPECT_TRUE(found);
}

TEST(HexapodChecks, InterferenceDetectedWhenStrutsCross) {
  // Neighbouring struts 0-1 meet the platform 129.41 mm apart; twisting the platform brings them
  // closer than that between the joints (129.33 mm at z 100, c 45 deg).
  HexapodModel m = test::millingModel();
  m.strut_diameter = 129.38;
  HexapodData data(m);
  EXPECT_TRUE(checkPose(m, data, m.home).ok());
  PoseRpy p = m.home;
  p.position.z() = 100;
  p.rpy.z() = degToRad(45);
  const HexapodCheckResult r = checkPose(m, data, p);
  ASSERT_FALSE(r.ok());
  bool found = false;
  for (const auto& v : r.violations) found = found || v.kind == LimitKind::kInterference;
  EXPECT_TRUE(found);
  EXPECT_LT(r.interference_margin, 0.0);
  EXPECT_GE(r.closest_pair[0], 0);
}

TEST(HexapodChecks, SharedJointsAreNotCheckedAndDiameterZeroDisables) {
  const HexapodModel m = test::linuxcncSimModel();  // 3-3 base: three shared base joints
  HexapodData data(m);
  const HexapodCheckResult r = checkPose(m, data, m.home);
  EXPECT_EQ(r.unchecked_pairs, 3);
  EXPECT_TRUE(std::isinf(r.interference_margin));
  EXPECT_TRUE(r.ok());
}

TEST(HexapodChecks, SingularityProximity) {
  HexapodModel m = test::millingModel();
  m.max_condition = 1.5;  // stricter than the machine can meet
  HexapodData data(m);
  const HexapodCheckResult r = checkPose(m, data, m.home);
  EXPECT_EQ(r.violations.back().kind, LimitKind::kSingular);
  EXPECT_LT(r.condition_margin, 0.0);
}

TEST(HexapodChecks, DegenerateStrut) {
  const HexapodModel m = test::millingModel();
  HexapodData data(m);
  PoseRpy p = m.home;
  p.position = m.struts[0].world_p_base - m.struts[0].platform_p_joint + m.tool_offset;
  const HexapodCheckResult r = checkPose(m, data, p);
  bool found = false;
  for (const auto& v : r.violations) found = found || v.kind == LimitKind::kDegenerate;
  EXPECT_TRUE(found);
}

TEST(HexapodChecks, KindStrings) {
  EXPECT_EQ(toString(LimitKind::kStroke), "stroke");
  EXPECT_EQ(toString(LimitKind::kJointAngle), "joint_angle");
  EXPECT_EQ(toString(LimitKind::kInterference), "interference");
  EXPECT_EQ(toString(LimitKind::kSingular), "singular");
  EXPECT_EQ(toString(LimitKind::kDegenerate), "degenerate");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
