#include "pkm/kinematics/exechon_ik.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "kinematics/exechon_sample_models.hpp"
#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

/// Zoppi's Table 2 values are printed with 4 decimals (metres); the model is in mm.
constexpr double kTolPaper4 = 5e-5;
/// The exechon-lib cross-check values are printed with 6 decimals.
constexpr double kTolPrinted6 = 5e-7;

const Eigen::Vector3d kZoppiS(20, 700, 1020);  // mm

/// Random e around `centre`: alpha, beta ± 12°, h ± 15 % of L.
Eigen::Vector3d randomE(std::mt19937& rng, const Eigen::Vector3d& centre, double length) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return centre +
         Eigen::Vector3d(degToRad(12) * u(rng), degToRad(12) * u(rng), 0.15 * length * u(rng));
}

TEST(ExechonIk, ZoppiTable1FourPoseBranches) {
  const ExechonModel m = test::zoppiTable1Model();
  struct Row {
    int d1, d2;
    double sa, ca, sb, cb, h;
  };
  const Row rows[] = {{1, 1, .9661, .2583, -.5477, .8367, 1.4035},
                      {1, -1, .9661, .2583, .5477, -.8367, -1.0035},
                      {-1, 1, -.9552, .2960, -.6234, -.7819, 1.4028},
                      {-1, -1, -.9552, .2960, .6234, .7819, -1.0028}};
  for (const Row& row : rows) {
    Eigen::Vector3d e;
    ASSERT_EQ(parametersFromWristPoint(m.tripod, kZoppiS, row.d1, row.d2, &e),
              ExechonIkStatus::kOk);
    EXPECT_NEAR(std::sin(e[0]), row.sa, kTolPaper4) << row.d1 << row.d2;
    EXPECT_NEAR(std::cos(e[0]), row.ca, kTolPaper4);
    EXPECT_NEAR(std::sin(e[1]), row.sb, kTolPaper4);
    EXPECT_NEAR(std::cos(e[1]), row.cb, kTolPaper4);
    EXPECT_NEAR(e[2] / 1000, row.h, kTolPaper4);
  }
  ExechonData data(m);
  ASSERT_EQ(tripodInverseKinematics(m, data, kZoppiS, {1, 1, 1, 1}), ExechonIkStatus::kOk);
  EXPECT_NEAR(data.lengths[0] / 1000, 1.6331, kTolPaper4);
  EXPECT_NEAR(data.lengths[1] / 1000, 1.4918, kTolPaper4);
  EXPECT_NEAR(data.lengths[2] / 1000, 0.9122, kTolPaper4);
}

TEST(ExechonIk, ForwardMapRoundTripsAllSixteenBranches) {
  const ExechonModel m = test::zoppiTable1Model();
  ExechonData data(m);
  std::mt19937 rng(test::kSeed);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d S = wristPointFromParameters(m.tripod, randomE(rng, m.home.e, 1000));
    for (int b = 0; b < 16; ++b) {
      const ExechonBranch branch = ExechonBranch::fromIndex(b);
      ASSERT_EQ(tripodInverseKinematics(m, data, S, branch), ExechonIkStatus::kOk);
      EXPECT_EQ(data.branch, branch);
      EXPECT_LT((wristPointFromParameters(m.tripod, data.e) - S).norm(), test::kTolExact * 1e3);
      // The platform pose carries S at (hx, 0, hz) and is a rotation.
      EXPECT_LT((data.zoppi_T_platform * Eigen::Vector3d(m.tripod.hx, 0, m.tripod.hz) - S).norm(),
                test::kTolExact * 1e3);
      const Eigen::Matrix3d R = data.zoppi_T_platform.linear();
      EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), test::kTolExact);
      EXPECT_NEAR(R.determinant(), 1.0, test::kTolExact);
      // evaluateTripod recovers the pose branch from e.
      ExechonData again(m);
      evaluateTripod(m, again, data.e, branch.deltaA, branch.deltaC);
      EXPECT_EQ(again.branch, branch);
      EXPECT_LT((again.lengths - data.lengths).norm(), test::kTolExact * 1e3);
    }
  }
}

TEST(ExechonIk, LegLengthsAreJointDistancesOfPlatformFixedPoints) {
  const ExechonModel m = test::zoppiTable1Model();
  ExechonData data(m);
  std::mt19937 rng(test::kSeed + 1);
  evaluateTripod(m, data, m.home.e, -1, 1);
  std::array<Eigen::Vector3d, kExechonLegs> local{};
  for (int i = 0; i < kExechonLegs; ++i)
    local[static_cast<std::size_t>(i)] =
        data.zoppi_T_platform.inverse() * data.zoppi_p_platform_joint[static_cast<std::size_t>(i)];
  EXPECT_NEAR(local[1].x(), m.tripod.pB, test::kTolRoundTrip);  // P5B at i = pB
  EXPECT_NEAR(local[0].y(), m.tripod.pA, test::kTolRoundTrip);  // P4A at j = pA
  EXPECT_NEAR(local[2].y(), m.tripod.pC, test::kTolRoundTrip);
  for (int k = 0; k < 100; ++k) {
    evaluateTripod(m, data, randomE(rng, m.home.e, 1000), -1, 1);
    for (int i = 0; i < kExechonLegs; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      EXPECT_LT(
          (data.zoppi_T_platform.inverse() * data.zoppi_p_platform_joint[ui] - local[ui]).norm(),
          test::kTolRoundTrip);
      EXPECT_NEAR((data.zoppi_p_platform_joint[ui] - data.zoppi_p_leg_start[ui]).norm(),
                  data.lengths[i],
                  test::kTolRoundTrip);
    }
    // Legs A and C move in the plane normal to i through the base axis; leg B is normal to j (kB5).
    const Eigen::Vector3d i_axis = data.zoppi_T_platform.linear().col(0),
                          j_axis = data.zoppi_T_platform.linear().col(1);
    EXPECT_NEAR((data.zoppi_p_platform_joint[1] - data.zoppi_p_leg_start[1]).dot(j_axis),
                0.0,
                test::kTolRoundTrip);
    EXPECT_NEAR((data.zoppi_p_platform_joint[0] - data.zoppi_p_leg_start[0]).dot(i_axis),
                0.0,
                test::kTolRoundTrip);
  }
}

TEST(ExechonIk, BiJinToyCrossCheck) {
  const test::BiJin bj = test::biJinInverse({10, -20, 250});
  EXPECT_NEAR(radToDeg(bj.alpha), 4.573921, kTolPrinted6);
  EXPECT_NEAR(radToDeg(bj.beta), 2.213030, kTolPrinted6);
  EXPECT_LT((bj.q - Eigen::Vector3d(255.084711, 261.278398, 248.491998)).cwiseAbs().maxCoeff(),
            kTolPrinted6);
  EXPECT_LT((bj.S - Eigen::Vector3d(14.826881, -29.960718, 374.508977)).cwiseAbs().maxCoeff(),
            kTolPrinted6);

  // Zoppi with (ib, jb, kb) = (y, x, −z) gives the same legs, and alpha = alpha_BJ − 90°, beta =
  // −beta_BJ.
  const ExechonModel m = test::biJinToyModel();
  ExechonData data(m);
  ASSERT_EQ(tripodInverseKinematics(m, data, m.world_T_zoppi.inverse() * bj.S),
            ExechonIkStatus::kOk);
  EXPECT_LT((data.lengths - bj.q).cwiseAbs().maxCoeff(), test::kTolRoundTrip);
  EXPECT_NEAR(data.e[0], bj.alpha - std::numbers::pi / 2, test::kTolRoundTrip);
  EXPECT_NEAR(data.e[1], -bj.beta, test::kTolRoundTrip);
  EXPECT_LT((data.world_p_S - bj.S).norm(), test::kTolRoundTrip);

  // Random platform centres: the two forms agree everywhere near the toy's working region.
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const test::BiJin r = test::biJinInverse({40 * u(rng), 40 * u(rng), 250 + 40 * u(rng)});
    ASSERT_EQ(tripodInverseKinematicsNearest(m, data, m.world_T_zoppi.inverse() * r.S, m.home.e),
              ExechonIkStatus::kOk);
    EXPECT_LT((data.lengths - r.q).cwiseAbs().maxCoeff(), test::kTolRoundTrip);
  }
}

TEST(ExechonIk, NearestPicksTheContinuousPoseBranch) {
  const ExechonModel m = test::zoppiTable1Model();
  ExechonData data(m);
  for (int b = 0; b < 4; ++b) {
    const ExechonBranch branch = ExechonBranch::fromIndex(b);
    ASSERT_EQ(tripodInverseKinematics(m, data, kZoppiS, branch), ExechonIkStatus::kOk);
    const Eigen::Vector3d e = data.e;
    const Eigen::Vector3d S = kZoppiS + Eigen::Vector3d(5, -3, 4);
    ASSERT_EQ(tripodInverseKinematicsNearest(m, data, S, e), ExechonIkStatus::kOk);
    EXPECT_EQ(data.branch.delta1B, branch.delta1B);
    EXPECT_EQ(data.branch.delta2B, branch.delta2B);
  }
}

TEST(ExechonIk, JacobianMatchesCentralDifferences) {
  for (const ExechonModel& m : {test::zoppiTable1Model(), test::biJinToyModel()}) {
    ExechonData data(m), probe(m);
    std::mt19937 rng(test::kSeed + 2);
    for (int k = 0; k < 50; ++k) {
      const ExechonBranch branch = ExechonBranch::fromIndex(k % 16);
      const Eigen::Vector3d S =
          wristPointFromParameters(m.tripod, randomE(rng, m.home.e, m.characteristicLength()));
      ASSERT_EQ(tripodInverseKinematics(m, data, S, branch), ExechonIkStatus::kOk);
      computeTripodJacobian(m, data);
      const double step = 1e-4 * m.characteristicLength();
      Eigen::Matrix3d numeric, numeric_e;
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d dS = step * Eigen::Vector3d::Unit(j);
        ASSERT_EQ(tripodInverseKinematics(m, probe, S + dS, branch), ExechonIkStatus::kOk);
        const Eigen::Vector3d plus = probe.lengths;
        ASSERT_EQ(tripodInverseKinematics(m, probe, S - dS, branch), ExechonIkStatus::kOk);
        numeric.col(j) = (plus - probe.lengths) / (2 * step);
        const double h = j < 2 ? 1e-6 : step;
        const Eigen::Vector3d de = h * Eigen::Vector3d::Unit(j);
        numeric_e.col(j) = (wristPointFromParameters(m.tripod, data.e + de) -
                            wristPointFromParameters(m.tripod, data.e - de)) /
                           (2 * h);
      }
      EXPECT_LT((numeric - data.J_q_S).norm(), test::kTolFiniteDiff * (1 + data.J_q_S.norm())) << k;
      EXPECT_LT((numeric_e - data.J_S_e).norm(), test::kTolFiniteDiff * (1 + data.J_S_e.norm()))
          << k;
      const double cond = tripodConditionNumber(data);
      EXPECT_TRUE(std::isfinite(cond));
      EXPECT_GE(cond, 1.0);
    }
  }
}

/// The four pose branches' solutions at S and the index of the one tripodInverseKinematicsNearest
/// must pick for e_near: its documented distance, evaluated branch by branch.
int nearestByBruteForce(const ExechonModel& m,
                        const Eigen::Vector3d& S,
                        const Eigen::Vector3d& e_near) {
  ExechonData probe(m);
  int best = -1;
  double best_distance = INFINITY;
  for (int b = 0; b < 4; ++b) {
    if (tripodInverseKinematics(m, probe, S, ExechonBranch::fromIndex(b)) != ExechonIkStatus::kOk)
      return -1;
    const double dh = (probe.e[2] - e_near[2]) / m.characteristicLength();
    const double distance = 2.0 * (1.0 - std::cos(probe.e[0] - e_near[0])) +
                            2.0 * (1.0 - std::cos(probe.e[1] - e_near[1])) + dh * dh;
    if (distance < best_distance) {
      best_distance = distance;
      best = b;
    }
  }
  return best;
}

TEST(ExechonIk, NearestAgreesWithEveryBranchSolved) {
  // tripodInverseKinematicsNearest skips the δ1B pair whose alpha alone is farther than the best
  // solution found: it must still choose as if all four were solved, for near and far e_near.
  const ExechonModel m = test::zoppiTable1Model();
  ExechonData data(m);
  std::mt19937 rng(test::kSeed + 7);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  int checked = 0;
  for (int k = 0; k < 400; ++k) {
    const Eigen::Vector3d S =
        wristPointFromParameters(m.tripod, randomE(rng, m.home.e, m.characteristicLength()));
    const Eigen::Vector3d e_near =
        k % 2 == 0
            ? randomE(rng, m.home.e, m.characteristicLength())
            : Eigen::Vector3d(angle(rng), angle(rng), m.home.e[2] * (0.5 + std::abs(angle(rng))));
    const int expected = nearestByBruteForce(m, S, e_near);
    ASSERT_GE(expected, 0) << k;
    ASSERT_EQ(tripodInverseKinematicsNearest(m, data, S, e_near), ExechonIkStatus::kOk) << k;
    EXPECT_EQ(data.branch.index() & 3, expected) << k;
    ++checked;
  }
  EXPECT_EQ(checked, 400);
}

TEST(ExechonIk, ConditionNumberIsUnitFree) {
  ExechonModel m = test::zoppiTable1Model();
  ExechonData data(m);
  evaluateTripod(m, data, m.home.e, 1, 1);
  computeTripodJacobian(m, data);
  const double cond_mm = tripodConditionNumber(data);
  auto& g = m.tripod;
  for (double* v :
       {&g.dA, &g.dB, &g.dC, &g.l12A, &g.l12C, &g.pA, &g.pB, &g.pC, &g.hA, &g.hC, &g.hx, &g.hz})
    *v /= 25.4;
  m.home.e[2] /= 25.4;
  ExechonData inch(m);
  evaluateTripod(m, inch, m.home.e, 1, 1);
  computeTripodJacobian(m, inch);
  EXPECT_NEAR(tripodConditionNumber(inch), cond_mm, test::kTolRoundTrip * cond_mm);
}

TEST(ExechonIk, ExpectedFailuresAreStatuses) {
  ExechonModel m = test::zoppiTable1Model();
  ExechonData data(m);
  ASSERT_EQ(tripodInverseKinematics(m, data, kZoppiS), ExechonIkStatus::kOk);
  const Eigen::Vector3d e_before = data.e;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(tripodInverseKinematics(m, data, {nan, 0, 1}), ExechonIkStatus::kInvalidInput);
  EXPECT_EQ(tripodInverseKinematics(m, data, {INFINITY, 0, 1}), ExechonIkStatus::kInvalidInput);
  EXPECT_EQ(tripodInverseKinematics(m, data, {100, 50, 0}),
            ExechonIkStatus::kUnreachable);  // |(Sx,Sz)| < hx
  EXPECT_EQ(tripodInverseKinematics(m, data, {0, 50, 0}),
            ExechonIkStatus::kUnreachable);  // on the jb axis
  EXPECT_EQ(tripodInverseKinematics(m, data, {m.tripod.hx, 50, 0}),
            ExechonIkStatus::kSingular);  // r = 0
  EXPECT_EQ(tripodInverseKinematicsNearest(m, data, kZoppiS, {nan, 0, 0}),
            ExechonIkStatus::kInvalidInput);
  EXPECT_EQ(data.e, e_before);  // untouched on failure
  m.tripod.hx = 0;
  EXPECT_EQ(tripodInverseKinematics(m, data, {0, 50, 0}),
            ExechonIkStatus::kSingular);  // on the jb axis, hx = 0
  // t6 = 0 and Sy = 0: S such that t0² = dB·Sx with hx = 0.
  EXPECT_EQ(tripodInverseKinematics(m, data, {m.tripod.dB, 0, 0}), ExechonIkStatus::kSingular);
  EXPECT_THROW(tripodInverseKinematics(m, data, kZoppiS, {2, 1, 1, 1}), InvalidArgument);
  EXPECT_THROW(static_cast<void>(ExechonBranch::fromIndex(16)), InvalidArgument);
  for (auto s : {ExechonIkStatus::kOk,
                 ExechonIkStatus::kUnreachable,
                 ExechonIkStatus::kSingular,
                 ExechonIkStatus::kInvalidInput})
    EXPECT_NE(toString(s), "unknown");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
