#include "pkm/kinematics/pose_rpy.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "pkm/geometry/so3.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

using test::kTolExact;

TEST(PoseRpy, ToRigidTransformIsPositionAndLinuxcncRotation) {
  const PoseRpy pose{Eigen::Vector3d(12.5, -40.0, 310.0), Eigen::Vector3d(0.1, -0.2, 2.9)};
  const geometry::RigidTransform T = toRigidTransform(pose);
  EXPECT_EQ(T.translation(), pose.position);
  EXPECT_EQ(T.linear(), geometry::rotationFromRpy(pose.rpy));
  // A point of the platform frame (relative to the TCP) maps to world as R·x + p.
  const Eigen::Vector3d x(30.0, -20.0, 60.0);
  EXPECT_LT((T * x - (geometry::rotationFromRpy(pose.rpy) * x + pose.position)).norm(),
            kTolExact * 1e3);
}

TEST(PoseRpy, RoundTripsThroughTheTransform) {
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 100; ++k) {
    // Principal angles: b in (−pi/2, pi/2), a and c in (−pi, pi).
    const PoseRpy pose{Eigen::Vector3d(500.0 * u(rng), 500.0 * u(rng), 500.0 * u(rng)),
                       Eigen::Vector3d(3.0 * u(rng), 1.5 * u(rng), 3.0 * u(rng))};
    const PoseRpy back = poseRpyFromTransform(toRigidTransform(pose));
    EXPECT_EQ(back.position, pose.position);
    EXPECT_LT((back.rpy - pose.rpy).norm(), kTolExact * 10.0) << pose.rpy.transpose();
  }
}

TEST(PoseRpy, NearPicksTheContinuousTriple) {
  // c just past +pi: the principal triple wraps to −pi, the one near the previous pose does not.
  const PoseRpy pose{Eigen::Vector3d(1.0, 2.0, 3.0), Eigen::Vector3d(0.05, -0.1, 3.2)};
  const geometry::RigidTransform T = toRigidTransform(pose);
  EXPECT_NEAR(poseRpyFromTransform(T).rpy.z(), 3.2 - 2.0 * std::numbers::pi, kTolExact * 10.0);
  const PoseRpy near = poseRpyFromTransform(T, Eigen::Vector3d(0.0, 0.0, 3.1));
  EXPECT_LT((near.rpy - pose.rpy).norm(), kTolExact * 10.0);
  EXPECT_EQ(near.position, pose.position);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
