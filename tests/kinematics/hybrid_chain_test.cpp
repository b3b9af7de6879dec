#include "pkm/kinematics/hybrid_chain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "support/hybrid_samples.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

using geometry::ErrorMotion;
using test::kTolExact;

/// Halving every error must divide exact − linear by 4; allowed relative deviation of the ratio at
/// the seed's error sizes (up to 14.7 mrad, third-order terms visible) and at a tenth of them.
constexpr double kTolRatioSeedSize = 0.01;
constexpr double kTolRatioSmall = 0.002;
/// Step of the central difference d(exact Δp)/d(error scale) compared with the linear model.
constexpr double kFiniteDiffStep = 1e-3;

/// Included angle between two directions minus 90°, radians (atan2 form: accurate near 90°).
double squarenessOf(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) - std::numbers::pi / 2;
}

HybridCommand command(double x2, double y2, const Eigen::Vector3d& pkm) {
  HybridCommand c;
  c.x2 = x2;
  c.y2 = y2;
  c.pkm = pkm;
  return c;
}

Eigen::Vector3d toolAt(const HybridMachineModel& m,
                       const HybridErrorValues& v,
                       const HybridCommand& c) {
  return hybridActualPose(m, v, c).translation();
}

TEST(HybridChain, ZeroErrorsGiveTheNominalPoseExactly) {
  std::mt19937 rng(test::kSeed);
  for (const HybridMachineModel& m : {test::mxt700sLikeModel(), test::offsetModel()}) {
    for (int k = 0; k < 100; ++k) {
      const HybridCommand c = test::randomCommand(rng, m);
      const geometry::RigidTransform actual = hybridActualPose(m, HybridErrorValues{}, c);
      EXPECT_LT(hybridVolumetricError(m, HybridErrorValues{}, c).norm(), kTolExact);
      EXPECT_LT(hybridVolumetricErrorLinear(m, HybridErrorValues{}, c).norm(), kTolExact);
      EXPECT_LT((actual.matrix() - hybridNominalPose(m, c).matrix()).norm(), kTolExact);
      EXPECT_TRUE(actual.linear().isIdentity(kTolExact));
    }
  }
}

TEST(HybridChain, LocalTransformsComposeAsEquation3) {
  std::mt19937 rng(test::kSeed);
  const HybridMachineModel m = test::offsetModel();
  const HybridCommand c = test::randomCommand(rng, m);
  const HybridErrorValues v = evaluateHybridErrors(test::randomErrors(rng, m), c);
  const HybridChain ch = hybridChain(m, v, c);
  const geometry::RigidTransform composed =
      (ch.F_T_Y2 * ch.Y2_T_w).inverse() * ch.F_T_X2 * ch.X2_T_P * ch.P_T_t;
  EXPECT_LT((ch.w_T_t.matrix() - composed.matrix()).norm(), kTolExact);
  // Nominal pieces: the table at y2·ŷ, the carriage at x2·x̂ (rotated by szX2), P at X2_p_P.
  const HybridChain nominal = hybridChain(m, HybridErrorValues{}, c);
  EXPECT_LT((nominal.F_T_Y2.translation() - c.y2 * Eigen::Vector3d::UnitY()).norm(), kTolExact);
  EXPECT_LT((nominal.F_T_X2.translation() - c.x2 * Eigen::Vector3d::UnitX()).norm(), kTolExact);
  EXPECT_LT((nominal.X2_T_P.translation() - m.X2_p_P).norm(), kTolExact);
  EXPECT_LT((nominal.P_T_t.translation() - (m.P_p_tcp0 + c.pkm)).norm(), kTolExact * 1e3);
}

TEST(HybridChain, SquarenessX2AloneTiltsTheX2Travel) {
  // Moving X2 alone by x moves the tool by (x·cos szX2, −x·sin szX2, 0): Δy = −szX2·x to first
  // order.
  const HybridMachineModel m = test::mxt700sLikeModel();
  for (double s : {test::seedSquareness().sz_x2, 1e-3, -5e-3}) {
    HybridErrorValues v;
    v.squareness.sz_x2 = s;
    for (double x : {-4000.0, -875.0}) {
      const HybridCommand c = command(x, 0.0, Eigen::Vector3d::Zero());
      const Eigen::Vector3d dp = hybridVolumetricError(m, v, c);
      EXPECT_NEAR(dp.x(), x * (std::cos(s) - 1.0), kTolExact * 1e4);
      EXPECT_NEAR(dp.y(), -x * std::sin(s), kTolExact * 1e4);
      EXPECT_NEAR(dp.z(), 0.0, kTolExact);
      const Eigen::Vector3d lin = hybridVolumetricErrorLinear(m, v, c);
      EXPECT_LT((lin - Eigen::Vector3d(0.0, -s * x, 0.0)).norm(), kTolExact * 1e4);
    }
    // The included angle between the X2 travel and the Y2 travel (+ŷ) is 90° + szX2.
    const Eigen::Vector3d x2_dir = toolAt(m, v, command(-4000.0, 0.0, Eigen::Vector3d::Zero())) -
                                   toolAt(m, v, command(0.0, 0.0, Eigen::Vector3d::Zero()));
    EXPECT_NEAR(squarenessOf(-x2_dir, Eigen::Vector3d::UnitY()), s, kTolExact);
  }
}

TEST(HybridChain, PkmSquarenessIsTheIncludedAngleOfThePkmTravel) {
  // Each alone is exact; szP holds exactly together with szX2 (both rotate about z).
  const HybridMachineModel m = test::mxt700sLikeModel();
  const HybridSquareness seed = test::seedSquareness();
  auto travel = [&m](const HybridErrorValues& v, const Eigen::Vector3d& dir) -> Eigen::Vector3d {
    return toolAt(m, v, command(-2000.0, 0.0, 300.0 * dir)) -
           toolAt(m, v, command(-2000.0, 0.0, -100.0 * dir));
  };
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY(),
                        ez = Eigen::Vector3d::UnitZ();
  HybridErrorValues v;
  v.squareness.sz_x2 = seed.sz_x2;
  v.squareness.sz_p = seed.sz_p;
  const Eigen::Vector3d x2_dir = toolAt(m, v, command(-1000.0, 0.0, Eigen::Vector3d::Zero())) -
                                 toolAt(m, v, command(-3000.0, 0.0, Eigen::Vector3d::Zero()));
  EXPECT_NEAR(squarenessOf(x2_dir, travel(v, ey)), seed.sz_p, kTolExact);
  v = HybridErrorValues{};
  v.squareness.sy_p = seed.sy_p;
  EXPECT_NEAR(squarenessOf(travel(v, ex), travel(v, ez)), 0.0, kTolExact);  // P stays rigid
  EXPECT_NEAR(squarenessOf(ex, travel(v, ez)), seed.sy_p, kTolExact);
  v = HybridErrorValues{};
  v.squareness.sx_p = seed.sx_p;
  EXPECT_NEAR(squarenessOf(ey, travel(v, ez)), seed.sx_p, kTolExact);
}

TEST(HybridChain, PkmYParallelismToY2) {
  // Seed 000 §3.1: moving the PKM along y, the tool's x slope is szX2 − szP and its z slope sxP
  // (to first order; F's y is the Y2 direction).
  const HybridMachineModel m = test::mxt700sLikeModel();
  HybridErrorValues v;
  v.squareness = test::seedSquareness();
  const double L = 50.0;  // the seed measured PY over 0..50 mm
  const HybridCommand a = command(0.0, 0.0, Eigen::Vector3d::Zero());
  const HybridCommand b = command(0.0, 0.0, Eigen::Vector3d(0.0, L, 0.0));
  const Eigen::Vector3d lin =
      hybridVolumetricErrorLinear(m, v, b) - hybridVolumetricErrorLinear(m, v, a);
  EXPECT_NEAR(lin.x() / L, v.squareness.sz_x2 - v.squareness.sz_p, kTolExact);
  EXPECT_NEAR(lin.z() / L, v.squareness.sx_p, kTolExact);
  const Eigen::Vector3d exact = toolAt(m, v, b) - toolAt(m, v, a);
  const double second_order = std::pow(v.squareness.sx_p, 2);
  EXPECT_NEAR(exact.x() / L, v.squareness.sz_x2 - v.squareness.sz_p, second_order);
  EXPECT_NEAR(exact.z() / L, v.squareness.sx_p, second_order);
}

TEST(HybridChain, SingleAxisErrorsActWhereDocumented) {
  const HybridMachineModel m = test::mxt700sLikeModel();
  const Eigen::Vector3d pkm(20.0, 250.0, 150.0);
  const HybridCommand c = command(-1500.0, -200.0, pkm);
  const double eps = 2e-4, delta = 0.01;
  // X2 yaw ECX2 about the carriage origin: Abbe arm (xP, yP, zP); Δx = −ECX2·yP to first order.
  HybridErrorValues v;
  v.x2[geometry::kEz] = eps;
  EXPECT_LT((hybridVolumetricError(m, v, c) -
             (geometry::so3Exp(eps * Eigen::Vector3d::UnitZ()) * pkm - pkm))
                .norm(),
            kTolExact * 1e3);
  EXPECT_LT(
      (hybridVolumetricErrorLinear(m, v, c) - Eigen::Vector3d(-eps * pkm.y(), eps * pkm.x(), 0.0))
          .norm(),
      kTolExact);
  // Y2 positioning EYY2 moves the work: the tool moves by −EYY2 relative to it, exactly.
  v = HybridErrorValues{};
  v.y2[geometry::kDy] = delta;
  EXPECT_LT((hybridVolumetricError(m, v, c) - Eigen::Vector3d(0.0, -delta, 0.0)).norm(),
            kTolExact * 1e3);
  // Y2 yaw ECY2: the tool, at s = (x2 + xP, yP − y2, zP) in the table frame, moves by −ECY2 × s.
  v = HybridErrorValues{};
  v.y2[geometry::kEz] = eps;
  const Eigen::Vector3d s = hybridNominalToolPosition(m, c);
  EXPECT_LT(
      (hybridVolumetricError(m, v, c) - (geometry::so3Exp(-eps * Eigen::Vector3d::UnitZ()) * s - s))
          .norm(),
      kTolExact * 1e4);
  // PKM errors act at the TCP: a translation adds, a rotation only turns the tool.
  v = HybridErrorValues{};
  v.pkm << 0.3, -0.2, 0.1, 1e-3, -2e-3, 3e-3;
  EXPECT_LT((hybridVolumetricError(m, v, c) - v.pkm.head<3>()).norm(), kTolExact * 1e3);
  EXPECT_LT((hybridActualPose(m, v, c).linear() - geometry::so3Exp(v.pkm.tail<3>())).norm(),
            kTolExact);
}

TEST(HybridChain, OffsetsAreAbbeArms) {
  // With the PKM base 800 mm above the TCP, syP turns the whole PKM about its base origin.
  const HybridMachineModel m = test::offsetModel();
  HybridErrorValues v;
  v.squareness.sy_p = 1e-3;
  const HybridCommand c = command(-100.0, -50.0, Eigen::Vector3d(10.0, 20.0, 30.0));
  const Eigen::Vector3d q = m.P_p_tcp0 + c.pkm;  // TCP in P
  const Eigen::Vector3d expected = geometry::so3Exp(Eigen::Vector3d(0.0, -1e-3, 0.0)) * q - q;
  EXPECT_LT((hybridVolumetricError(m, v, c) - expected).norm(), kTolExact * 1e3);
  EXPECT_LT(
      (hybridVolumetricErrorLinear(m, v, c) - Eigen::Vector3d(-1e-3 * q.z(), 0.0, 1e-3 * q.x()))
          .norm(),
      kTolExact);
}

/// |exact − linear| at `values` scaled by `f`.
double remainder(const HybridMachineModel& m,
                 const HybridErrorValues& v,
                 const HybridCommand& c,
                 double f) {
  const HybridErrorValues s = scaled(v, f);
  return (hybridVolumetricError(m, s, c) - hybridVolumetricErrorLinear(m, s, c)).norm();
}

TEST(HybridChain, ExactAndLinearAgreeToSecondOrder) {
  std::mt19937 rng(test::kSeed);
  for (const HybridMachineModel& m : {test::mxt700sLikeModel(), test::offsetModel()}) {
    const GeometricErrors errors = test::randomErrors(rng, m);
    for (int k = 0; k < 20; ++k) {
      const HybridCommand c = test::randomCommand(rng, m);
      const HybridErrorValues v = evaluateHybridErrors(errors, c);
      EXPECT_NEAR(remainder(m, v, c, 1.0) / remainder(m, v, c, 0.5), 4.0, 4.0 * kTolRatioSeedSize);
      EXPECT_NEAR(remainder(m, v, c, 0.1) / remainder(m, v, c, 0.05), 4.0, 4.0 * kTolRatioSmall);
    }
  }
}

TEST(HybridChain, LinearModelIsTheDerivativeOfTheExactChain) {
  std::mt19937 rng(test::kSeed);
  const HybridMachineModel m = test::offsetModel();
  const GeometricErrors errors = test::randomErrors(rng, m);
  for (int k = 0; k < 20; ++k) {
    const HybridCommand c = test::randomCommand(rng, m);
    const HybridErrorValues v = evaluateHybridErrors(errors, c);
    const Eigen::Vector3d fd = (hybridVolumetricError(m, scaled(v, kFiniteDiffStep), c) -
                                hybridVolumetricError(m, scaled(v, -kFiniteDiffStep), c)) /
                               (2.0 * kFiniteDiffStep);
    const Eigen::Vector3d lin = hybridVolumetricErrorLinear(m, v, c);
    EXPECT_LT((fd - lin).norm(), test::kTolFiniteDiff * std::max(1.0, lin.norm()))
        << lin.transpose();
  }
}

TEST(HybridChain, TableOverloadsMatchValueOverloads) {
  std::mt19937 rng(test::kSeed);
  const HybridMachineModel m = test::offsetModel();
  const GeometricErrors errors = test::randomErrors(rng, m);
  const HybridCommand c = test::randomCommand(rng, m);
  const HybridErrorValues v = evaluateHybridErrors(errors, c);
  EXPECT_EQ(hybridVolumetricError(m, errors, c), hybridVolumetricError(m, v, c));
  EXPECT_EQ(hybridVolumetricErrorLinear(m, errors, c), hybridVolumetricErrorLinear(m, v, c));
  EXPECT_TRUE(hybridActualPose(m, errors, c).isApprox(hybridActualPose(m, v, c), 0.0));
}

TEST(HybridChain, RejectsNonFiniteCommands) {
  const HybridMachineModel m = test::mxt700sLikeModel();
  const HybridCommand c = command(std::nan(""), 0.0, Eigen::Vector3d::Zero());
  EXPECT_THROW((void)hybridChain(m, HybridErrorValues{}, c), InvalidArgument);
  EXPECT_THROW((void)hybridNominalPose(m, c), InvalidArgument);
  EXPECT_THROW((void)hybridVolumetricErrorLinear(m, HybridErrorValues{}, c), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
