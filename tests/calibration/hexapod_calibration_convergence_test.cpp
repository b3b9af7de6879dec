// Hexapod calibration's convergence on noisy data (tracker poses, SMR points in a tracker frame,
// bidirectional poses with backlash): Levenberg–Marquardt stops within a few iterations at the
// minimum that stopping rules far below the noise floor reach.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "calibration/hexapod_calibration_samples.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/pose_rpy.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "pkm/simulation/laser_tracker.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using kinematics::HexapodModel;
using test::kNoiseFactor;
using test::kTrackerAngleSigma;
using test::kTrackerSigma;
using test::maxTcpError;
using test::measurePoses;
using test::trueMachine;

// Convergence on noisy data: Levenberg–Marquardt reaches the noise floor in a few steps; the
// stopping rules must be reachable there, or it runs rejected steps until the trust region
// collapses (or to max_iterations).
constexpr int kMaxNoisyIterations = 12;       ///< LM iterations (Ceres', rejected steps included)
constexpr double kTolStationary = 1e-6;       ///< mm: estimate, default vs strict stopping rules
constexpr double kPointTrackerSigma = 0.010;  ///< mm, laser tracker position noise (SMR points)

/// The estimate once more with stopping rules far below the noise floor (they end by the trust
/// region collapsing, whatever it costs): the default answer must already be that minimum.
HexapodCalibrationSummary strictRerun(const HexapodModel& nominal,
                                      const HexapodCalibrationData& data,
                                      HexapodCalibrationOptions options) {
  options.function_tolerance = 1e-16;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-16;
  options.max_iterations = 200;
  return calibrateHexapod(nominal, data, options);
}

TEST(HexapodCalibration, ConvergesInAFewIterationsOnNoisyPoses) {
  const HexapodModel nominal = test::millingModel();
  const HexapodModel truth = trueMachine(test::kSeed + 40);
  HexapodCalibrationData data;
  data.poses = measurePoses(truth, 200, test::kSeed + 41, kTrackerSigma, kTrackerAngleSigma);
  const HexapodCalibrationSummary s = calibrateHexapod(nominal, data);
  EXPECT_TRUE(s.converged) << s.termination;
  EXPECT_LE(s.iterations, kMaxNoisyIterations) << s.termination;
  RecordProperty("iterations", s.iterations);
  const HexapodCalibrationSummary strict = strictRerun(nominal, data, {});
  EXPECT_LT((strict.parameters - s.parameters).cwiseAbs().maxCoeff(), kTolStationary);
  EXPECT_NEAR(strict.after.rms, s.after.rms, 1e-6 * s.after.rms);
  EXPECT_NEAR(s.after.rms, kTrackerSigma, 0.3 * kTrackerSigma);
  const double after =
      maxTcpError(withHexapodParameters(nominal, s.parameters), truth, test::kSeed + 42);
  EXPECT_LT(after, kNoiseFactor * kTrackerSigma);
}

TEST(HexapodCalibration, ConvergesInAFewIterationsOnNoisyTrackerPoints) {
  // SMR points in a tracker frame (10 µm): FK residuals and the frame estimated with them.
  const HexapodModel nominal = test::millingModel();
  const HexapodModel truth = trueMachine(test::kSeed + 43);
  const geometry::RigidTransform world_T_tracker =
      geometry::makeTransform(geometry::rotationFromRpy(Eigen::Vector3d(1e-4, 2e-4, -0.7)),
                              Eigen::Vector3d(900, 1200, -80));
  const Eigen::Matrix3d tracker_R_world = world_T_tracker.linear().transpose();
  std::mt19937 rng(test::kSeed + 44);
  std::normal_distribution<double> n(0.0, kPointTrackerSigma);
  HexapodCalibrationData data;
  for (const PoseObservation& o : measurePoses(truth, 150, test::kSeed + 45, 0.0, 0.0)) {
    Eigen::Vector3d p = tracker_R_world * (o.pose.position - world_T_tracker.translation());
    for (int i = 0; i < 3; ++i) p(i) += n(rng);
    data.points.push_back({o.readings, p});
  }
  data.measurement_frame = initialMeasurementFrame(nominal, data);
  const HexapodCalibrationSummary s = calibrateHexapod(nominal, data);
  EXPECT_TRUE(s.converged) << s.termination;
  EXPECT_LE(s.iterations, kMaxNoisyIterations) << s.termination;
  RecordProperty("iterations", s.iterations);
  const HexapodCalibrationSummary strict = strictRerun(nominal, data, {});
  EXPECT_LT((strict.parameters - s.parameters).cwiseAbs().maxCoeff(), kTolStationary);
  EXPECT_NEAR(s.after.rms, kPointTrackerSigma, 0.3 * kPointTrackerSigma);
}

TEST(HexapodCalibration, ConvergesInAFewIterationsOnNoisyBidirectionalData) {
  // Backlash estimated from tracker poses with the simulated tracker's noise.
  simulation::HexapodVirtualMachine vm = test::backlashMachine();
  simulation::TrackerSetup setup = test::bidirectionalSetup("bidirectional-noisy", 200);
  setup.noise = *simulation::trackerNoise("laser-tracker");
  simulation::RandomStream rng(test::kSeed + 46);
  HexapodCalibrationData data;
  std::vector<kinematics::StrutVector> q;
  for (const auto& r : simulation::simulateLaserTracker(vm, setup, rng)) {
    PoseObservation o;
    o.readings = r.lengths;
    o.pose = kinematics::poseRpyFromTransform(r.measured);
    data.poses.push_back(o);
    q.push_back(r.lengths);
  }
  const auto approach = approachFromSequence(q, 1.0);
  for (std::size_t k = 0; k < data.poses.size(); ++k) data.poses[k].approach = approach[k];
  HexapodCalibrationOptions options;
  options.estimate_backlash = true;
  const HexapodCalibrationSummary s = calibrateHexapod(test::millingModel(), data, options);
  EXPECT_TRUE(s.converged) << s.termination;
  EXPECT_LE(s.iterations, kMaxNoisyIterations) << s.termination;
  RecordProperty("iterations", s.iterations);
  ASSERT_TRUE(s.backlash.has_value());
  const HexapodCalibrationSummary strict = strictRerun(test::millingModel(), data, options);
  EXPECT_LT((strict.parameters - s.parameters).cwiseAbs().maxCoeff(), kTolStationary);
  ASSERT_TRUE(strict.backlash.has_value());
  EXPECT_LT((*strict.backlash - *s.backlash).cwiseAbs().maxCoeff(), kTolStationary);
  for (int i = 0; i < kinematics::kStruts; ++i)
    EXPECT_NEAR((*s.backlash)(i), test::trueBacklash()(i), 4.0 * s.backlash_standard_deviation(i))
        << i;
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration