// Tests of leg B's base-joint offsets (src/kinematics/exechon_leg_b.cpp, declared in
// exechon_tripod_math.hpp) through the public tripod IK, FK and Jacobians. The closure is checked
// against the joint geometry itself (docs/conventions.md, "Leg B's base-joint offsets"), not the
// solver's equations.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "kinematics/exechon_sample_models.hpp"
#include "kinematics/exechon_tripod_math.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_fk.hpp"
#include "pkm/kinematics/exechon_ik.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

/// Zoppi's Table 1 machine with leg B's joint offsets of a few mm (the paper's offsets are
/// manufacturing errors, small against the ~1 m legs).
ExechonModel offsetModel(double l12B = 3.0, double l23B = -2.0) {
  ExechonModel m = test::zoppiTable1Model();
  m.tripod.l12B = l12B;
  m.tripod.l23B = l23B;
  return m;
}

Eigen::Vector3d randomE(std::mt19937& rng, const ExechonModel& m) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return m.home.e + Eigen::Vector3d(degToRad(12) * u(rng),
                                    degToRad(12) * u(rng),
                                    0.15 * m.characteristicLength() * u(rng));
}

/// The joint geometry of leg B, rebuilt from the solved points: the leg axis is ⟂ kB5 and ⟂ R2,
/// R2 ⟂ R1 = jb, R2 meets the common normal with R1 at Q = P1B − l12B·(jb × a2), and the leg axis
/// lies l23B from R2 (towards jb × … as documented) with its foot at the common normal.
void expectLegBClosed(const ExechonModel& m, const ExechonData& data) {
  const Eigen::Vector3d jb = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d P1B(m.tripod.dB, 0, 0);
  const Eigen::Vector3d& F = data.zoppi_p_leg_start[1];
  const Eigen::Vector3d& P5B = data.zoppi_p_platform_joint[1];
  const Eigen::Vector3d kB5 = data.zoppi_T_platform.linear().col(1);
  const Eigen::Vector3d w = (P5B - F).normalized();
  EXPECT_NEAR((P5B - F).norm(), data.lengths[1], test::kTolRoundTrip);
  EXPECT_NEAR(w.dot(kB5), 0.0, test::kTolRoundTrip);    // the platform revolute is ⟂ the leg
  const Eigen::Vector3d a2 = jb.cross(w).normalized();  // R2: ⟂ R1 and ⟂ the leg
  const Eigen::Vector3d Q = P1B - m.tripod.l12B * jb.cross(a2);
  EXPECT_NEAR((F - Q).dot(a2), 0.0, test::kTolRoundTrip);  // F on the common normal of R2, leg
  EXPECT_NEAR((F - Q).dot(w), 0.0, test::kTolRoundTrip);
  EXPECT_NEAR((F - Q).dot(w.cross(a2)), m.tripod.l23B, test::kTolRoundTrip);
  // P5B is pB along the platform's i from P, which lies in the legs-A/C plane.
  const Eigen::Vector3d P = data.zoppi_T_platform.translation();
  EXPECT_NEAR(
      (P5B - P).dot(data.zoppi_T_platform.linear().col(0)), m.tripod.pB, test::kTolRoundTrip);
  EXPECT_NEAR((P5B - P).norm(), std::abs(m.tripod.pB), test::kTolRoundTrip);
}

TEST(ExechonLegB, ClosesTheJointGeometry) {
  for (const auto& [l12, l23] :
       {std::pair{3.0, -2.0}, std::pair{-5.0, 4.0}, std::pair{0.0, 6.0}, std::pair{7.0, 0.0}}) {
    const ExechonModel m = offsetModel(l12, l23);
    ExechonData data(m);
    std::mt19937 rng(test::kSeed);
    for (int k = 0; k < 20; ++k) {
      evaluateTripod(m, data, randomE(rng, m), 1, 1);
      ASSERT_TRUE(data.lengths.allFinite());
      expectLegBClosed(m, data);
      EXPECT_LT((wristPointFromParameters(m.tripod, data.e) - data.zoppi_p_S).norm(),
                test::kTolExact * 1e3);
    }
  }
}

TEST(ExechonLegB, TinyOffsetsApproachZoppisClosedForm) {
  const ExechonModel ideal = test::zoppiTable1Model();
  const ExechonModel tiny = offsetModel(1e-10, -1e-10);
  ExechonData a(ideal), b(tiny);
  std::mt19937 rng(test::kSeed + 1);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d e = randomE(rng, ideal);
    evaluateTripod(ideal, a, e, 1, 1);
    evaluateTripod(tiny, b, e, 1, 1);
    EXPECT_LT((a.lengths - b.lengths).norm(), 1e-8);
    EXPECT_LT((a.zoppi_p_S - b.zoppi_p_S).norm(), 1e-8);
    EXPECT_LT((a.zoppi_p_platform_joint[1] - b.zoppi_p_platform_joint[1]).norm(), 1e-8);
    EXPECT_LT((a.zoppi_p_leg_start[1] - b.zoppi_p_leg_start[1]).norm(), 1e-8);
  }
}

TEST(ExechonLegB, OffsetsMoveThePlatformAtFirstOrder) {
  // At the same leg readings, 3 mm and -2 mm of joint offsets move S by millimetres: the closed
  // form of the ideal joint would be wrong by that much (Lopez-Custodio et al. 2020's point).
  const ExechonModel ideal = test::zoppiTable1Model();
  const ExechonModel off = offsetModel();
  ExechonData a(ideal), b(off);
  evaluateTripod(ideal, a, ideal.home.e, 1, 1);
  const FkSummary s = tripodForwardKinematics(off, b, a.readings, ideal.home.e);
  ASSERT_EQ(s.status, FkStatus::kOk);
  const double moved = (a.zoppi_p_S - b.zoppi_p_S).norm();
  EXPECT_GT(moved, 0.5);
  EXPECT_LT(moved, 20.0);
}

TEST(ExechonLegB, IkFkRoundTripEveryPoseBranch) {
  const ExechonModel m = offsetModel();
  ExechonData ik(m), fk(m);
  std::mt19937 rng(test::kSeed + 2);
  for (int k = 0; k < 40; ++k) {
    ExechonBranch branch = branchOf(m.tripod);
    branch.delta1B = k % 2 == 0 ? 1 : -1;
    branch.delta2B = (k / 2) % 2 == 0 ? 1 : -1;
    ExechonData truth(m);
    evaluateTripod(m, truth, randomE(rng, m), 1, 1);
    const Eigen::Vector3d S = truth.zoppi_p_S;
    // The same S in another pose branch: solve it and check it reproduces S and closes leg B.
    const ExechonIkStatus status = tripodInverseKinematics(m, ik, S, branch);
    ASSERT_EQ(status, ExechonIkStatus::kOk) << k;
    EXPECT_LT((wristPointFromParameters(m.tripod, ik.e) - S).norm(), test::kTolRoundTrip) << k;
    expectLegBClosed(m, ik);
    if (branch == branchOf(m.tripod)) {
      EXPECT_LT((ik.lengths - truth.lengths).norm(), test::kTolRoundTrip) << k;
    }
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Eigen::Vector3d seed = ik.e + Eigen::Vector3d(0.02 * u(rng), 0.02 * u(rng), 10 * u(rng));
    const FkSummary s = tripodForwardKinematics(m, fk, ik.readings, seed);
    ASSERT_EQ(s.status, FkStatus::kOk) << k;
    EXPECT_LT((fk.zoppi_p_S - S).norm(), test::kTolRoundTrip) << k;
  }
}

TEST(ExechonLegB, NearestBranchFollowsAPath) {
  const ExechonModel m = offsetModel();
  ExechonData data(m);
  Eigen::Vector3d e = m.home.e;
  for (int k = 0; k <= 50; ++k) {
    const Eigen::Vector3d target =
        m.home.e + Eigen::Vector3d(degToRad(0.2) * k, degToRad(-0.1) * k, 0.5 * k);
    ExechonData truth(m);
    evaluateTripod(m, truth, target, 1, 1);
    ASSERT_EQ(tripodInverseKinematicsNearest(m, data, truth.zoppi_p_S, e), ExechonIkStatus::kOk);
    EXPECT_LT((data.e - target).norm(), test::kTolRoundTrip) << k;
    e = data.e;
  }
}

TEST(ExechonLegB, JacobiansMatchCentralDifferences) {
  const ExechonModel m = offsetModel(4.0, -3.0);
  ExechonData data(m), probe(m);
  std::mt19937 rng(test::kSeed + 3);
  for (int k = 0; k < 20; ++k) {
    evaluateTripod(m, data, randomE(rng, m), 1, 1);
    const Eigen::Vector3d S = data.zoppi_p_S;
    computeTripodJacobian(m, data);
    const double step = 1e-4 * m.characteristicLength();
    Eigen::Matrix3d J_q_S, J_S_e, J_q_e;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d dS = step * Eigen::Vector3d::Unit(j);
      ASSERT_EQ(tripodInverseKinematics(m, probe, S + dS, data.branch), ExechonIkStatus::kOk);
      const Eigen::Vector3d plus = probe.lengths;
      ASSERT_EQ(tripodInverseKinematics(m, probe, S - dS, data.branch), ExechonIkStatus::kOk);
      J_q_S.col(j) = (plus - probe.lengths) / (2 * step);
      const double h = j < 2 ? 1e-6 : step;
      const Eigen::Vector3d de = h * Eigen::Vector3d::Unit(j);
      J_S_e.col(j) = (wristPointFromParameters(m.tripod, data.e + de) -
                      wristPointFromParameters(m.tripod, data.e - de)) /
                     (2 * h);
      evaluateTripod(m, probe, data.e + de, 1, 1);
      const Eigen::Vector3d q_plus = probe.lengths;
      evaluateTripod(m, probe, data.e - de, 1, 1);
      J_q_e.col(j) = (q_plus - probe.lengths) / (2 * h);
    }
    EXPECT_LT((J_q_S - data.J_q_S).norm(), test::kTolFiniteDiff * (1 + data.J_q_S.norm())) << k;
    EXPECT_LT((J_S_e - data.J_S_e).norm(), test::kTolFiniteDiff * (1 + data.J_S_e.norm())) << k;
    EXPECT_LT((J_q_e - data.J_q_e).norm(), test::kTolFiniteDiff * (1 + data.J_q_e.norm())) << k;
  }
}

TEST(ExechonLegB, PlatformPointJacobianMatchesCentralDifferences) {
  // detail::platformPointAt (the tool-point IK's Newton map): S(e) + R(e)·v and its e-derivative,
  // with and without leg B's offsets.
  std::mt19937 rng(test::kSeed + 4);
  for (const ExechonModel& m : {test::zoppiTable1Model(), offsetModel(4.0, -3.0)}) {
    ExechonData data(m);
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector3d e = randomE(rng, m);
      const Eigen::Vector3d v(120.0 + k, -40.0, 250.0 - 3 * k);
      Eigen::Vector3d point, plus, minus;
      Eigen::Matrix3d J, unused;
      ASSERT_TRUE(detail::platformPointAt(m.tripod, detail::trigOf(e), v, &point, &J));
      evaluateTripod(m, data, e, 1, 1);
      EXPECT_LT((point - (data.zoppi_p_S + data.zoppi_T_platform.linear() * v)).norm(),
                test::kTolRoundTrip)
          << k;
      Eigen::Matrix3d numeric;
      for (int j = 0; j < 3; ++j) {
        const double h = j < 2 ? 1e-6 : 1e-4 * m.characteristicLength();
        const Eigen::Vector3d de = h * Eigen::Vector3d::Unit(j);
        ASSERT_TRUE(detail::platformPointAt(m.tripod, detail::trigOf(e + de), v, &plus, nullptr));
        ASSERT_TRUE(detail::platformPointAt(m.tripod, detail::trigOf(e - de), v, &minus, &unused));
        numeric.col(j) = (plus - minus) / (2 * h);
      }
      EXPECT_LT((numeric - J).norm(), test::kTolFiniteDiff * (1 + J.norm())) << k;
    }
  }
}

TEST(ExechonLegB, LargeOffsetsStillCloseAndRoundTrip) {
  // Offsets of 5 % of the machine (40 mm) are far beyond manufacturing errors: the Newton solves
  // from Zoppi's ideal solution still converge.
  const ExechonModel m = offsetModel(40.0, -30.0);
  ExechonData data(m), ik(m), fk(m);
  std::mt19937 rng(test::kSeed + 4);
  for (int k = 0; k < 20; ++k) {
    evaluateTripod(m, data, randomE(rng, m), 1, 1);
    ASSERT_TRUE(data.lengths.allFinite()) << k;
    expectLegBClosed(m, data);
    ASSERT_EQ(tripodInverseKinematics(m, ik, data.zoppi_p_S, data.branch), ExechonIkStatus::kOk);
    EXPECT_LT((ik.lengths - data.lengths).norm(), test::kTolRoundTrip) << k;
    ASSERT_EQ(tripodForwardKinematics(m, fk, data.readings, m.home.e).status, FkStatus::kOk) << k;
    EXPECT_LT((fk.zoppi_p_S - data.zoppi_p_S).norm(), test::kTolRoundTrip) << k;
  }
}

TEST(ExechonLegB, ModelRejectsNonFiniteOffsets) {
  ExechonModel m = offsetModel();
  EXPECT_NO_THROW(m.validate());
  m.tripod.l23B = std::nan("");
  EXPECT_THROW(m.validate(), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
