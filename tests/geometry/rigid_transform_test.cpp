#include "pkm/geometry/rigid_transform.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "pkm/geometry/so3.hpp"
#include "support/tolerances.hpp"

namespace pkm::geometry {
namespace PKM_TEST_NS {

using test::kTolExact;
using test::kTolFiniteDiff;

/// A random twist: translation components in [−length, length], rotation vector components in
/// [−angle, angle].
Twist randomTwist(std::mt19937& rng, double length, double angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Twist xi;
  xi << length * u(rng), length * u(rng), length * u(rng), angle * u(rng), angle * u(rng),
      angle * u(rng);
  return xi;
}

/// The 4×4 matrix ξ^ = [[w]×, v; 0, 0] of a twist.
Eigen::Matrix4d wedge(const Twist& xi) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m.topLeftCorner<3, 3>() = hat(xi.tail<3>());
  m.topRightCorner<3, 1>() = xi.head<3>();
  return m;
}

double maxAbs(const Eigen::Matrix4d& m) { return m.cwiseAbs().maxCoeff(); }

TEST(RigidTransform, Constructors) {
  const Eigen::Vector3d p(1.0, -2.0, 3.0), w(0.1, 0.2, -0.3);
  EXPECT_EQ(translationTransform(p).translation(), p);
  EXPECT_TRUE(translationTransform(p).linear().isIdentity(0.0));
  EXPECT_LT((rotationTransform(w).linear() - so3Exp(w)).norm(), kTolExact);
  EXPECT_TRUE(rotationTransform(w).translation().isZero(0.0));
  const RigidTransform T = makeTransform(so3Exp(w), p);
  EXPECT_EQ(T.linear(), so3Exp(w));
  EXPECT_EQ(T.translation(), p);
  EXPECT_EQ(T.matrix().row(3), Eigen::RowVector4d(0, 0, 0, 1));
  EXPECT_LT(maxAbs(T.matrix() - (translationTransform(p) * rotationTransform(w)).matrix()),
            kTolExact);
  // T·x = R·x + p (up to rounding: Eigen adds in another order).
  const Eigen::Vector3d x(400.0, -250.0, 150.0);
  EXPECT_LT((T * x - (so3Exp(w) * x + p)).norm(), kTolExact * 1e3);
  EXPECT_EQ(Eigen::Vector3d(T.linear() * x + T.translation()), Eigen::Vector3d(so3Exp(w) * x + p));
}

TEST(RigidTransform, ComposeAndInverseFollowTheFrameNames) {
  std::mt19937 rng(test::kSeed);
  for (int k = 0; k < 20; ++k) {
    const RigidTransform a_T_b = se3Exp(randomTwist(rng, 500.0, 3.0));
    const RigidTransform b_T_c = se3Exp(randomTwist(rng, 500.0, 3.0));
    const Eigen::Vector3d x_c(120.0, -40.0, 75.0);
    const RigidTransform a_T_c = a_T_b * b_T_c;
    EXPECT_LT((a_T_c * x_c - a_T_b * (b_T_c * x_c)).norm(), 1e-9);
    const RigidTransform b_T_a = a_T_b.inverse(Eigen::Isometry);
    EXPECT_LT(maxAbs((a_T_b * b_T_a).matrix() - Eigen::Matrix4d::Identity()), 1e-12 * 500.0);
    EXPECT_LT(maxAbs((b_T_a * a_T_b).matrix() - Eigen::Matrix4d::Identity()), 1e-12 * 500.0);
    EXPECT_LT(maxAbs(b_T_a.matrix() - a_T_b.matrix().inverse()), 1e-12 * 500.0);
  }
}

TEST(RigidTransform, ExpOfRotationOnlyAndTranslationOnly) {
  Twist xi = Twist::Zero();
  xi.head<3>() = Eigen::Vector3d(10.0, -20.0, 30.0);
  EXPECT_LT(maxAbs(se3Exp(xi).matrix() - translationTransform(xi.head<3>()).matrix()), kTolExact);
  xi.head<3>().setZero();
  xi.tail<3>() = Eigen::Vector3d(0.3, -0.2, 1.1);
  EXPECT_LT(maxAbs(se3Exp(xi).matrix() - rotationTransform(xi.tail<3>()).matrix()), kTolExact);
  EXPECT_TRUE(se3Exp(Twist::Zero()).matrix().isIdentity(0.0));
}

TEST(RigidTransform, ExpIsAOneParameterSubgroup) {
  // exp(s·ξ)·exp(t·ξ) = exp((s + t)·ξ) and exp(−ξ) = exp(ξ)⁻¹.
  std::mt19937 rng(test::kSeed);
  for (int k = 0; k < 20; ++k) {
    const Twist xi = randomTwist(rng, 100.0, 1.0);
    EXPECT_LT(maxAbs((se3Exp(0.3 * xi) * se3Exp(0.7 * xi)).matrix() - se3Exp(xi).matrix()),
              1e-12 * 100.0);
    EXPECT_LT(maxAbs(se3Exp(-xi).matrix() - se3Exp(xi).inverse(Eigen::Isometry).matrix()),
              1e-12 * 100.0);
  }
}

TEST(RigidTransform, LogOfExpRecoversTheTwist) {
  std::mt19937 rng(test::kSeed);
  // Where log is the inverse of exp: |w| < pi (kept below 3 rad here).
  for (int k = 0; k < 200; ++k) {
    Twist xi = randomTwist(rng, 500.0, 1.8);
    if (xi.tail<3>().norm() >= 3.0) continue;
    EXPECT_LT((se3Log(se3Exp(xi)) - xi).norm(), 1e-9) << xi.transpose();
  }
}

TEST(RigidTransform, ExpOfLogRecoversTheTransform) {
  std::mt19937 rng(test::kSeed);
  for (int k = 0; k < 200; ++k) {
    const Twist r = randomTwist(rng, 1000.0, 3.0);  // any rotation vector, even beyond pi
    const RigidTransform T = makeTransform(so3Exp(r.tail<3>()), r.head<3>());
    EXPECT_LT(maxAbs(se3Exp(se3Log(T)).matrix() - T.matrix()), 1e-9);
    EXPECT_LE(se3Log(T).tail<3>().norm(), std::numbers::pi + kTolExact);
  }
}

TEST(RigidTransform, LogNearAHalfTurn) {
  // θ → pi: the coefficient (1 − (θ/2)·cot(θ/2))/θ² stays finite (cot(pi/2) = 0).
  for (const double theta : {std::numbers::pi - 1e-6, std::numbers::pi}) {
    Twist xi;
    xi << 5.0, -3.0, 2.0, 0.0, 0.0, theta;
    const Twist back = se3Log(se3Exp(xi));
    EXPECT_TRUE(back.allFinite());
    EXPECT_LT(maxAbs(se3Exp(back).matrix() - se3Exp(xi).matrix()), 1e-9);
  }
}

TEST(RigidTransform, SmallAnglesAreSmoothAndFirstOrderExact) {
  // Below and around the series switch (1e-3 rad) and at the identity, log∘exp is the identity
  // and exp(ξ) = I + ξ^ + O(|ξ|²).
  for (const double angle : {0.0, 1e-12, 1e-8, 9.99e-4, 1.001e-3, 1e-2}) {
    Twist xi;
    xi << 0.4, -0.7, 0.2, angle * 0.6, -angle * 0.8, 0.0;
    EXPECT_LT((se3Log(se3Exp(xi)) - xi).norm(), 1e-15 + 1e-12 * xi.norm()) << angle;
    const double second = maxAbs(se3Exp(xi).matrix() - Eigen::Matrix4d::Identity() - wedge(xi));
    EXPECT_LE(second, xi.tail<3>().norm() * xi.norm() + kTolExact) << angle;
  }
}

TEST(RigidTransform, ExpMatchesFiniteDifferencesNearTheIdentity) {
  // Central differences: d/dh exp(h·ξ) at h = 0 is ξ^, and near the identity (|ξ₀| ~ 1e-7) the
  // derivative of exp along each coordinate e_i is that coordinate's generator e_i^ (to O(|ξ₀|)).
  std::mt19937 rng(test::kSeed);
  constexpr double kStep = 1e-6;
  for (int k = 0; k < 10; ++k) {
    const Twist xi = randomTwist(rng, 1.0, 1.0);
    const Eigen::Matrix4d d =
        (se3Exp(kStep * xi).matrix() - se3Exp(-kStep * xi).matrix()) / (2.0 * kStep);
    EXPECT_LT(maxAbs(d - wedge(xi)), kTolFiniteDiff);
  }
  const Twist xi0 = 1e-7 * randomTwist(rng, 1.0, 1.0);
  for (int i = 0; i < 6; ++i) {
    const Twist e = Twist::Unit(i);
    const Eigen::Matrix4d d =
        (se3Exp(xi0 + kStep * e).matrix() - se3Exp(xi0 - kStep * e).matrix()) / (2.0 * kStep);
    EXPECT_LT(maxAbs(d - wedge(e)), kTolFiniteDiff) << i;
  }
}

TEST(RigidTransform, PerturbationRotatesInPlaceAndShifts) {
  const RigidTransform T =
      makeTransform(so3Exp(Eigen::Vector3d(0.2, -0.1, 2.6)), Eigen::Vector3d(1500, -900, 350));
  Twist delta;
  delta << 0.3, -0.2, 0.1, 1e-3, -2e-3, 5e-4;
  const RigidTransform P = perturbedTransform(T, delta);
  EXPECT_EQ(P.translation(), Eigen::Vector3d(T.translation() + delta.head<3>()));
  EXPECT_LT((P.linear() - so3Exp(delta.tail<3>()) * T.linear()).norm(), kTolExact);
  EXPECT_EQ(perturbedTransform(T, Twist::Zero()).matrix(), T.matrix());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::geometry
