#include "pkm/kinematics/hexapod_ik.hpp"

#include <gtest/gtest.h>

#include <random>

#include "pkm/geometry/so3.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

PoseRpy pose(double x, double y, double z, double a, double b, double c) {
  return {{x, y, z}, {degToRad(a), degToRad(b), degToRad(c)}};
}

// LinuxCNC genhexkins reference: strut lengths of the default geometry (genhexkins.h, the same as
// configs/sim/axis/vismach/hexapod-sim/kinematics.hal; inches). The home row reproduces the sim's
// HOME strut length 29.7466 (hexapod.ini); the last row is given to five decimals.
struct Reference {
  PoseRpy pose;
  std::array<double, 6> lengths;
};

TEST(HexapodIk, MatchesLinuxcncReferenceTable) {
  const HexapodModel model = test::linuxcncSimModel();
  HexapodData data(model);
  const Reference refs[] = {
      {pose(0, 0, 20, 0, 0, 0), {29.746680, 29.746680, 29.746715, 29.746363, 29.746363, 29.746715}},
      {pose(0, 0, 25, 0, 0, 0), {33.314636, 33.314636, 33.314667, 33.314353, 33.314353, 33.314667}},
      {pose(1, 2, 20, 0, 0, 0), {30.442815, 28.964893, 28.148695, 31.437241, 30.829598, 29.022630}},
      {pose(0, 0, 20, 5, 0, 0), {30.432159, 30.432159, 29.450769, 29.378828, 29.378828, 29.450769}},
      {pose(0, 0, 20, 0, 5, 0), {29.808151, 29.690966, 29.158727, 29.186810, 30.295584, 30.383488}},
      {pose(0, 0, 20, 0, 0, 5), {29.025916, 30.494177, 29.025967, 30.493835, 29.025625, 30.494195}},
      {pose(2, -1, 22, 3, -4, 10),
       {31.597194, 31.713899, 29.975223, 32.850082, 27.921167, 33.441616}},
      {pose(-3, 2, 18, 10, 10, -15),
       {30.022945, 29.402324, 29.682443, 25.351693, 33.820068, 24.667812}},
      {pose(1, -2, 20, 5, -3, 10), {29.89893, 31.41741, 29.21640, 30.24571, 26.02386, 32.41408}},
  };
  for (const Reference& ref : refs) {
    const StrutVector& q = inverseKinematics(model, data, ref.pose);
    for (int i = 0; i < kStruts; ++i)
      EXPECT_NEAR(q[i], ref.lengths[static_cast<std::size_t>(i)], test::kTolLinuxcnc * 10)
          << "strut " << i;
  }
}

TEST(HexapodIk, ReadingPlusOffsetIsJointDistance) {
  const HexapodModel model = test::millingModel();
  HexapodData data(model);
  const PoseRpy p = pose(10, -20, 230, 3, -2, 7);
  const StrutVector& q = inverseKinematics(model, data, p);
  const Eigen::Matrix3d R = geometry::rotationFromRpy(p.rpy);
  for (int i = 0; i < kStruts; ++i) {
    const auto& s = model.struts[static_cast<std::size_t>(i)];
    // Independent: platform origin = TCP - R * tool_offset; joint = origin + R * a.
    const Eigen::Vector3d origin = p.position - R * model.tool_offset;
    const double dist = (origin + R * s.platform_p_joint - s.world_p_base).norm();
    EXPECT_NEAR(q[i] + s.length_offset, dist, 1e-9);
    EXPECT_NEAR(data.joint_distance[i], dist, 1e-9);
    EXPECT_NEAR(data.unit_leg[static_cast<std::size_t>(i)].norm(), 1.0, test::kTolExact);
  }
  EXPECT_LT((data.pose.rpy - p.rpy).norm(), test::kTolExact);
}

TEST(HexapodIk, JacobianMatchesCentralDifferences) {
  for (const HexapodModel& model : {test::linuxcncSimModel(), test::millingModel()}) {
    HexapodData data(model);
    std::mt19937 rng(test::kSeed);
    const double reach = 0.1 * model.characteristicLength();
    for (int k = 0; k < 20; ++k) {
      const PoseRpy p = test::randomPose(rng, model.home, reach, degToRad(15));
      const Eigen::Matrix3d R = geometry::rotationFromRpy(p.rpy);
      inverseKinematics(model, data, p.position, R);
      const Matrix6d J = computeStrutJacobian(model, data);
      const double h = 1e-6 * model.characteristicLength(), hr = 1e-6;
      Matrix6d numeric;
      for (int j = 0; j < 6; ++j) {
        Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
        d[j] = j < 3 ? h : hr;
        // Convention: p + dp, R <- exp([dtheta]x) R (docs/conventions.md).
        const StrutVector plus = inverseKinematics(
            model, data, p.position + d.head<3>(), geometry::so3Exp(d.tail<3>()) * R);
        const StrutVector minus = inverseKinematics(
            model, data, p.position - d.head<3>(), geometry::so3Exp(-d.tail<3>()) * R);
        numeric.col(j) = (plus - minus) / (2 * d[j]);
      }
      EXPECT_LT((numeric - J).norm() / J.norm(), test::kTolFiniteDiff);
    }
  }
}

TEST(HexapodIk, ConditionNumberIsUnitIndependent) {
  HexapodModel mm = test::millingModel();
  HexapodModel inch = mm;
  for (auto& s : inch.struts) {
    s.world_p_base /= 25.4;
    s.platform_p_joint /= 25.4;
    s.length_offset /= 25.4;
  }
  inch.tool_offset /= 25.4;
  inch.home.position /= 25.4;
  HexapodData d1(mm), d2(inch);
  const PoseRpy p = pose(30, 20, 210, 5, 4, 3);
  PoseRpy p_inch = p;
  p_inch.position /= 25.4;
  inverseKinematics(mm, d1, p);
  computeStrutJacobian(mm, d1);
  inverseKinematics(inch, d2, p_inch);
  computeStrutJacobian(inch, d2);
  EXPECT_NEAR(scaledConditionNumber(mm, d1), scaledConditionNumber(inch, d2), 1e-9);
  EXPECT_GT(scaledConditionNumber(mm, d1), 1.0);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
