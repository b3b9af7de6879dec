#include "pkm/kinematics/exechon_wrist.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "kinematics/exechon_sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

/// A random configuration near home: alpha, beta ± 10°, h ± 10 % of L, C ± 150°, A in ±[10°, 80°].
ExechonConfiguration randomConfiguration(std::mt19937& rng, const ExechonModel& m) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ExechonConfiguration c;
  c.e = m.home.e + Eigen::Vector3d(degToRad(10) * u(rng),
                                   degToRad(10) * u(rng),
                                   0.1 * m.characteristicLength() * u(rng));
  c.c = degToRad(150) * u(rng);
  const double a = degToRad(45 + 35 * u(rng));
  c.a = u(rng) < 0 ? -a : a;
  return c;
}

ExechonToolPose toolPoseOf(const ExechonData& data) {
  return {data.world_p_tool, data.world_u_tool};
}

TEST(ExechonWrist, ToolDirectionConvention) {
  ExechonWrist w;
  w.c_axis = {0, 0, 2};
  w.a_axis = {3, 0, 0};
  EXPECT_LT((toolRotationInPlatform(w, 0, 0).col(2) - Eigen::Vector3d::UnitZ()).norm(),
            test::kTolExact);
  const double c = 0.4, a = 0.7;
  const Eigen::Vector3d expected(
      std::sin(c) * std::sin(a), -std::cos(c) * std::sin(a), std::cos(a));
  EXPECT_LT((toolRotationInPlatform(w, c, a).col(2) - expected).norm(), test::kTolExact);
  w.c_sign = -1;
  w.a_sign = -1;
  w.c0 = 0.1;
  w.a0 = 0.2;
  const Eigen::Vector3d flipped(std::sin(0.1 - c) * std::sin(0.2 - a),
                                -std::cos(0.1 - c) * std::sin(0.2 - a),
                                std::cos(0.2 - a));
  EXPECT_LT((toolRotationInPlatform(w, c, a).col(2) - flipped).norm(), test::kTolExact);
}

TEST(ExechonWrist, IkFkRoundTrips) {
  const ExechonModel m = test::machineModel();
  ExechonData truth(m), data(m), fk(m);
  std::mt19937 rng(test::kSeed);
  for (int k = 0; k < 500; ++k) {
    const ExechonConfiguration config = randomConfiguration(rng, m);
    evaluateConfiguration(m, truth, config);
    ExechonConfiguration previous = config;
    previous.c += 0.01;
    previous.a -= 0.01;
    previous.e[0] += 0.01;
    ASSERT_EQ(toolInverseKinematics(m, data, toolPoseOf(truth), previous), ExechonIkStatus::kOk);
    EXPECT_LT((data.e - config.e).norm(), test::kTolRoundTrip) << k;
    EXPECT_NEAR(data.c, config.c, test::kTolRoundTrip);
    EXPECT_NEAR(data.a, config.a, test::kTolRoundTrip);
    EXPECT_LT((data.readings - truth.readings).norm(), test::kTolRoundTrip);
    EXPECT_LT((data.world_p_tool - truth.world_p_tool).norm(), test::kTolRoundTrip);
    EXPECT_LT((data.world_R_tool - truth.world_R_tool).norm(), test::kTolRoundTrip);
    EXPECT_FALSE(data.wrist_at_pole);

    const FkSummary s = toolForwardKinematics(m, fk, jointsOf(data), m.home);
    ASSERT_TRUE(s.ok()) << k;
    EXPECT_LT((fk.world_p_tool - truth.world_p_tool).norm(), test::kTolRoundTrip);
    EXPECT_LT((fk.world_u_tool - truth.world_u_tool).norm(), test::kTolRoundTrip);
  }
}

TEST(ExechonWrist, ReusedDataFollowsAChangedWrist) {
  // ExechonData caches the wrist frame: a model with other wrist axes must not reuse it.
  ExechonModel m = test::machineModel();
  ExechonModel tilted = m;
  tilted.wrist.c_axis = Eigen::Vector3d(0.1, 0.0, 1.0).normalized();
  tilted.wrist.a_axis = Eigen::Vector3d(1.0, 0.0, -0.1).normalized();
  ExechonData data(m), truth(tilted);
  std::mt19937 rng(test::kSeed + 7);
  for (const ExechonModel* model : {&m, &tilted, &m}) {
    const ExechonConfiguration config = randomConfiguration(rng, *model);
    evaluateConfiguration(*model, truth, config);
    ASSERT_EQ(toolInverseKinematics(*model, data, toolPoseOf(truth), config), ExechonIkStatus::kOk);
    EXPECT_NEAR(data.c, config.c, test::kTolRoundTrip);
    EXPECT_NEAR(data.a, config.a, test::kTolRoundTrip);
    EXPECT_LT((data.world_R_tool - truth.world_R_tool).norm(), test::kTolRoundTrip);
  }
}

TEST(ExechonWrist, OtherWristSolutionWhenPreviousIsThere) {
  const ExechonModel m = test::machineModel();
  ExechonData truth(m), data(m);
  ExechonConfiguration config = m.home;
  config.c = 0.5;
  config.a = 0.6;
  evaluateConfiguration(m, truth, config);
  ExechonConfiguration other = config;
  other.c += m.wrist.c_sign * std::numbers::pi;  // θC + pi ...
  other.a = -config.a - 2 * m.wrist.a0;          // ... and θA -> −θA
  ASSERT_EQ(toolInverseKinematics(m, data, toolPoseOf(truth), other), ExechonIkStatus::kOk);
  EXPECT_NEAR(data.c, other.c, test::kTolRoundTrip);
  EXPECT_NEAR(data.a, other.a, test::kTolRoundTrip);
  EXPECT_LT((data.world_p_tool - truth.world_p_tool).norm(), test::kTolRoundTrip);
  EXPECT_LT((data.world_u_tool - truth.world_u_tool).norm(), test::kTolRoundTrip);
  // Without a previous solution the wrist solution nearest home (c, a) is taken.
  ASSERT_EQ(toolInverseKinematics(m, data, toolPoseOf(truth)), ExechonIkStatus::kOk);
  EXPECT_NEAR(data.c, config.c, test::kTolRoundTrip);
  EXPECT_NEAR(data.a, config.a, test::kTolRoundTrip);
}

TEST(ExechonWrist, ContinuousAlongAPathThroughManyTurnsOfC) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m), start(m);
  evaluateConfiguration(m, start, m.home);
  ExechonConfiguration previous = m.home;
  const int n = 3000;
  double worst_step = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double t = 3 * 2 * std::numbers::pi * k / n;  // the tool direction circles three times
    const Eigen::Vector3d tilt =
        0.4 * (std::cos(t) * Eigen::Vector3d::UnitX() + std::sin(t) * Eigen::Vector3d::UnitY());
    const ExechonToolPose target{start.world_p_tool + Eigen::Vector3d(20 * std::sin(t / 3), 0, 0),
                                 (-Eigen::Vector3d::UnitZ() + tilt).normalized()};
    ASSERT_EQ(toolInverseKinematics(m, data, target, previous), ExechonIkStatus::kOk) << k;
    if (k > 0)
      worst_step =
          std::max({worst_step, std::abs(data.c - previous.c), std::abs(data.a - previous.a)});
    EXPECT_LT((data.world_u_tool - target.direction).norm(), test::kTolRoundTrip);
    previous = configurationOf(data);
  }
  EXPECT_LT(worst_step, degToRad(2));
  EXPECT_GT(std::abs(data.c - m.home.c), 4 * std::numbers::pi);  // C unwound, not wrapped
}

TEST(ExechonWrist, PoleKeepsC) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m), truth(m);
  ExechonConfiguration config = m.home;
  config.c = 1.234;
  config.a = -m.wrist.a0 * m.wrist.a_sign;  // θA = 0
  evaluateConfiguration(m, truth, config);
  EXPECT_TRUE(truth.wrist_at_pole);
  ExechonConfiguration previous = config;
  previous.c = -0.5;
  ASSERT_EQ(toolInverseKinematics(m, data, toolPoseOf(truth), previous), ExechonIkStatus::kOk);
  EXPECT_TRUE(data.wrist_at_pole);
  EXPECT_EQ(data.c, previous.c);
  EXPECT_NEAR(data.a, config.a, test::kTolRoundTrip);
  EXPECT_LT((data.world_p_tool - truth.world_p_tool).norm(), test::kTolRoundTrip);
}

TEST(ExechonWrist, BiJinToolFrameCrossCheck) {
  const ExechonModel m = test::biJinToyModel();
  ExechonData data(m);
  const test::BiJin bj = test::biJinInverse({10, -20, 250});
  ASSERT_EQ(tripodInverseKinematics(m, data, m.world_T_zoppi.inverse() * bj.S),
            ExechonIkStatus::kOk);
  // exechon-lib's platform axes (x', y', z') are Zoppi's (j, −i, k).
  Eigen::Matrix3d platform_R_bj;
  platform_R_bj << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  EXPECT_LT((data.world_T_platform.linear() * platform_R_bj - bj.R).norm(), test::kTolRoundTrip);
  const double q4 = 0.3, q5 = -0.7, L2 = 150;
  evaluateConfiguration(m, data, {data.e, q4, q5});
  const Eigen::Matrix3d R45 = bj.R * (Eigen::AngleAxisd(q4, Eigen::Vector3d::UnitZ()) *
                                      Eigen::AngleAxisd(q5, Eigen::Vector3d::UnitX()))
                                         .toRotationMatrix();
  EXPECT_LT((data.world_p_tool - (bj.S + L2 * R45.col(1))).norm(), test::kTolRoundTrip);
  EXPECT_LT((data.world_u_tool - R45.col(1)).norm(), test::kTolRoundTrip);
}

TEST(ExechonWrist, BadInputLeavesDataUntouched) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  evaluateConfiguration(m, data, m.home);
  const ExechonConfiguration before = configurationOf(data);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(toolInverseKinematics(m, data, {{0, 0, 0}, {0, 0, 0}}), ExechonIkStatus::kInvalidInput);
  EXPECT_EQ(toolInverseKinematics(m, data, {{nan, 0, 0}, {0, 0, 1}}),
            ExechonIkStatus::kInvalidInput);
  // A wrist point on Zoppi's base axis jb (the A/C first joint axis) is unreachable (|hx| > 0).
  const Eigen::Vector3d on_axis = m.world_T_zoppi * Eigen::Vector3d(0, 100, 0);
  const Eigen::Vector3d u = -Eigen::Vector3d::UnitZ();
  EXPECT_EQ(toolInverseKinematics(m, data, {on_axis + m.wrist.tool_length * u, u}),
            ExechonIkStatus::kUnreachable);
  EXPECT_EQ(configurationOf(data).e, before.e);
  EXPECT_EQ(data.c, before.c);
}

TEST(ExechonWrist, ToolPointIkRoundTripsWithTheReadingsHeld) {
  ExechonModel offsets = test::machineModel();
  offsets.tripod.l12B = 3.0;  // leg B's base-joint offsets: S(e) by its own Newton solve
  offsets.tripod.l23B = -2.0;
  for (const ExechonModel& m : {test::machineModel(), test::biJinToyModel(), offsets}) {
    std::mt19937 rng(test::kSeed + 11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    ExechonData truth(m), data(m);
    for (int k = 0; k < 100; ++k) {
      const ExechonConfiguration cfg = randomConfiguration(rng, m);
      evaluateConfiguration(m, truth, cfg);
      // Started a few degrees and millimetres away, or a turn away in alpha (the same pose).
      const Eigen::Vector3d start =
          k % 10 == 0 ? Eigen::Vector3d(cfg.e + Eigen::Vector3d(2 * std::numbers::pi, 0, 0))
                      : Eigen::Vector3d(cfg.e + Eigen::Vector3d(degToRad(3) * u(rng),
                                                                degToRad(3) * u(rng),
                                                                5.0 * u(rng)));
      ASSERT_EQ(toolPointInverseKinematics(m, data, truth.world_p_tool, cfg.c, cfg.a, start),
                ExechonIkStatus::kOk)
          << m.name << " " << k;
      EXPECT_LT((data.world_p_tool - truth.world_p_tool).norm(), test::kTolRoundTrip) << k;
      EXPECT_LT((data.e - cfg.e).norm(), test::kTolRoundTrip) << m.name << " " << k;
      EXPECT_LT((data.readings - truth.readings).cwiseAbs().maxCoeff(), test::kTolRoundTrip);
      EXPECT_LT((data.world_u_tool - truth.world_u_tool).norm(), test::kTolRoundTrip);
      EXPECT_EQ(data.c, cfg.c);
      EXPECT_EQ(data.a, cfg.a);
      EXPECT_EQ(data.branch, truth.branch);
    }
  }
}

TEST(ExechonWrist, ToolPointIkFailuresLeaveDataUntouched) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  evaluateConfiguration(m, data, m.home);
  const Eigen::Vector3d p = data.world_p_tool, e_before = data.e;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(toolPointInverseKinematics(m, data, {nan, 0, 0}, 0, 0, m.home.e),
            ExechonIkStatus::kInvalidInput);
  EXPECT_EQ(toolPointInverseKinematics(m, data, p, nan, 0, m.home.e),
            ExechonIkStatus::kInvalidInput);
  EXPECT_EQ(toolPointInverseKinematics(m, data, p, 0, 0, {0, nan, 0}),
            ExechonIkStatus::kInvalidInput);
  // A tool point on the base axis jb: its wrist point, within the tool length (250 mm), would lie
  // inside the cylinder |(Sx, Sz)| < hx (282.8 mm) that no tripod pose reaches.
  const Eigen::Vector3d on_axis = m.world_T_zoppi * Eigen::Vector3d(0.0, 700.0, 0.0);
  EXPECT_EQ(toolPointInverseKinematics(m, data, on_axis, m.home.c, m.home.a, m.home.e),
            ExechonIkStatus::kSingular);
  EXPECT_EQ(data.e, e_before);
  EXPECT_EQ(data.world_p_tool, p);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
