#include "pkm/kinematics/exechon_fk.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "kinematics/exechon_sample_models.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_ik.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

Eigen::Vector3d randomE(std::mt19937& rng, const Eigen::Vector3d& centre, double length) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return centre +
         Eigen::Vector3d(degToRad(12) * u(rng), degToRad(12) * u(rng), 0.15 * length * u(rng));
}

double angleDistance(double a, double b) {
  return std::abs(std::remainder(a - b, 2 * std::numbers::pi));
}

/// IK -> FK round trips over the workspace in every one of the 16 branches, seeded 2° / 2 % of L
/// away.
TEST(ExechonFk, RoundTripsEveryBranch) {
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int b = 0; b < 16; ++b) {
    ExechonModel m = test::machineModel();
    const ExechonBranch branch = ExechonBranch::fromIndex(b);
    m.tripod.deltaA = branch.deltaA;
    m.tripod.deltaC = branch.deltaC;
    const double length = m.characteristicLength();
    ExechonData data(m);
    for (int k = 0; k < 100; ++k) {
      const Eigen::Vector3d S = wristPointFromParameters(m.tripod, randomE(rng, m.home.e, length));
      ASSERT_EQ(tripodInverseKinematics(m, data, S, branch), ExechonIkStatus::kOk);
      const Eigen::Vector3d truth = data.e;
      const ExechonLegVector readings = data.readings;
      const Eigen::Vector3d seed =
          truth +
          Eigen::Vector3d(degToRad(2) * u(rng), degToRad(2) * u(rng), 0.02 * length * u(rng));
      const FkSummary s = tripodForwardKinematics(m, data, readings, seed);
      ASSERT_TRUE(s.ok()) << toString(s.status) << " branch " << b << " pose " << k;
      EXPECT_LE(s.max_residual, test::kTolRoundTrip);
      EXPECT_LT(angleDistance(data.e[0], truth[0]) + angleDistance(data.e[1], truth[1]),
                test::kTolRoundTrip);
      EXPECT_NEAR(data.e[2], truth[2], test::kTolRoundTrip);
      EXPECT_LT((data.zoppi_p_S - S).norm(), test::kTolRoundTrip);
      EXPECT_EQ(data.branch, branch);
      EXPECT_LE(s.iterations, 6);
    }
  }
}

TEST(ExechonFk, ColdStartFromHome) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  std::mt19937 rng(test::kSeed + 1);
  int worst = 0;
  for (int k = 0; k < 300; ++k) {
    evaluateTripod(m, data, randomE(rng, m.home.e, m.characteristicLength()), 1, 1);
    const Eigen::Vector3d truth = data.e;
    const FkSummary s = tripodForwardKinematics(m, data, data.readings, m.home.e);
    ASSERT_TRUE(s.ok()) << k;
    EXPECT_LT((data.e - truth).norm(), test::kTolRoundTrip);
    worst = std::max(worst, s.iterations);
  }
  EXPECT_LE(worst, 8);
}

TEST(ExechonFk, WarmStartAlongPathTakesFewSteps) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  Eigen::Vector3d seed = m.home.e;
  int worst = 0;
  const int n = 2000;
  for (int k = 0; k <= n; ++k) {
    const double t = 2 * std::numbers::pi * k / n;
    const Eigen::Vector3d e =
        m.home.e +
        Eigen::Vector3d(0.1 * std::sin(t), 0.1 * std::sin(2 * t), 80 * (1 - std::cos(t)));
    evaluateTripod(m, data, e, 1, 1);
    const FkSummary s = tripodForwardKinematics(m, data, data.readings, seed);
    ASSERT_TRUE(s.ok());
    EXPECT_LT((data.e - e).norm(), test::kTolRoundTrip);
    worst = std::max(worst, s.iterations);
    seed = data.e;
  }
  EXPECT_LE(worst, 3);
}

TEST(ExechonFk, BadInputAndOptions) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  evaluateTripod(m, data, m.home.e, 1, 1);
  const ExechonLegVector q = data.readings;
  EXPECT_EQ(tripodForwardKinematics(m, data, {nan, 1, 1}, m.home.e).status,
            FkStatus::kInvalidInput);
  EXPECT_EQ(tripodForwardKinematics(m, data, q, {0, INFINITY, 0}).status, FkStatus::kInvalidInput);
  FkOptions bad;
  bad.tolerance = -1;
  EXPECT_THROW(tripodForwardKinematics(m, data, q, m.home.e, bad), InvalidArgument);
  // Readings no configuration reaches (legs far longer than the geometry allows) do not converge.
  FkOptions few;
  few.max_iterations = 30;
  const FkSummary s = tripodForwardKinematics(m, data, {1e6, 0, 0}, m.home.e, few);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.status, FkStatus::kInvalidInput);
}

/// det(J_q_e) at (alpha, beta, h), from the public Jacobian.
double jacobianDeterminant(const ExechonModel& m, const Eigen::Vector3d& e) {
  ExechonData data(m);
  evaluateTripod(m, data, e, m.tripod.deltaA, m.tripod.deltaC);
  computeTripodJacobian(m, data);
  return data.J_q_e.determinant();
}

TEST(ExechonFk, SingularSeedIsReported) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  evaluateTripod(m, data, m.home.e, 1, 1);
  const ExechonLegVector q = data.readings;
  // Find h where J_q_e is singular (det changes sign along h at the home angles), by bisection.
  Eigen::Vector3d lo = m.home.e, hi = m.home.e;
  const double L = m.characteristicLength();
  bool found = false;
  for (double h = -3 * L; h < 3 * L && !found; h += 0.05 * L) {
    lo[2] = h;
    hi[2] = h + 0.05 * L;
    found = jacobianDeterminant(m, lo) * jacobianDeterminant(m, hi) < 0.0;
  }
  ASSERT_TRUE(found);
  for (int k = 0; k < 200; ++k) {
    Eigen::Vector3d mid = 0.5 * (lo + hi);
    (jacobianDeterminant(m, lo) * jacobianDeterminant(m, mid) <= 0.0 ? hi : lo) = mid;
  }
  const FkSummary s = tripodForwardKinematics(m, data, q, lo);
  EXPECT_EQ(s.status, FkStatus::kSingular);
  EXPECT_EQ(s.iterations, 0);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
