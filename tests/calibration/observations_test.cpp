#include "calibration/detail/observations.hpp"

#include <gtest/gtest.h>

#include <random>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration::detail {
namespace PKM_TEST_NS {

constexpr double kStep = 1e-6;  ///< central-difference step (mm, rad)

HexapodCalibrationData trackerData(const kinematics::HexapodModel& model, FrameEstimate& frame) {
  frame.initial =
      geometry::makeTransform(geometry::rotationFromRpy(Eigen::Vector3d(0.01, -0.02, 2.6)),
                              Eigen::Vector3d(1500, -900, 350));
  frame.delta << 0.3, -0.2, 0.1, 1e-3, -2e-3, 5e-4;
  const geometry::RigidTransform f = frame.current();
  std::mt19937 rng(test::kSeed);
  kinematics::HexapodData work(model);
  HexapodCalibrationData data;
  for (int k = 0; k < 3; ++k) {
    const auto pose = test::randomPose(rng, model.home, 100.0, 0.1);
    PoseObservation o;
    o.readings = kinematics::inverseKinematics(model, work, pose);
    o.readings(1) += 0.05;  // not an exact fit: residuals ≠ 0
    o.pose.position = f.linear().transpose() * (pose.position - f.translation());
    o.pose.rpy =
        geometry::rpyFromRotation(f.linear().transpose() * geometry::rotationFromRpy(pose.rpy));
    data.poses.push_back(o);
    data.points.push_back({o.readings, o.pose.position + Eigen::Vector3d(0.01, 0, 0)});
  }
  data.measurement_frame = frame.initial;
  return data;
}

TEST(CalibrationObservations, FrameJacobiansMatchCentralDifferences) {
  const kinematics::HexapodModel model = test::millingModel();
  FrameEstimate frame;
  const HexapodCalibrationData data = trackerData(model, frame);
  kinematics::HexapodData work(model);
  for (const ObservationRef& ref : observations(data)) {
    double r[6];
    Eigen::MatrixXd Jt, Jf;
    ASSERT_TRUE(evaluate(model, work, data, ref, &frame, r, &Jt, &Jf));
    for (int k = 0; k < 6; ++k) {
      FrameEstimate plus = frame, minus = frame;
      plus.delta(k) += kStep;
      minus.delta(k) -= kStep;
      double rp[6], rm[6];
      ASSERT_TRUE(evaluate(model, work, data, ref, &plus, rp, nullptr, nullptr));
      ASSERT_TRUE(evaluate(model, work, data, ref, &minus, rm, nullptr, nullptr));
      for (Eigen::Index i = 0; i < ref.rows(); ++i) {
        const double fd = (rp[i] - rm[i]) / (2 * kStep);
        // Rotation columns are per rad at lever arms of ~2 m: compare relative to 1000 mm.
        const double scale = k < 3 ? 1.0 : 1e3;
        EXPECT_NEAR(fd / scale, Jf(i, k) / scale, test::kTolFiniteDiff)
            << "kind " << static_cast<int>(ref.kind) << " row " << i << " col " << k;
      }
    }
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration::detail
