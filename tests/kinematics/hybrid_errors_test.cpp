#include "pkm/kinematics/hybrid_errors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "support/hybrid_samples.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

using geometry::so3Exp;
using test::kTolExact;

/// Included angle between two directions minus 90°, radians (atan2 form: accurate near 90°).
double squarenessOf(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) - std::numbers::pi / 2;
}

const Eigen::Vector3d kX = Eigen::Vector3d::UnitX(), kY = Eigen::Vector3d::UnitY();

TEST(HybridSquareness, RotationVectors) {
  const HybridSquareness s = test::seedSquareness();
  EXPECT_EQ(squarenessRotationX2(s), Eigen::Vector3d(0.0, 0.0, -s.sz_x2));
  EXPECT_EQ(squarenessRotationP(s), Eigen::Vector3d(s.sx_p, -s.sy_p, s.sz_p));
}

TEST(HybridSquareness, EachValueIsTheIncludedAngleMinus90Degrees) {
  // F_R_X2: +X2 is column 0, +Y2 is F's y. Exact for any size.
  for (double v : {-0.034e-3, 0.02, -0.3}) {
    HybridSquareness s;
    s.sz_x2 = v;
    const Eigen::Matrix3d F_R_X2 = so3Exp(squarenessRotationX2(s));
    EXPECT_NEAR(squarenessOf(F_R_X2.col(0), kY), v, kTolExact);
    EXPECT_LT((F_R_X2.col(0) - Eigen::Vector3d(std::cos(v), -std::sin(v), 0.0)).norm(), kTolExact);
  }
  // X2_R_P: +PY, +PZ are columns 1, 2; the X2 frame's x, y are the unit vectors. Exact when alone.
  for (double v : {4.35e-3, -14.74e-3, 0.2}) {
    HybridSquareness sx, sy, sz;
    sx.sx_p = sy.sy_p = sz.sz_p = v;
    EXPECT_NEAR(squarenessOf(kY, so3Exp(squarenessRotationP(sx)).col(2)), v, kTolExact);
    EXPECT_NEAR(squarenessOf(kX, so3Exp(squarenessRotationP(sy)).col(2)), v, kTolExact);
    EXPECT_NEAR(squarenessOf(kX, so3Exp(squarenessRotationP(sz)).col(1)), v, kTolExact);
  }
}

TEST(HybridSquareness, TogetherTheyHoldToFirstOrder) {
  const HybridSquareness s = test::seedSquareness();
  const Eigen::Matrix3d X2_R_P = so3Exp(squarenessRotationP(s));
  const double second_order =
      std::pow(std::max({std::abs(s.sx_p), std::abs(s.sy_p), std::abs(s.sz_p)}), 2);
  EXPECT_NEAR(squarenessOf(kY, X2_R_P.col(2)), s.sx_p, second_order);
  EXPECT_NEAR(squarenessOf(kX, X2_R_P.col(2)), s.sy_p, second_order);
  EXPECT_NEAR(squarenessOf(kX, X2_R_P.col(1)), s.sz_p, second_order);
}

TEST(GeometricErrors, ValidateChecksColumnsAndFiniteness) {
  std::mt19937 rng(test::kSeed);
  GeometricErrors e = test::randomErrors(rng, test::mxt700sLikeModel());
  EXPECT_NO_THROW(e.validate());
  EXPECT_NO_THROW(GeometricErrors{}.validate());
  GeometricErrors bad = e;
  bad.x2 = geometry::ErrorTable1d({0.0, 1.0}, Eigen::MatrixXd::Zero(2, 5));
  EXPECT_THROW(bad.validate(), InvalidArgument);
  bad = e;
  bad.pkm = geometry::ErrorGrid3d(
      {std::vector<double>{0.0}, std::vector<double>{0.0}, std::vector<double>{0.0}},
      Eigen::MatrixXd::Zero(1, 3));
  EXPECT_THROW(bad.validate(), InvalidArgument);
  bad = e;
  bad.squareness.sy_p = std::nan("");
  EXPECT_THROW(bad.validate(), InvalidArgument);
}

TEST(GeometricErrors, EvaluatesAtTheCommandedPositions) {
  std::mt19937 rng(test::kSeed);
  const HybridMachineModel m = test::mxt700sLikeModel();
  const GeometricErrors e = test::randomErrors(rng, m);
  const HybridCommand c = test::randomCommand(rng, m);
  const HybridErrorValues v = evaluateHybridErrors(e, c);
  EXPECT_EQ(v.x2, e.x2->evaluateMotion(c.x2));
  EXPECT_EQ(v.y2, e.y2->evaluateMotion(c.y2));
  EXPECT_EQ(v.pkm, e.pkm->evaluateMotion(c.pkm));
  EXPECT_EQ(v.squareness.sx_p, e.squareness.sx_p);
  const HybridErrorValues none = evaluateHybridErrors(GeometricErrors{}, c);  // absent = zero
  EXPECT_TRUE(none.x2.isZero(0.0) && none.y2.isZero(0.0) && none.pkm.isZero(0.0));
}

TEST(GeometricErrors, ThrowingTablesThrowOutsideTheirRange) {
  GeometricErrors e;
  e.x2 = geometry::ErrorTable1d(
      {-875.0, 0.0}, Eigen::MatrixXd::Zero(2, 6), geometry::OutOfRange::kThrow);
  HybridCommand c;
  c.x2 = -1000.0;
  EXPECT_THROW((void)evaluateHybridErrors(e, c), InvalidArgument);
}

TEST(GeometricErrors, ScaledMultipliesEveryError) {
  std::mt19937 rng(test::kSeed);
  const HybridMachineModel m = test::mxt700sLikeModel();
  const HybridErrorValues v =
      evaluateHybridErrors(test::randomErrors(rng, m), test::randomCommand(rng, m));
  const HybridErrorValues h = scaled(v, 0.5);
  EXPECT_EQ(h.x2, 0.5 * v.x2);
  EXPECT_EQ(h.y2, 0.5 * v.y2);
  EXPECT_EQ(h.pkm, 0.5 * v.pkm);
  EXPECT_EQ(h.squareness.sz_x2, 0.5 * v.squareness.sz_x2);
  EXPECT_EQ(h.squareness.sx_p, 0.5 * v.squareness.sx_p);
  EXPECT_EQ(h.squareness.sy_p, 0.5 * v.squareness.sy_p);
  EXPECT_EQ(h.squareness.sz_p, 0.5 * v.squareness.sz_p);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
