// calibration::hexapodHoldoutErrors: zero on exact data, the known offset when every measurement
// is displaced (each observation's error too), measurements given in another frame, hysteresis
// removed, FK failures counted (NaN in the per-observation errors).
#include "pkm/calibration/holdout.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using test::kTolRoundTrip;

/// 20 poses about home with their exact readings and measured positions (world).
HexapodCalibrationData exactPoints(const kinematics::HexapodModel& model) {
  std::mt19937 rng(test::kSeed);
  kinematics::HexapodData data(model);
  HexapodCalibrationData held;
  for (int k = 0; k < 20; ++k) {
    const kinematics::PoseRpy pose = test::randomPose(rng, model.home, 40.0, 0.1);
    PointObservation o;
    o.readings = kinematics::inverseKinematics(model, data, pose);
    o.point = data.world_p_tcp;
    held.points.push_back(o);
  }
  return held;
}

TEST(HexapodHoldoutErrors, ExactDataGiveZeroAndADisplacementGivesItself) {
  const kinematics::HexapodModel model = test::millingModel();
  HexapodCalibrationData held = exactPoints(model);
  const HoldoutErrors exact = hexapodHoldoutErrors(model, std::nullopt, held);
  EXPECT_EQ(exact.poses, 20);
  EXPECT_EQ(exact.failures, 0);
  EXPECT_LT(exact.max, kTolRoundTrip);
  const Eigen::Vector3d shift(0.3, -0.4, 0.0);  // |shift| = 0.5
  for (PointObservation& o : held.points) o.point += shift;
  const HoldoutErrors shifted = hexapodHoldoutErrors(model, std::nullopt, held);
  ASSERT_EQ(shifted.errors.size(), 20u);
  for (const double d : shifted.errors) EXPECT_NEAR(d, 0.5, kTolRoundTrip);
  EXPECT_NEAR(shifted.rms, 0.5, kTolRoundTrip);
  EXPECT_NEAR(shifted.mean, 0.5, kTolRoundTrip);
  EXPECT_NEAR(shifted.max, 0.5, kTolRoundTrip);
}

TEST(HexapodHoldoutErrors, MeasurementsInAnotherFrameAreMappedByTheFrame) {
  const kinematics::HexapodModel model = test::millingModel();
  HexapodCalibrationData held = exactPoints(model);
  const geometry::RigidTransform world_T_tracker =
      geometry::makeTransform(geometry::rotationFromRpy(Eigen::Vector3d(0.1, -0.2, 2.5)),
                              Eigen::Vector3d(1500.0, -80.0, 20.0));
  for (PointObservation& o : held.points)
    o.point = world_T_tracker.linear().transpose() * (o.point - world_T_tracker.translation());
  EXPECT_LT(hexapodHoldoutErrors(model, world_T_tracker, held).max, kTolRoundTrip);
  EXPECT_GT(hexapodHoldoutErrors(model, std::nullopt, held).max, 100.0);
}

TEST(HexapodHoldoutErrors, BacklashIsRemovedInTheApproachDirection) {
  const kinematics::HexapodModel model = test::millingModel();
  HexapodCalibrationData held = exactPoints(model);
  const kinematics::StrutVector backlash = kinematics::StrutVector::Constant(0.02);
  for (PointObservation& o : held.points) {
    o.approach = kinematics::StrutVector::Constant(1.0);
    o.readings += 0.5 * backlash;  // the encoder reads past the true length when approaching +
  }
  EXPECT_GT(hexapodHoldoutErrors(model, std::nullopt, held).max, 1e-3);
  EXPECT_LT(hexapodHoldoutErrors(model, std::nullopt, held, backlash).max, kTolRoundTrip);
}

TEST(HexapodHoldoutErrors, ReadingsWithoutASolutionAreCountedAsFailures) {
  const kinematics::HexapodModel model = test::millingModel();
  HexapodCalibrationData held = exactPoints(model);
  held.points[3].readings(2) = std::numeric_limits<double>::quiet_NaN();  // a broken encoder
  const HoldoutErrors e = hexapodHoldoutErrors(model, std::nullopt, held);
  EXPECT_EQ(e.poses, 19);
  EXPECT_EQ(e.failures, 1);
  EXPECT_LT(e.max, kTolRoundTrip);
  // Per observation, in order, NaN where the FK failed.
  ASSERT_EQ(e.errors.size(), 20u);
  EXPECT_TRUE(std::isnan(e.errors[3]));
  EXPECT_LT(e.errors[4], kTolRoundTrip);
}

TEST(HexapodHoldoutErrors, PosesCountWithTheirPositions) {
  const kinematics::HexapodModel model = test::millingModel();
  const HexapodCalibrationData points = exactPoints(model);
  HexapodCalibrationData held;
  for (const PointObservation& p : points.points) {
    PoseObservation o;
    o.readings = p.readings;
    o.pose.position = p.point + Eigen::Vector3d(0.0, 0.0, 0.1);
    held.poses.push_back(o);
  }
  const HoldoutErrors e = hexapodHoldoutErrors(model, std::nullopt, held);
  EXPECT_EQ(e.poses, 20);
  EXPECT_NEAR(e.rms, 0.1, kTolRoundTrip);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
