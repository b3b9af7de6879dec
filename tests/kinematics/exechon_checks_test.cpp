#include "pkm/kinematics/exechon_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "kinematics/exechon_sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

ExechonToolPose homeTool(const ExechonModel& m) {
  ExechonData data(m);
  evaluateConfiguration(m, data, m.home);
  return {data.world_p_tool, data.world_u_tool};
}

TEST(ExechonChecks, HomeIsOkWithPositiveMargins) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  const ExechonCheckResult r = checkToolPose(m, data, homeTool(m));
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.status(), "ok");
  EXPECT_GT(r.stroke_margin.minCoeff(), 0.0);
  EXPECT_GT(std::min({r.alpha_margin, r.beta_margin, r.c_margin, r.a_margin}), 0.0);
  EXPECT_GT(r.condition_margin, 0.0);
  EXPECT_NEAR(r.c, m.home.c, test::kTolRoundTrip);
  EXPECT_NEAR(r.a, m.home.a, test::kTolRoundTrip);
  // Stroke margin is the distance to the nearer end.
  const ExechonLeg& legB = m.legs[1];
  EXPECT_NEAR(r.stroke_margin[1],
              std::min(r.readings[1] - legB.min_reading, legB.max_reading - r.readings[1]),
              test::kTolExact);
}

TEST(ExechonChecks, NamesTheViolatedLimitWithItsMargin) {
  ExechonModel m = test::machineModel();
  ExechonData data(m);
  evaluateConfiguration(m, data, m.home);
  const double qB = data.readings[1];
  m.legs[1].max_reading = qB - 10;
  m.limits.a = {-1.0, m.home.a - 0.1};
  ExechonCheckResult r = checkConfiguration(m, data);
  ASSERT_EQ(r.violations.size(), 2u);
  EXPECT_EQ(r.status(), "stroke");
  EXPECT_EQ(r.violations[0].item, "leg B");
  EXPECT_NEAR(r.violations[0].margin, -10, test::kTolRoundTrip);
  EXPECT_EQ(r.violations[0].limit, qB - 10);
  EXPECT_EQ(toString(r.violations[1].kind), "joint_angle");
  EXPECT_EQ(r.violations[1].item, "wrist A");
  EXPECT_NEAR(r.violations[1].margin, -0.1, test::kTolRoundTrip);

  m = test::machineModel();
  m.limits.beta = {m.home.e[1] + 0.05, 1.0};
  r = checkConfiguration(m, data);
  ASSERT_EQ(r.violations.size(), 1u);
  EXPECT_EQ(r.violations[0].item, "beta");
  EXPECT_NEAR(r.beta_margin, -0.05, test::kTolRoundTrip);

  m = test::machineModel();
  m.max_condition = 1.0 + 1e-9;  // any real configuration is above it
  r = checkConfiguration(m, data);
  EXPECT_EQ(r.status(), "singular");
  EXPECT_EQ(r.violations.back().item, "jacobian");
  EXPECT_LT(r.condition_margin, 0.0);
}

TEST(ExechonChecks, SolverFailuresAreStatusWords) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(checkToolPose(m, data, {{nan, 0, 0}, {0, 0, -1}}).status(), "invalid_input");
  const Eigen::Vector3d u(0, 0, -1);
  const Eigen::Vector3d on_axis = m.world_T_zoppi * Eigen::Vector3d(0, 100, 0);
  const ExechonCheckResult r =
      checkToolPose(m, data, {on_axis + m.wrist.tool_length * u, u}, m.home);
  EXPECT_EQ(r.status(), "unreachable");
  EXPECT_FALSE(r.ok());
  FkOptions few;
  few.max_iterations = 3;
  EXPECT_EQ(checkJoints(m, data, {{1e6, 0, 0}, 0, 0}, m.home, few).status(), "no_convergence");
  // FK of the home joints is ok and checks like IK.
  evaluateConfiguration(m, data, m.home);
  const ExechonCheckResult fk = checkJoints(m, data, jointsOf(data), m.home);
  EXPECT_TRUE(fk.ok());
  EXPECT_NEAR(fk.alpha, m.home.e[0], test::kTolRoundTrip);
}

TEST(ExechonChecks, PoleIsReportedNotViolated) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  ExechonConfiguration config = m.home;
  config.a = -m.wrist.a0 * m.wrist.a_sign;
  evaluateConfiguration(m, data, config);
  const ExechonCheckResult r = checkConfiguration(m, data);
  EXPECT_TRUE(r.wrist_at_pole);
  EXPECT_TRUE(r.ok());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
