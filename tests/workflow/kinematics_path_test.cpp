// workflow::HexapodFkPath, ExechonPosePath, ExechonFkPath and solveWristPoint: round trips along a
// path, the re-seed after a failed solve, the hybrid split and the dependent rotation's reference.
#include "pkm/workflow/kinematics_path.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_ik.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;

TEST(HexapodFkPath, ReturnsThePosesAndRecoversAfterAFailure) {
  const io::HexapodMachine machine = io::loadHexapodMachine("hexapod-default");
  kin::HexapodData data(machine.model);
  HexapodFkPath path(machine);
  for (int k = 0; k < 5; ++k) {
    kin::PoseRpy pose = machine.model.home;
    pose.position += Eigen::Vector3d(2.0 * k, -1.0 * k, 0.5 * k);
    pose.rpy.x() += 0.01 * k;
    const kin::StrutVector q = kin::inverseKinematics(machine.model, data, pose);
    const FkStep step = path.solve(q);
    ASSERT_TRUE(step.summary.ok());
    EXPECT_LT((step.pose.position - pose.position).norm(), 1e-9);
    if (k == 2) {  // readings no pose has: fails, and the next row starts from home again
      kin::StrutVector bad = q;
      bad.setConstant(std::nan(""));
      EXPECT_FALSE(path.solve(bad).summary.ok());
    }
  }
}

TEST(HexapodFkAngles, GiveThePathsAnglesWhenConvertedApart) {
  // A path without angles and a HexapodFkAngles fed its steps in order give the same angles as a
  // path that converts them, across a failure and past c = 180° (continuity, not wrapping).
  const io::HexapodMachine machine = io::loadHexapodMachine("hexapod-default");
  kin::HexapodData data(machine.model);
  kin::PoseRpy seed = machine.model.home;
  seed.rpy.z() = 3.0;
  HexapodFkPath with_angles(machine, seed);
  HexapodFkPath without(machine, seed, false, /*angles=*/false);
  HexapodFkAngles angles(machine, seed, false);
  int ok = 0;
  for (int k = 0; k < 40; ++k) {
    kin::PoseRpy pose = seed;
    pose.position += Eigen::Vector3d(0.5 * k, -0.25 * k, 0.1 * k);
    pose.rpy.z() = 3.0 + 0.01 * k;  // goes past pi
    kin::StrutVector q = kin::inverseKinematics(machine.model, data, pose);
    if (k == 20) q.setConstant(std::nan(""));  // a failed row: both start again from home
    const FkStep a = with_angles.solve(q);
    const FkStep b = without.solve(q);
    const Eigen::Vector3d rpy = angles.next(b);
    ASSERT_EQ(a.summary.ok(), b.summary.ok()) << k;
    if (!a.summary.ok()) continue;
    ++ok;
    EXPECT_EQ(a.pose.position, b.pose.position) << k;
    EXPECT_EQ(a.pose.rpy, rpy) << k;
    if (k < 20) EXPECT_NEAR(rpy.z(), pose.rpy.z(), 1e-9) << k;  // continuous past pi
  }
  EXPECT_EQ(ok, 39);
}

TEST(HexapodFkPath, LongServoPathStaysOnSo3AndAgreesWithSolvesFromTheSeed) {
  // 20 000 rows of a smooth noisy path, each seeded by the prediction from the last two
  // solutions: every row converges in one step (or one and the polishing step), the rotations
  // stay orthonormal to rounding (the prediction's products are taken back to SO(3) now and then),
  // and every pose is the one a solve from a far seed finds. Solving into a step gives the
  // same as the returned step, and angles converted apart (HexapodFkAngles::convert on another
  // step) give next()'s.
  const io::HexapodMachine machine = io::loadHexapodMachine("hexapod-linuxcnc-sim");
  kin::HexapodData data(machine.model), cold(machine.model);
  HexapodFkPath path(machine), twin(machine, std::nullopt, false, /*angles=*/false);
  HexapodFkAngles angles(machine, std::nullopt, false);
  std::mt19937 rng(20261127);
  std::normal_distribution<double> noise(0.0, 2e-5);
  const int n = 20000;
  int most_iterations = 0;
  double worst_orthonormality = 0.0, worst_position = 0.0;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 10000.0;
    kin::PoseRpy pose = machine.model.home;
    pose.position += Eigen::Vector3d(3 * std::sin(t), 3 * (1 - std::cos(t)), std::sin(2 * t));
    pose.rpy += Eigen::Vector3d(0.15 * std::sin(t), 0.12 * std::sin(3 * t), 0.2 * std::sin(t));
    kin::StrutVector q = kin::inverseKinematics(machine.model, data, pose);
    for (int i = 0; i < kin::kStruts; ++i) q[i] += noise(rng);
    const FkStep step = path.solve(q);
    FkStep in_place;
    twin.solve(q, in_place);
    ASSERT_TRUE(step.summary.ok()) << k;
    most_iterations = std::max(most_iterations, step.summary.iterations);
    EXPECT_EQ(step.pose.position, in_place.pose.position) << k;
    EXPECT_EQ(step.world_R_platform, in_place.world_R_platform) << k;
    FkStep converted = in_place;
    HexapodFkAngles::convert(converted);
    EXPECT_EQ(angles.next(converted), step.pose.rpy) << k;
    worst_orthonormality = std::max(
        worst_orthonormality,
        (step.world_R_platform.transpose() * step.world_R_platform - Eigen::Matrix3d::Identity())
            .cwiseAbs()
            .maxCoeff());
    if (k % 500 == 0) {
      ASSERT_TRUE(kin::forwardKinematics(machine.model, cold, q, machine.model.home).ok()) << k;
      worst_position = std::max(worst_position, (cold.pose.position - step.pose.position).norm());
    }
  }
  EXPECT_LE(most_iterations, 2);
  EXPECT_LT(worst_orthonormality, 1e-14);
  EXPECT_LT(worst_position, 1e-12);
}

TEST(ExechonPosePath, SplitsAHybridCommandAndRoundTripsThroughFk) {
  const io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  ASSERT_TRUE(machine.hybrid.has_value());
  ExechonPosePath poses(machine);
  ExechonFkPath fk(machine);
  for (int k = 0; k < 4; ++k) {
    const kin::ExechonToolPose tool{{1000.0 + 20.0 * k, 50.0, -40.0 + 5.0 * k},
                                    {0.05 * k, 0.0, -1.0}};
    const ExechonPoseStep step = poses.solve(tool);
    ASSERT_TRUE(step.solved) << step.check.solver_status;
    EXPECT_EQ(step.status, "ok");
    if (k == 0) {
      EXPECT_EQ(step.drm, 0.0);  // the first pose is the reference
    }
    const FkStep back =
        fk.solve(step.joints, std::array<double, 2>{step.command.x2, step.command.y2});
    ASSERT_TRUE(back.summary.ok());
    EXPECT_LT((back.tool_point - tool.position).norm(), 1e-8);
    EXPECT_LT((back.tool_direction - tool.direction.normalized()).norm(), 1e-8);
  }
}

TEST(ExechonPosePath, RefusesX2Y2WithoutAHybridMachine) {
  io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  machine.hybrid.reset();
  ExechonPosePath poses(machine);
  EXPECT_THROW((void)poses.solve({}, std::array<double, 2>{0.0, 0.0}), InvalidArgument);
}

TEST(SolveWristPoint, SolvesTheHomeWristPoint) {
  const io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  kin::ExechonData data(machine.model);
  kin::evaluateConfiguration(machine.model, data, machine.model.home);
  const Eigen::Vector3d S = data.zoppi_p_S;
  const kin::ExechonLegVector readings = data.readings;
  const ExechonWristStep step = solveWristPoint(machine.model, data, S);
  ASSERT_EQ(step.ik, kin::ExechonIkStatus::kOk);
  EXPECT_EQ(step.status, "ok");
  EXPECT_LT((step.readings - readings).norm(), 1e-9);
  EXPECT_NE(solveWristPoint(machine.model, data, Eigen::Vector3d::Constant(std::nan(""))).ik,
            kin::ExechonIkStatus::kOk);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
