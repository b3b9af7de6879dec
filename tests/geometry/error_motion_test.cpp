#include "pkm/geometry/error_motion.hpp"

#include <gtest/gtest.h>

#include <random>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "support/tolerances.hpp"

namespace pkm::geometry {
namespace PKM_TEST_NS {

using test::kTolExact;

/// Halving the error must divide a second-order remainder by 4; allowed relative deviation of the
/// ratio.
constexpr double kTolSecondOrderRatio = 0.02;

ErrorMotion randomMotion(std::mt19937& rng, double length, double angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ErrorMotion e;
  e << length * u(rng), length * u(rng), length * u(rng), angle * u(rng), angle * u(rng),
      angle * u(rng);
  return e;
}

TEST(ErrorMotion, ComponentsFollowIsoOrder) {
  ErrorMotion e;
  e << 1, 2, 3, 4, 5, 6;
  EXPECT_EQ(e[kDx], 1);
  EXPECT_EQ(e[kEz], 6);
  EXPECT_EQ(errorTranslation(e), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(errorRotation(e), Eigen::Vector3d(4, 5, 6));
}

TEST(ErrorMotion, ExactHtmIsExpRotationThenTranslation) {
  std::mt19937 rng(test::kSeed);
  for (int k = 0; k < 50; ++k) {
    const ErrorMotion e = randomMotion(rng, 0.1, 0.5);
    const geometry::RigidTransform E = errorMotionHtm(e);
    EXPECT_LT((E.linear() - so3Exp(errorRotation(e))).norm(), kTolExact);
    EXPECT_LT((E.translation() - errorTranslation(e)).norm(), kTolExact);
    EXPECT_LT((E.linear() * E.linear().transpose() - Eigen::Matrix3d::Identity()).norm(),
              kTolExact);
    // A point p of the perturbed frame goes to R·p + δ.
    const Eigen::Vector3d p(100.0, -50.0, 20.0);
    EXPECT_LT((E * p - (so3Exp(errorRotation(e)) * p + errorTranslation(e))).norm(),
              kTolExact * 100.0);
  }
  EXPECT_TRUE(errorMotionHtm(ErrorMotion::Zero()).matrix().isIdentity(0.0));
}

TEST(ErrorMotion, SingleAngleIsPlainAxisRotation) {
  const double a = 0.01;
  ErrorMotion e = ErrorMotion::Zero();
  e[kEz] = a;
  Eigen::Matrix3d Rz;
  Rz << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  EXPECT_LT((errorMotionHtm(e).linear() - Rz).norm(), kTolExact);
}

TEST(ErrorMotion, FirstOrderFormIsLinearisation) {
  std::mt19937 rng(test::kSeed);
  const ErrorMotion e = randomMotion(rng, 0.05, 1e-3);
  Eigen::Matrix4d expected = Eigen::Matrix4d::Identity();
  expected.topLeftCorner<3, 3>() += hat(errorRotation(e));
  expected.topRightCorner<3, 1>() = errorTranslation(e);
  EXPECT_LT((errorMotionHtmFirstOrder(e) - expected).norm(), kTolExact);
  const Eigen::Vector3d p(300.0, 200.0, -100.0);
  const Eigen::Vector4d ph(p.x(), p.y(), p.z(), 1.0);
  EXPECT_LT(
      ((errorMotionHtmFirstOrder(e) * ph).head<3>() - p - firstOrderDisplacement(e, p)).norm(),
      kTolExact * 1e3);
}

TEST(ErrorMotion, ExactAndFirstOrderAgreeToSecondOrder) {
  std::mt19937 rng(test::kSeed);
  const Eigen::Vector3d p(400.0, -250.0, 150.0);
  for (int k = 0; k < 20; ++k) {
    const ErrorMotion e = randomMotion(rng, 0.05, 1e-3);
    auto remainder = [&p](const ErrorMotion& m) {
      return ((errorMotionHtm(m) * p - p) - firstOrderDisplacement(m, p)).norm();
    };
    const double ratio = remainder(e) / remainder(0.5 * e);
    EXPECT_NEAR(ratio, 4.0, 4.0 * kTolSecondOrderRatio);
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::geometry
