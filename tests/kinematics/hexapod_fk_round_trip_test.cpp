// IK -> FK round trips of the hexapod on both sample models (cold starts from home, warm starts
// along a servo path, noisy readings polished to the rounding floor, the second-order corrected
// step), and HexapodFkSolver: its servo-loop path against its general solver bit for bit, and its
// results against the free functions'.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "kinematics/detail/hexapod_legs.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {

namespace PKM_TEST_NS {

double rotationError(const PoseRpy& a, const PoseRpy& b) {
  return geometry::so3Log(geometry::rotationFromRpy(a.rpy) *
                          geometry::rotationFromRpy(b.rpy).transpose())
      .norm();
}

/// Pose k of n on a closed servo path around home: a circle of radius 0.2 L with tilts of 10° and
/// 8° and a yaw of 30°.
PoseRpy servoPathPose(const HexapodModel& m, int k, int n) {
  const double r = 0.2 * m.characteristicLength();
  const double t = 2 * std::numbers::pi * k / n;
  PoseRpy pose = m.home;
  pose.position +=
      Eigen::Vector3d(r * std::sin(t), r * (1 - std::cos(t)), 0.2 * r * std::sin(2 * t));
  pose.rpy += Eigen::Vector3d(
      degToRad(10) * std::sin(t), degToRad(8) * std::sin(3 * t), degToRad(30) * std::sin(t));
  return pose;
}

class HexapodFkRoundTrip : public ::testing::TestWithParam<int> {
 protected:
  HexapodModel model() const {
    return GetParam() == 0 ? test::linuxcncSimModel() : test::millingModel();
  }
};

TEST_P(HexapodFkRoundTrip, ColdStartFromHomeRecoversRandomPoses) {
  const HexapodModel m = model();
  HexapodData data(m);
  std::mt19937 rng(test::kSeed);
  const double reach = 0.3 * m.characteristicLength();
  for (int k = 0; k < 500; ++k) {
    const PoseRpy truth = test::randomPose(rng, m.home, reach, degToRad(15));
    const StrutVector q = inverseKinematics(m, data, truth);
    const FkSummary s = forwardKinematics(m, data, q, m.home);
    ASSERT_TRUE(s.ok()) << toString(s.status) << " at pose " << k;
    EXPECT_LE(s.max_residual, test::kTolRoundTrip);
    EXPECT_LT((data.pose.position - truth.position).norm(), test::kTolRoundTrip);
    EXPECT_LT(rotationError(data.pose, truth), test::kTolRoundTrip);
    EXPECT_LT((data.pose.rpy - truth.rpy).norm(),
              test::kTolRoundTrip);  // same angle triple (continuity)
    EXPECT_LE(s.iterations, 12);     // the continuation's stages together
  }
}

TEST_P(HexapodFkRoundTrip, WarmStartAlongServoPathTakesFewSteps) {
  const HexapodModel m = model();
  HexapodData data(m);
  PoseRpy seed = m.home;
  int max_iter = 0;
  const int n = 2000;
  for (int k = 0; k <= n; ++k) {
    const PoseRpy truth = servoPathPose(m, k, n);
    const StrutVector q = inverseKinematics(m, data, truth);
    const FkSummary s = forwardKinematics(m, data, q, seed);
    ASSERT_TRUE(s.ok());
    EXPECT_LT((data.pose.position - truth.position).norm(), test::kTolRoundTrip);
    EXPECT_LT(rotationError(data.pose, truth), test::kTolRoundTrip);
    max_iter = std::max(max_iter, s.iterations);
    seed = data.pose;
  }
  EXPECT_LE(max_iter, 3);  // quadratic convergence: two steps from the previous cycle, rarely three
}

TEST_P(HexapodFkRoundTrip, NoisyServoPathPolishesToTheRoundingFloor) {
  // Readings with encoder noise along a servo path: one Newton step converges, and the polishing
  // step (a chord step with the last factorisation) leaves the same pose as a solve to a far
  // tighter criterion.
  const HexapodModel m = model();
  HexapodData data(m), tight_data(m), ik(m);
  FkOptions tight;
  tight.tolerance = 1e-13 * m.characteristicLength();
  std::mt19937 rng(test::kSeed);
  std::normal_distribution<double> noise(0.0, 1e-6 * m.characteristicLength());
  const double r = 0.2 * m.characteristicLength();
  PoseRpy seed = m.home;
  int max_iter = 0;
  const int n = 2000;
  for (int k = 0; k <= n; ++k) {
    StrutVector q = inverseKinematics(m, ik, servoPathPose(m, k, n));
    for (int i = 0; i < kStruts; ++i) q[i] += noise(rng);
    const FkSummary s = forwardKinematics(m, data, q, seed);
    ASSERT_TRUE(s.ok()) << k;
    ASSERT_TRUE(forwardKinematics(m, tight_data, q, seed, tight).ok()) << k;
    EXPECT_LT((data.pose.position - tight_data.pose.position).norm(), 1e-12 * r);
    EXPECT_LT(rotationError(data.pose, tight_data.pose), 1e-12);
    max_iter = std::max(max_iter, s.iterations);
    seed = data.pose;
  }
  EXPECT_LE(max_iter, 3);
}

TEST_P(HexapodFkRoundTrip, SecondOrderCorrectedStepLandsInOneIteration) {
  // A seed 5e-6·L and 5e-6 rad from the solution (a servo cycle with noisy readings): the full
  // Newton step leaves ~1e-11·L of second-order residual; corrected for it with the same
  // factorisation it lands below the polishing threshold, so one iteration, no polishing step,
  // and the pose of a solve to a far tighter criterion.
  const HexapodModel m = model();
  HexapodData data(m), tight_data(m), ik(m);
  FkOptions tight;
  tight.tolerance = 1e-13 * m.characteristicLength();
  const double length = m.characteristicLength();
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const PoseRpy truth = servoPathPose(m, k, 200);
    const StrutVector q = inverseKinematics(m, ik, truth);
    PoseRpy seed = truth;
    for (int i = 0; i < 3; ++i) {
      seed.position[i] += 5e-6 * length * unit(rng);
      seed.rpy[i] += 5e-6 * unit(rng);
    }
    const FkSummary s = forwardKinematics(m, data, q, seed);
    ASSERT_TRUE(s.ok()) << k;
    EXPECT_EQ(s.iterations, 1) << k;
    EXPECT_LE(s.max_residual, 1e-3 * FkOptions{}.tolerance) << k;
    ASSERT_TRUE(forwardKinematics(m, tight_data, q, seed, tight).ok()) << k;
    EXPECT_LT((data.pose.position - tight_data.pose.position).norm(), 1e-12 * length);
    EXPECT_LT(rotationError(data.pose, tight_data.pose), 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, HexapodFkRoundTrip, ::testing::Values(0, 1));

}  // namespace PKM_TEST_NS

/// The servo-loop path of HexapodFkSolver beside its general solver.
struct HexapodFkSolverTestPeer {
  using Pose = HexapodFkSolver::Pose;
  static bool near(const HexapodFkSolver& solver,
                   HexapodData& data,
                   const StrutVector& readings,
                   Pose& x,
                   FkSummary& out) {
    StrutVector r0;
    const double gap = detail::computeLegsResidual(solver.model(), data, x.p, x.R, readings, r0);
    return solver.solveNear(data, readings, r0, gap, x, out);
  }
  static FkSummary general(const HexapodFkSolver& solver,
                           HexapodData& data,
                           const StrutVector& readings,
                           Pose& x) {
    detail::computeLegs(solver.model(), data, x.p, x.R);
    return solver.solveGeneral(data, readings, x);
  }
};

namespace PKM_TEST_NS {

TEST(HexapodFkSolver, ServoLoopPathTakesTheGeneralSolversStepsBitForBit) {
  // solveNear is solveGeneral's damped Newton iteration without its bookkeeping: on a noisy servo
  // path (one step, or one step and the polishing step), the same pose, residual and iteration
  // count, bit for bit, and the same legs in data.
  for (const HexapodModel& m : {test::linuxcncSimModel(), test::millingModel()}) {
    const HexapodFkSolver solver(m);
    HexapodData near_data(m), general_data(m), ik(m);
    std::mt19937 rng(test::kSeed);
    std::normal_distribution<double> noise(0.0, 1e-6 * m.characteristicLength());
    PoseRpy seed = m.home;
    int taken = 0, polished = 0;
    for (int k = 0; k <= 1000; ++k) {
      StrutVector q = inverseKinematics(m, ik, servoPathPose(m, k, 50000));
      for (int i = 0; i < kStruts; ++i) q[i] += (k % 3 == 0 ? 30.0 : 1.0) * noise(rng);
      HexapodFkSolverTestPeer::Pose a{seed.position, geometry::rotationFromRpy(seed.rpy)};
      HexapodFkSolverTestPeer::Pose b = a;
      FkSummary near;
      if (!HexapodFkSolverTestPeer::near(solver, near_data, q, a, near)) continue;
      const FkSummary general = HexapodFkSolverTestPeer::general(solver, general_data, q, b);
      ++taken;
      polished += near.iterations == 2 ? 1 : 0;
      ASSERT_EQ(near.status, general.status) << k;
      EXPECT_EQ(near.iterations, general.iterations) << k;
      EXPECT_EQ(near.backtracks, 0) << k;
      EXPECT_EQ(near.max_residual, general.max_residual) << k;
      EXPECT_EQ(a.p, b.p) << k;
      EXPECT_EQ(a.R, b.R) << k;
      EXPECT_EQ(near_data.readings, general_data.readings) << k;
      EXPECT_EQ(near_data.unit_leg, general_data.unit_leg) << k;
      seed.position = a.p;
      seed.rpy = geometry::rpyFromRotation(a.R, seed.rpy);
    }
    EXPECT_GT(taken, 990);
    EXPECT_GT(polished, 0);  // the noisier rows take the polishing step
  }
}

TEST(HexapodFkSolver, SolvesAsTheFreeFunctionsAndLeavesTheSolutionsLegs) {
  // The solver set up once gives forwardKinematics' results bit for bit, from near seeds (a
  // servo path) and far ones (cold starts from home); data's legs are those of the returned pose.
  const HexapodModel m = test::millingModel();
  const HexapodFkSolver solver(m);
  HexapodData a(m), b(m), ik(m), check(m);
  std::mt19937 rng(test::kSeed + 3);
  for (int k = 0; k < 300; ++k) {
    const PoseRpy truth =
        k % 2 == 0 ? servoPathPose(m, k, 300)
                   : test::randomPose(rng, m.home, 0.3 * m.characteristicLength(), degToRad(15));
    const StrutVector q = inverseKinematics(m, ik, truth);
    const PoseRpy seed = k % 2 == 0 ? servoPathPose(m, k - 1, 300) : m.home;
    const Eigen::Matrix3d R = geometry::rotationFromRpy(seed.rpy);
    const FkSummary s = solver.solve(a, q, seed.position, R, &seed.rpy);
    const FkSummary f = forwardKinematics(m, b, q, seed.position, R, &seed.rpy);
    ASSERT_TRUE(s.ok()) << k;
    EXPECT_EQ(s.iterations, f.iterations) << k;
    EXPECT_EQ(s.max_residual, f.max_residual) << k;
    EXPECT_EQ(a.pose.position, b.pose.position) << k;
    EXPECT_EQ(a.pose.rpy, b.pose.rpy) << k;
    EXPECT_EQ(a.world_R_platform, b.world_R_platform) << k;
    detail::computeLegs(m, check, a.world_p_tcp, a.world_R_platform);
    EXPECT_EQ(a.readings, check.readings) << k;
    for (int i = 0; i < kStruts; ++i)
      EXPECT_DOUBLE_EQ(a.inverse_joint_distance[i], 1.0 / a.joint_distance[i]) << k;
  }
  EXPECT_THROW(HexapodFkSolver(m, FkOptions{.tolerance = -1.0}), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics