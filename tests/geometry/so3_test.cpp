#include "pkm/geometry/so3.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "support/tolerances.hpp"

namespace pkm::geometry {
namespace PKM_TEST_NS {

using test::kTolExact;

Eigen::Vector3d randomVector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

bool isRotation(const Eigen::Matrix3d& R) {
  return (R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-12 &&
         std::abs(R.determinant() - 1) < 1e-12;
}

TEST(So3, HatIsCrossProduct) {
  std::mt19937 rng(test::kSeed);
  for (int k = 0; k < 50; ++k) {
    const Eigen::Vector3d w = randomVector(rng, 3), v = randomVector(rng, 3);
    EXPECT_LT((hat(w) * v - w.cross(v)).norm(), kTolExact);
  }
}

TEST(So3, ExpMatchesAngleAxis) {
  std::mt19937 rng(test::kSeed);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d w = randomVector(rng, 3);
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
    EXPECT_LT((so3Exp(w) - expected).norm(), kTolExact);
    EXPECT_TRUE(isRotation(so3Exp(w)));
  }
}

TEST(So3, ExpSeriesBranchMatchesAngleAxisAcrossItsSwitch) {
  // so3Exp uses a Taylor series below 1e-3 rad: the small angles of Newton steps (1e-9 .. 1e-2
  // rad, across the switch) against Eigen's angle-axis rotation, to rounding.
  constexpr double kTolRounding = 4e-16;  // a few units in the last place of an entry
  std::mt19937 rng(test::kSeed);
  for (const double angle : {1e-9, 3e-7, 2e-5, 9.99e-4, 1.001e-3, 5e-3, 2e-2}) {
    for (int k = 0; k < 20; ++k) {
      const Eigen::Vector3d axis = randomVector(rng, 1.0).normalized();
      const Eigen::Matrix3d expected = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
      EXPECT_LT((so3Exp(angle * axis) - expected).cwiseAbs().maxCoeff(), kTolRounding) << angle;
      EXPECT_TRUE(isRotation(so3Exp(angle * axis)));
    }
  }
}

TEST(So3, ExpNearIdentityIsFirstOrderAccurate) {
  const Eigen::Vector3d w(1e-9, -2e-9, 3e-10);
  EXPECT_LT((so3Exp(w) - (Eigen::Matrix3d::Identity() + hat(w))).norm(), kTolExact);
  EXPECT_TRUE(so3Exp(Eigen::Vector3d::Zero()).isIdentity(0.0));
}

TEST(So3, LeftJacobianMatchesFiniteDifferences) {
  // exp(w + δ)·exp(w)ᵀ ≈ exp([J_l δ]x): compare J_l columns with central differences, across the
  // series threshold and at large angles.
  constexpr double kStep = 1e-6;
  for (const double angle : {0.0, 1e-7, 5e-4, 2e-3, 0.7, 2.6}) {
    const Eigen::Vector3d w = angle * Eigen::Vector3d(0.3, -0.5, 0.81).normalized();
    const Eigen::Matrix3d J = so3LeftJacobian(w);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d d = kStep * Eigen::Vector3d::Unit(k);
      const Eigen::Vector3d fd = (so3Log(so3Exp(w + d) * so3Exp(w).transpose()) -
                                  so3Log(so3Exp(w - d) * so3Exp(w).transpose())) /
                                 (2 * kStep);
      EXPECT_LT((fd - J.col(k)).cwiseAbs().maxCoeff(), 1e-8) << angle;
    }
  }
}

TEST(So3, LogInvertsExpIncludingNearPi) {
  std::mt19937 rng(test::kSeed);
  for (int k = 0; k < 200; ++k) {
    Eigen::Vector3d w = randomVector(rng, 1).normalized();
    w *= (k % 4 == 0) ? std::numbers::pi - 1e-7
                      : (k % 4 == 1 ? 1e-8 : std::uniform_real_distribution<>(0, 3.1)(rng));
    EXPECT_LT((so3Log(so3Exp(w)) - w).norm(), 1e-9) << w.transpose();
  }
}

TEST(So3, RpyIsFixedAxisRollPitchYaw) {
  const Eigen::Vector3d rpy(0.3, -0.2, 1.1);
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  EXPECT_LT((rotationFromRpy(rpy) - expected).norm(), kTolExact);
}

TEST(So3, RpyRoundTrip) {
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> ang(-3.1, 3.1), pitch(-1.5, 1.5);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d rpy(ang(rng), pitch(rng), ang(rng));
    EXPECT_LT((rpyFromRotation(rotationFromRpy(rpy)) - rpy).norm(), 1e-12);
  }
}

TEST(So3, RpyAtGimbalLockReproducesRotation) {
  for (double b : {std::numbers::pi / 2, -std::numbers::pi / 2}) {
    const Eigen::Matrix3d R = rotationFromRpy({0.4, b, -0.7});
    EXPECT_LT((rotationFromRpy(rpyFromRotation(R)) - R).norm(), 1e-12);
  }
}

TEST(So3, RpyNearestKeepsAnglesContinuous) {
  // c = 200 deg is returned as -160 deg by the plain extraction, as 200 deg near a 190 deg seed.
  const Eigen::Vector3d rpy(0.1, 0.2, 200.0 * std::numbers::pi / 180.0);
  const Eigen::Matrix3d R = rotationFromRpy(rpy);
  EXPECT_LT(rpyFromRotation(R).z(), 0.0);
  const Eigen::Vector3d near(0.1, 0.2, 190.0 * std::numbers::pi / 180.0);
  EXPECT_LT((rpyFromRotation(R, near) - rpy).norm(), 1e-12);
  // The second branch (a+pi, pi-b, c+pi) is chosen when the seed is on it.
  const Eigen::Vector3d other(
      rpy.x() + std::numbers::pi, std::numbers::pi - rpy.y(), rpy.z() + std::numbers::pi);
  EXPECT_LT((rpyFromRotation(R, other) - other).norm(), 1e-12);
}

TEST(So3, NearestRpyOfTheExtractedAnglesIsRpyNear) {
  // rpyFromRotation(R, near) is nearestRpy(rpyFromRotation(R), near), bit for bit, on both
  // branches, across +-pi, with near far and close; a triple already nearest comes back as +0,
  // not -0.
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Matrix3d R = rotationFromRpy({u(rng), 0.4 * u(rng), u(rng)});
    const Eigen::Vector3d near(u(rng), u(rng), 3.0 * u(rng));
    EXPECT_EQ(nearestRpy(rpyFromRotation(R), near), rpyFromRotation(R, near)) << k;
  }
  const Eigen::Vector3d zero =
      nearestRpy(Eigen::Vector3d(-0.0, 0.0, -0.0), Eigen::Vector3d::Zero());
  EXPECT_FALSE(std::signbit(zero.x()));
  EXPECT_FALSE(std::signbit(zero.z()));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::geometry
