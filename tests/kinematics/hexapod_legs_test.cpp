// kinematics/detail/hexapod_legs.hpp: computeLegs against the leg vectors computed here one by one
// (the definition: platform joint − base joint, its length, unit vector and reading), and
// computeLegsResidual against computeLegs and the readings it leaves, bit for bit.
#include "kinematics/detail/hexapod_legs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "pkm/geometry/so3.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

TEST(HexapodLegs, EveryLegAsDefined) {
  for (const HexapodModel& m : {test::linuxcncSimModel(), test::millingModel()}) {
    HexapodData data(m);
    std::mt19937 rng(test::kSeed);
    for (int k = 0; k < 200; ++k) {
      const PoseRpy pose =
          test::randomPose(rng, m.home, 0.2 * m.characteristicLength(), degToRad(10));
      const Eigen::Matrix3d R = geometry::rotationFromRpy(pose.rpy);
      detail::computeLegs(m, data, pose.position, R);
      EXPECT_EQ(data.world_R_platform, R);
      EXPECT_EQ(data.world_p_tcp, pose.position);
      for (int i = 0; i < kStruts; ++i) {
        const auto j = static_cast<std::size_t>(i);
        const Eigen::Vector3d r = R * m.effectivePlatform(i);
        const Eigen::Vector3d leg = pose.position + r - m.effectiveBase(i);
        const double len = leg.norm();
        EXPECT_EQ(data.world_r_joint[j], r);
        EXPECT_EQ(data.world_p_platform_joint[j], pose.position + r);
        EXPECT_EQ(data.leg[j], leg);
        EXPECT_EQ(data.joint_distance[i], len);
        EXPECT_EQ(data.inverse_joint_distance[i], 1.0 / len);
        EXPECT_EQ(data.unit_leg[j], leg * (1.0 / len));
        EXPECT_EQ(data.readings[i], len - m.struts[j].length_offset);
      }
    }
  }
}

TEST(HexapodLegs, ResidualIsReadingsMinusTargetWithItsLargestMagnitude) {
  const HexapodModel m = test::millingModel();
  HexapodData a(m), b(m);
  std::mt19937 rng(test::kSeed + 1);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int k = 0; k < 200; ++k) {
    const PoseRpy pose = test::randomPose(rng, m.home, 0.2 * m.characteristicLength(), 0.2);
    const Eigen::Matrix3d R = geometry::rotationFromRpy(pose.rpy);
    detail::computeLegs(m, a, pose.position, R);
    StrutVector target = a.readings;
    for (int i = 0; i < kStruts; ++i) target[i] += noise(rng);
    StrutVector r;
    const double worst = detail::computeLegsResidual(m, b, pose.position, R, target, r);
    EXPECT_EQ(b.readings, a.readings);
    EXPECT_EQ(b.unit_leg, a.unit_leg);
    EXPECT_EQ(r, StrutVector(a.readings - target));
    EXPECT_EQ(worst, r.cwiseAbs().maxCoeff());
  }
}

TEST(HexapodLegs, ANaNResidualIsReportedAsNaN) {
  const HexapodModel m = test::linuxcncSimModel();
  HexapodData data(m);
  const Eigen::Matrix3d R = geometry::rotationFromRpy(m.home.rpy);
  for (int i = 0; i < kStruts; ++i) {
    StrutVector target = StrutVector::Constant(20.0);
    target[i] = std::numeric_limits<double>::quiet_NaN();
    StrutVector r;
    EXPECT_TRUE(std::isnan(detail::computeLegsResidual(m, data, m.home.position, R, target, r)))
        << i;
  }
}

TEST(HexapodLegs, ALegOfZeroLengthHasNoUnitVector) {
  // A platform joint on its base joint (degenerate, but must not divide by zero).
  HexapodModel m = test::linuxcncSimModel();
  HexapodData data(m);
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d p = m.effectiveBase(2) - m.effectivePlatform(2);
  detail::computeLegs(m, data, p, R);
  EXPECT_EQ(data.joint_distance[2], 0.0);
  EXPECT_EQ(data.inverse_joint_distance[2], 0.0);
  EXPECT_EQ(data.unit_leg[2], Eigen::Vector3d::Zero());
  EXPECT_GT(data.joint_distance[1], 0.0);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
