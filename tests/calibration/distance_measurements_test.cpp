#include "pkm/calibration/distance_measurements.hpp"

#include <gtest/gtest.h>

#include <random>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using kinematics::HexapodData;
using kinematics::HexapodModel;
using kinematics::PoseRpy;

constexpr double kStep = 1e-6;        // mm, central-difference step
constexpr double kDerivative = 1e-6;  // relative agreement analytic vs central differences
constexpr double kReach = 120.0;      // mm
constexpr double kTilt = 0.1;         // rad
constexpr double kError = 0.5;        // mm, injected parameter errors
constexpr double kExact = 1e-7;       // mm, residuals after a noise-free fit

HexapodModel perturbed(unsigned seed) {
  const HexapodModel nominal = test::millingModel();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-kError, kError);
  HexapodParameterVector p = hexapodParameters(nominal);
  for (int k = 0; k < kHexapodParameters; ++k) p(k) += u(rng);
  return withHexapodParameters(nominal, p);
}

/// Distances measured on `truth`: interferometer lines from a start pose and a ball bar on a
/// pivot, both exact.
std::vector<DistanceObservation> measure(const HexapodModel& truth, unsigned seed, int count) {
  std::mt19937 rng(seed);
  HexapodData d(truth);
  std::vector<DistanceObservation> out;
  const PoseRpy start = test::randomPose(rng, truth.home, kReach, kTilt);
  const kinematics::StrutVector q0 = kinematics::inverseKinematics(truth, d, start);
  (void)kinematics::forwardKinematics(truth, d, q0, start);
  const Eigen::Vector3d p0 = d.world_p_tcp;
  const Eigen::Vector3d pivot = truth.home.position + Eigen::Vector3d(10, -20, -150);
  for (int k = 0; k < count; ++k) {
    const PoseRpy pose = test::randomPose(rng, truth.home, kReach, kTilt);
    DistanceObservation o;
    o.readings = kinematics::inverseKinematics(truth, d, pose);
    EXPECT_TRUE(kinematics::forwardKinematics(truth, d, o.readings, pose).ok());
    if (k % 2 == 0) {
      o.readings_from = q0;
      o.distance = (d.world_p_tcp - p0).norm();
    } else {
      o.from_point = pivot;
      o.distance = (d.world_p_tcp - pivot).norm();
    }
    out.push_back(o);
  }
  return out;
}

TEST(DistanceMeasurements, ExactDataHasZeroResidualAndJacobianMatchesDifferences) {
  const HexapodModel truth = perturbed(test::kSeed);
  const auto obs = measure(truth, test::kSeed + 1, 6);
  HexapodData d(truth);
  for (const DistanceObservation& o : obs) {
    DistanceParameterJacobian J;
    const auto r = distanceResidual(truth, d, o, truth.home, &J);
    ASSERT_TRUE(r.has_value());
    EXPECT_NEAR(*r, 0.0, test::kTolRoundTrip);
    const HexapodParameterVector p = hexapodParameters(truth);
    for (int k = 0; k < kHexapodParameters; ++k) {
      HexapodParameterVector plus = p, minus = p;
      plus(k) += kStep;
      minus(k) -= kStep;
      const auto rp = distanceResidual(withHexapodParameters(truth, plus), d, o, truth.home);
      const auto rm = distanceResidual(withHexapodParameters(truth, minus), d, o, truth.home);
      ASSERT_TRUE(rp && rm);
      const double fd = (*rp - *rm) / (2 * kStep);
      EXPECT_NEAR(J(k), fd, kDerivative * std::max(1.0, std::fabs(fd))) << hexapodParameterName(k);
    }
  }
}

TEST(DistanceMeasurements, CoincidentEndsAreNotAResidual) {
  const HexapodModel m = test::millingModel();
  HexapodData d(m);
  DistanceObservation o;
  o.readings = kinematics::inverseKinematics(m, d, m.home);
  o.readings_from = o.readings;
  EXPECT_FALSE(distanceResidual(m, d, o, m.home).has_value());
}

TEST(DistanceMeasurements, DistancesAloneIdentifyShapeNotPlacement) {
  const HexapodModel truth = perturbed(test::kSeed + 2);
  HexapodCalibrationData data;
  data.distances = measure(truth, test::kSeed + 3, 300);
  const HexapodCalibrationSummary s = calibrateHexapod(test::millingModel(), data);
  EXPECT_GT(s.before.rms, 0.01);
  EXPECT_LT(s.after.max, kExact);
  // A rigid motion of the whole machine changes no distance: at least 6 combinations unseen,
  // named rather than silently fixed.
  EXPECT_GE(static_cast<int>(s.identifiability.combinations.size()), 6);
  EXPECT_EQ(s.identifiability.rank + static_cast<int>(s.identifiability.combinations.size()),
            kHexapodParameters);
}

TEST(DistanceMeasurements, BadValuesAreRejected) {
  HexapodCalibrationData data;
  data.distances = measure(test::millingModel(), test::kSeed + 4, 60);
  data.distances[5].distance = -1.0;
  EXPECT_THROW((void)calibrateHexapod(test::millingModel(), data), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration

namespace pkm::calibration {
namespace PKM_TEST_NS {

TEST(DistanceMeasurements, ConvergesInAFewIterationsOnNoisyDistances) {
  // Interferometer lines and a ball bar, 1 µm noise: rank-deficient (6 placement directions held
  // by priors), so the stopping rules must also be reachable with the priors in the cost.
  constexpr int kMaxIterations = 12;       ///< LM iterations (rejected steps included)
  constexpr double kNoise = 0.001;         ///< mm, interferometer / ball-bar noise
  constexpr double kTolStationary = 1e-6;  ///< mm: default vs strict stopping rules
  const HexapodModel truth = perturbed(test::kSeed + 20);
  HexapodCalibrationData data;
  data.distances = measure(truth, test::kSeed + 21, 300);
  std::mt19937 rng(test::kSeed + 22);
  std::normal_distribution<double> n(0.0, kNoise);
  for (DistanceObservation& o : data.distances) o.distance += n(rng);
  const HexapodCalibrationSummary s = calibrateHexapod(test::millingModel(), data);
  EXPECT_TRUE(s.converged) << s.termination;
  EXPECT_LE(s.iterations, kMaxIterations) << s.termination;
  RecordProperty("iterations", s.iterations);
  EXPECT_NEAR(s.after.rms, kNoise, 0.3 * kNoise);
  HexapodCalibrationOptions strict;
  strict.function_tolerance = 1e-16;
  strict.gradient_tolerance = 1e-16;
  strict.parameter_tolerance = 1e-16;
  strict.max_iterations = 200;
  const HexapodCalibrationSummary tight = calibrateHexapod(test::millingModel(), data, strict);
  EXPECT_LT((tight.parameters - s.parameters).cwiseAbs().maxCoeff(), kTolStationary);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
