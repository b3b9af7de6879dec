#include "pkm/calibration/constrained_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "constrained_samples.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using kinematics::HexapodData;
using kinematics::HexapodModel;
using kinematics::PoseRpy;

constexpr double kStep = 1e-5;             ///< central-difference step, mm
constexpr double kJointError = 0.5;        ///< mm, injected joint errors
constexpr double kPlanarRange = 150.0;     ///< mm, station moves in x and y
constexpr double kYawRange = 0.2;          ///< rad, station moves about z
constexpr double kRemovedFraction = 0.95;  ///< acceptance: at least 95 % of the error removed

HexapodModel perturbed(const HexapodModel& nominal, unsigned seed) {
  return test::perturbedModel(nominal, seed, kJointError);
}

ConstrainedMotionData constrainedData(
    const HexapodModel& nominal, const HexapodModel& truth, double z, int stations, unsigned seed) {
  return test::constrainedData(nominal, truth, z, stations, seed, kPlanarRange, kYawRange);
}

/// Largest gauge deviation from the reference plane when `controller` commands planar moves on
/// `truth` (what the gauges of seed 004 would show without jogging).
double planarError(const HexapodModel& controller, const HexapodModel& truth, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  HexapodData c(controller), t(truth);
  ConstrainedMotionData set = constrainedData(controller, controller, 200.0, 0, seed);
  const auto heights = [&](const PoseRpy& command) {
    GaugeStation s;
    s.readings = kinematics::inverseKinematics(controller, c, command);
    s.command = command;
    return gaugeHeights(truth, t, set, s).value();
  };
  PoseRpy ref = controller.home;
  ref.position.z() = 200.0;
  const Eigen::Vector3d h0 = heights(ref);
  double worst = 0.0;
  for (int k = 0; k < 40; ++k) {
    PoseRpy p = ref;
    p.position.x() += kPlanarRange * u(rng);
    p.position.y() += kPlanarRange * u(rng);
    p.rpy.z() += kYawRange * u(rng);
    worst = std::max(worst, (heights(p) - h0).cwiseAbs().maxCoeff());
  }
  return worst;
}

TEST(ConstrainedMotion, ExactDataHasZeroResidualsUnderTheTrueModel) {
  const HexapodModel nominal = test::millingModel();
  const HexapodModel truth = perturbed(nominal, test::kSeed);
  const ConstrainedMotionData set = constrainedData(nominal, truth, 150.0, 10, test::kSeed + 1);
  HexapodData work(truth);
  for (std::size_t k = 0; k < set.stations.size(); ++k) {
    const auto r = constrainedResiduals(truth, work, set, k);
    ASSERT_TRUE(r.has_value());
    EXPECT_LT(r->cwiseAbs().maxCoeff(), test::kTolRoundTrip);
  }
}

TEST(ConstrainedMotion, JacobianMatchesCentralDifferences) {
  const HexapodModel nominal = test::millingModel();
  const ConstrainedMotionData set =
      constrainedData(nominal, perturbed(nominal, test::kSeed), 150.0, 3, test::kSeed + 2);
  HexapodData work(nominal);
  GaugeParameterJacobian J;
  ASSERT_TRUE(constrainedResiduals(nominal, work, set, 1, &J).has_value());
  const HexapodParameterVector p0 = hexapodParameters(nominal);
  for (int k = 0; k < kHexapodParameters; ++k) {
    HexapodParameterVector p = p0;
    p(k) += kStep;
    const auto rp = constrainedResiduals(withHexapodParameters(nominal, p), work, set, 1);
    p(k) -= 2 * kStep;
    const auto rm = constrainedResiduals(withHexapodParameters(nominal, p), work, set, 1);
    ASSERT_TRUE(rp && rm);
    const Eigen::Vector3d fd = (*rp - *rm) / (2 * kStep);
    EXPECT_LT((fd - J.col(k)).cwiseAbs().maxCoeff(), test::kTolFiniteDiff)
        << hexapodParameterName(k);
  }
}

TEST(ConstrainedMotion, CalibrationNamesWhatItCannotSeeAndRemovesThePlanarError) {
  const HexapodModel nominal = test::millingModel();
  const HexapodModel truth = perturbed(nominal, test::kSeed + 3);
  HexapodCalibrationData data;
  // Two plate heights, as with a spacer under the gauges.
  data.constrained.push_back(constrainedData(nominal, truth, 150.0, 40, test::kSeed + 4));
  data.constrained.push_back(constrainedData(nominal, truth, 250.0, 40, test::kSeed + 5));
  const HexapodCalibrationSummary s = calibrateHexapod(nominal, data);
  EXPECT_LT(s.identifiability.rank, kHexapodParameters);
  EXPECT_FALSE(s.identifiability.combinations.empty());
  EXPECT_LT(s.after.rms, 1e-6);
  const double before = planarError(nominal, truth, test::kSeed + 6);
  const HexapodModel calibrated = withHexapodParameters(nominal, s.parameters);
  const double after = planarError(calibrated, truth, test::kSeed + 6);
  RecordProperty("planar_error_before_mm", std::to_string(before));
  RecordProperty("planar_error_after_mm", std::to_string(after));
  RecordProperty("rank", s.identifiability.rank);
  EXPECT_GT(before, 0.05);
  EXPECT_LT(after, (1.0 - kRemovedFraction) * before)
      << "before " << before << " after " << after << " rank " << s.identifiability.rank;
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration

namespace pkm::calibration {
namespace PKM_TEST_NS {

TEST(ConstrainedMotion, BadSetsAreRejected) {
  const kinematics::HexapodModel nominal = test::millingModel();
  HexapodCalibrationData data;
  data.constrained.push_back(constrainedData(nominal, nominal, 150.0, 20, test::kSeed));
  data.constrained[0].stations[4].gauges[1] = std::nan("");
  try {
    (void)calibrateHexapod(nominal, data);
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "calibration: constrained set 1: station 5 has a non-finite value");
  }
  data.constrained[0].stations[4].gauges[1] = 0.0;
  data.constrained[0].table_normal = Eigen::Vector3d(0, 0, 2);
  EXPECT_THROW((void)calibrateHexapod(nominal, data), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration

namespace pkm::calibration {
namespace PKM_TEST_NS {

/// One plate height, few stations and noisy strut readings: combinations the gauges see only
/// weakly. A Tikhonov prior of the plausible geometry error keeps them near the machine file, so
/// the solve converges well inside the iteration limit and still removes the planar error
/// (docs/calibration.md, "Weakly identified directions").
TEST(ConstrainedMotion, ParameterPriorConvergesOnWeakGaugeData) {
  constexpr double kReadingNoise = 0.002;  ///< mm, strut repeatability (seed 004)
  constexpr double kPriorSigma = 4 * kJointError;
  const HexapodModel nominal = test::millingModel();
  const HexapodModel truth = perturbed(nominal, test::kSeed + 7);
  HexapodCalibrationData data;
  data.constrained.push_back(constrainedData(nominal, truth, 200.0, 24, test::kSeed + 8));
  std::mt19937 rng(test::kSeed + 9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (GaugeStation& s : data.constrained[0].stations)
    for (int i = 0; i < kinematics::kStruts; ++i)
      s.readings(i) += kReadingNoise * std::sqrt(3.0) * u(rng);
  HexapodCalibrationOptions options;
  options.measurement_sigma = kReadingNoise;
  options.parameter_prior_sigma = kPriorSigma;
  const HexapodCalibrationSummary s = calibrateHexapod(nominal, data, options);
  EXPECT_TRUE(s.converged) << s.termination;
  RecordProperty("iterations", s.iterations);
  const HexapodCalibrationSummary plain = calibrateHexapod(nominal, data);
  RecordProperty("iterations_without_prior", plain.iterations);
  const double before = planarError(nominal, truth, test::kSeed + 6);
  const double after =
      planarError(withHexapodParameters(nominal, s.parameters), truth, test::kSeed + 6);
  const double after_plain =
      planarError(withHexapodParameters(nominal, plain.parameters), truth, test::kSeed + 6);
  RecordProperty("planar_error_before_mm", std::to_string(before));
  RecordProperty("planar_error_after_mm", std::to_string(after));
  RecordProperty("planar_error_after_without_prior_mm", std::to_string(after_plain));
  EXPECT_LT(after, (1.0 - kRemovedFraction) * before);
  EXPECT_LT(after, after_plain);  // the weak directions were fitting noise
  // The prior bounds every parameter's σ by σ_θ (the data can only shrink it).
  for (int k = 0; k < kHexapodParameters; ++k)
    EXPECT_LE(s.standard_deviation(k), kPriorSigma * (1.0 + test::kTolFiniteDiff))
        << hexapodParameterName(k);
  // The prior's weight needs the measurement σ.
  options.measurement_sigma = 0.0;
  EXPECT_THROW((void)calibrateHexapod(nominal, data, options), InvalidArgument);
  options.measurement_sigma = kReadingNoise;
  options.parameter_prior_sigma = -1.0;
  EXPECT_THROW((void)calibrateHexapod(nominal, data, options), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration

namespace pkm::calibration {
namespace PKM_TEST_NS {

TEST(ConstrainedMotion, ConvergesInAFewIterationsOnNoisyGauges) {
  // Two plate heights, strut readings with seed 004's repeatability (2 µm), gauges at 1 µm. The
  // gauges see some combinations only weakly: without a prior the fit crawls along them for all
  // its iterations (docs/calibration.md, "Weakly identified directions"); with the documented
  // prior it must stop at its noise floor in a few steps.
  constexpr int kMaxIterations = 12;  ///< LM iterations (rejected steps included)
  constexpr double kPriorSigma = 4 * kJointError;
  constexpr double kReadingNoise = 0.002;  ///< mm, strut repeatability
  constexpr double kGaugeNoise = 0.001;    ///< mm, dial gauge
  constexpr double kTolStationary = 1e-5;  ///< mm: default vs strict stopping rules
  const HexapodModel nominal = test::millingModel();
  const HexapodModel truth = perturbed(nominal, test::kSeed + 20);
  HexapodCalibrationData data;
  data.constrained.push_back(constrainedData(nominal, truth, 150.0, 40, test::kSeed + 21));
  data.constrained.push_back(constrainedData(nominal, truth, 250.0, 40, test::kSeed + 22));
  std::mt19937 rng(test::kSeed + 23);
  std::normal_distribution<double> n(0.0, 1.0);
  for (ConstrainedMotionData& set : data.constrained)
    for (GaugeStation& s : set.stations) {
      for (int i = 0; i < kinematics::kStruts; ++i) s.readings(i) += kReadingNoise * n(rng);
      for (double& g : s.gauges) g += kGaugeNoise * n(rng);
    }
  HexapodCalibrationOptions options;
  options.measurement_sigma = kReadingNoise;
  options.parameter_prior_sigma = kPriorSigma;
  const HexapodCalibrationSummary s = calibrateHexapod(nominal, data, options);
  EXPECT_TRUE(s.converged) << s.termination;
  EXPECT_LE(s.iterations, kMaxIterations) << s.termination;
  RecordProperty("iterations", s.iterations);
  HexapodCalibrationOptions strict = options;
  strict.function_tolerance = 1e-16;
  strict.gradient_tolerance = 1e-16;
  strict.parameter_tolerance = 1e-16;
  strict.max_iterations = 200;
  const HexapodCalibrationSummary tight = calibrateHexapod(nominal, data, strict);
  EXPECT_LT((tight.parameters - s.parameters).cwiseAbs().maxCoeff(), kTolStationary);
  const double before = planarError(nominal, truth, test::kSeed + 6);
  const double after =
      planarError(withHexapodParameters(nominal, s.parameters), truth, test::kSeed + 6);
  EXPECT_LT(after, (1.0 - kRemovedFraction) * before);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
