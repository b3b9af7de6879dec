#include "pkm/calibration/hexapod_measurements.hpp"

#include <gtest/gtest.h>

#include <random>

#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using kinematics::HexapodData;
using kinematics::HexapodModel;

constexpr double kStep = 1e-5;  ///< central-difference step, mm

/// Exact observation of `pose` on `model`.
PoseObservation observe(const HexapodModel& model, const kinematics::PoseRpy& pose) {
  HexapodData data(model);
  PoseObservation o;
  o.readings = kinematics::inverseKinematics(model, data, pose);
  o.pose = pose;
  return o;
}

TEST(HexapodMeasurements, ExactPoseDataHasZeroResiduals) {
  const HexapodModel model = test::millingModel();
  std::mt19937 rng(test::kSeed);
  HexapodData data(model);
  for (int k = 0; k < 20; ++k) {
    const auto pose = test::randomPose(rng, model.home, 100.0, 0.1);
    EXPECT_LT(poseResiduals(model, data, observe(model, pose)).cwiseAbs().maxCoeff(),
              test::kTolExact * 1e3);
    const auto e = forwardPoseError(model, data, observe(model, pose).readings, pose, model.home);
    ASSERT_TRUE(e.has_value());
    EXPECT_LT(e->cwiseAbs().maxCoeff(), test::kTolRoundTrip);
  }
}

TEST(HexapodMeasurements, PoseJacobianMatchesCentralDifferences) {
  const HexapodModel model = test::millingModel();
  std::mt19937 rng(test::kSeed + 1);
  const PoseObservation o = observe(model, test::randomPose(rng, model.home, 100.0, 0.1));
  HexapodData data(model);
  PoseParameterJacobian J;
  (void)poseResiduals(model, data, o, &J);
  const HexapodParameterVector p0 = hexapodParameters(model);
  for (int k = 0; k < kHexapodParameters; ++k) {
    HexapodParameterVector p = p0;
    p(k) += kStep;
    const auto rp = poseResiduals(withHexapodParameters(model, p), data, o);
    p(k) -= 2 * kStep;
    const auto rm = poseResiduals(withHexapodParameters(model, p), data, o);
    const kinematics::StrutVector fd = (rp - rm) / (2 * kStep);
    EXPECT_LT((fd - J.col(k)).cwiseAbs().maxCoeff(), test::kTolFiniteDiff)
        << hexapodParameterName(k);
  }
}

TEST(HexapodMeasurements, ForwardJacobianMatchesCentralDifferences) {
  const HexapodModel model = test::millingModel();
  std::mt19937 rng(test::kSeed + 2);
  const auto pose = test::randomPose(rng, model.home, 100.0, 0.1);
  const PoseObservation o = observe(model, pose);
  HexapodData data(model);
  PoseParameterJacobian J;
  ASSERT_TRUE(forwardPoseError(model, data, o.readings, pose, pose, &J).has_value());
  PointParameterJacobian Jpoint;
  const PointObservation point{o.readings, pose.position};
  ASSERT_TRUE(pointResiduals(model, data, point, pose, &Jpoint).has_value());
  EXPECT_LT((Jpoint - J.topRows<3>()).cwiseAbs().maxCoeff(), test::kTolExact);
  const HexapodParameterVector p0 = hexapodParameters(model);
  for (int k = 0; k < kHexapodParameters; ++k) {
    HexapodParameterVector p = p0;
    p(k) += kStep;
    const auto ep = forwardPoseError(withHexapodParameters(model, p), data, o.readings, pose, pose);
    p(k) -= 2 * kStep;
    const auto em = forwardPoseError(withHexapodParameters(model, p), data, o.readings, pose, pose);
    ASSERT_TRUE(ep && em);
    const Eigen::Matrix<double, 6, 1> fd = (*ep - *em) / (2 * kStep);
    // Position rows in mm/mm; angular rows in rad/mm, scaled by a characteristic length.
    EXPECT_LT((fd - J.col(k)).head<3>().cwiseAbs().maxCoeff(), test::kTolFiniteDiff)
        << hexapodParameterName(k);
    EXPECT_LT((fd - J.col(k)).tail<3>().cwiseAbs().maxCoeff() * model.characteristicLength(),
              test::kTolFiniteDiff)
        << hexapodParameterName(k);
  }
}

TEST(HexapodMeasurements, FailedForwardKinematicsIsNullopt) {
  const HexapodModel model = test::millingModel();
  HexapodData data(model);
  PointObservation o;
  o.readings.setConstant(-5000.0);  // no pose has these strut readings
  kinematics::FkOptions options;
  options.max_iterations = 5;
  EXPECT_FALSE(pointResiduals(model, data, o, model.home).has_value());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
