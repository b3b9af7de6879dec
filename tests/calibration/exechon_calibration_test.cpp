#include "pkm/calibration/exechon_calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/simulation/exechon_tracker.hpp"
#include "pkm/simulation/hybrid_tripod_errors.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using kinematics::ExechonModel;

constexpr double kExactFit = 1e-6;      // mm: noise-free data, after the fit
constexpr double kNoise = 0.005;        // mm: tracker noise per axis in the noisy tests
constexpr double kHeldOutFactor = 3.0;  // acceptance: held-out error <= 3 x the measurement noise
constexpr double kOutlier = 2.0;        // mm added to one observation
constexpr double kDeg = M_PI / 180.0;

ExechonModel nominal() { return io::loadExechonMachine("mxt700s-like").model; }

simulation::ExechonTripodErrors errors() {
  simulation::ExechonTripodErrors e;
  e.dA = 1.2;
  e.dB = -0.8;
  e.dC = 0.9;
  e.l12A = 0.4;
  e.l12C = -0.5;
  e.pA = 0.6;
  e.pB = -0.7;
  e.pC = 0.3;
  e.hA = 0.25;
  e.hC = -0.35;
  e.hx = 0.2;
  e.hz = -0.6;
  e.length_offset = Eigen::Vector3d(0.8, -1.1, 0.5);
  e.c0 = 0.8e-3;
  e.a0 = -0.6e-3;
  e.tool_length = 0.3;
  return e;
}

simulation::ExechonTrackerSetup setup(int count, double sigma, const std::string& name) {
  simulation::ExechonTrackerSetup s;
  s.name = name;
  s.count = count;
  s.box_min = Eigen::Vector3d(-300, -300, -100);
  s.box_max = Eigen::Vector3d(300, 300, 300);
  s.max_tilt = 30 * kDeg;
  s.smr_offset = Eigen::Vector3d(40, 0, 20);
  s.noise.range_sigma = sigma;
  s.noise.angle_sigma = sigma / 2000.0;  // about sigma at 2 m
  s.world_T_tracker.translation() = Eigen::Vector3d(1200, -1500, 400);
  s.world_T_tracker.linear() = Eigen::AngleAxisd(2.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return s;
}

/// Tracker readings as calibration data; in world coordinates unless `tracker_frame`.
ExechonCalibrationData toData(const std::vector<simulation::ExechonTrackerReading>& readings,
                              const simulation::ExechonTrackerSetup& s,
                              bool tracker_frame) {
  ExechonCalibrationData d;
  d.target_offset = s.smr_offset;
  for (std::size_t k = 0; k < readings.size(); ++k) {
    ExechonObservation o;
    o.joints = readings[k].joints;
    o.point = tracker_frame ? readings[k].measured
                            : Eigen::Vector3d(s.world_T_tracker * readings[k].measured);
    o.source = "sim.csv:" + std::to_string(k + 2);
    d.observations.push_back(o);
  }
  return d;
}

struct Fixture {
  ExechonModel nominal_model = nominal();
  ExechonModel true_model = simulation::perturbedExechon(nominal_model, errors());
  std::vector<simulation::ExechonTrackerReading> simulate(
      const simulation::ExechonTrackerSetup& s) {
    simulation::RandomStream rng(test::kSeed, s.name);
    return simulation::simulateExechonTracker(nominal_model, true_model, {}, s, rng);
  }
};

/// Max error of the estimated model's target prediction vs the truth over `readings` (world).
double heldOutError(const ExechonModel& estimated,
                    const std::vector<simulation::ExechonTrackerReading>& readings,
                    const simulation::ExechonTrackerSetup& s) {
  double worst = 0.0;
  for (const auto& r : readings) {
    const auto p = exechonTarget(estimated, r.joints, s.smr_offset, estimated.home);
    EXPECT_TRUE(p.has_value());
    if (p) worst = std::max(worst, (*p - s.world_T_tracker * r.truth).norm());
  }
  return worst;
}

TEST(ExechonCalibration, RecoversTheTruthFromExactWorldData) {
  Fixture f;
  const auto s = setup(80, 0.0, "fit");
  const ExechonCalibrationData data = toData(f.simulate(s), s, false);
  ExechonCalibrationOptions options;
  for (int k = kExechonBaseParameter; k < kExechonParameters; ++k)
    options.free[static_cast<std::size_t>(k)] = false;  // world data: the base placement is known
  const ExechonCalibrationSummary sum = calibrateExechon(f.nominal_model, data, options);
  EXPECT_GT(sum.before.rms, 0.5);
  EXPECT_LT(sum.after.max, kExactFit);
  EXPECT_TRUE(sum.warnings.empty());
  EXPECT_TRUE(sum.large_changes.empty());
  const ExechonModel est =
      withExechonParameters(f.nominal_model, sum.parameters, f.nominal_model.world_T_zoppi);
  const auto hold = setup(30, 0.0, "holdout");
  EXPECT_LT(heldOutError(est, f.simulate(hold), hold), kExactFit * 10);
  // Every identifiable parameter combination is recovered; report what is not.
  EXPECT_EQ(sum.identifiability.parameters, kExechonBaseParameter);
  EXPECT_EQ(sum.identifiability.rank + static_cast<int>(sum.identifiability.combinations.size()),
            kExechonBaseParameter);
}

TEST(ExechonCalibration, NoisyTrackerFrameDataMeetsTheHeldOutTarget) {
  Fixture f;
  const auto s = setup(200, kNoise, "fit-noisy");
  ExechonCalibrationData data = toData(f.simulate(s), s, true);
  data.measurement_frame = initialExechonMeasurementFrame(f.nominal_model, data);
  const ExechonCalibrationSummary sum = calibrateExechon(f.nominal_model, data);
  ASSERT_TRUE(sum.measurement_frame.has_value());
  // The base placement and the tracker frame are one rigid motion apart: 6 directions unseen.
  EXPECT_GE(static_cast<int>(sum.identifiability.combinations.size()), 6);
  EXPECT_LT(sum.after.rms, 2.0 * kNoise);
  const ExechonModel est =
      withExechonParameters(f.nominal_model, sum.parameters, f.nominal_model.world_T_zoppi);
  // Compare in the estimated frame: map the truth into it through the estimated tracker frame.
  const auto hold = setup(50, kNoise, "holdout-noisy");
  const auto readings = f.simulate(hold);
  double worst = 0.0;
  for (const auto& r : readings) {
    const auto p = exechonTarget(est, r.joints, hold.smr_offset, est.home);
    ASSERT_TRUE(p.has_value());
    const Eigen::Vector3d measured_in_world =
        sum.measurement_frame->linear() * r.truth + sum.measurement_frame->translation();
    worst = std::max(worst, (*p - measured_in_world).norm());
  }
  EXPECT_LT(worst, kHeldOutFactor * kNoise * std::sqrt(3.0));
  EXPECT_GT(sum.standard_deviation(0), 0.0);
  // The linearised target uncertainty is positive, below the noise-free scale of the errors, and
  // zero for a zero covariance.
  const auto u =
      exechonTargetUncertainty(est, sum.covariance, readings[0].joints, hold.smr_offset, est.home);
  ASSERT_TRUE(u.has_value());
  EXPECT_GT(*u, 0.0);
  EXPECT_LT(*u, 0.5);
  const auto zero =
      exechonTargetUncertainty(est,
                               Eigen::MatrixXd::Zero(kExechonParameters, kExechonParameters),
                               readings[0].joints,
                               hold.smr_offset,
                               est.home);
  ASSERT_TRUE(zero.has_value());
  EXPECT_EQ(*zero, 0.0);
  EXPECT_THROW((void)exechonTargetUncertainty(
                   est, Eigen::MatrixXd::Zero(3, 3), readings[0].joints, hold.smr_offset, est.home),
               InvalidArgument);
}

TEST(ExechonCalibration, CauchyLossSurvivesAnOutlierAndNamesIt) {
  Fixture f;
  const auto s = setup(80, 0.002, "fit-outlier");
  ExechonCalibrationData data = toData(f.simulate(s), s, false);
  data.observations[17].point.x() += kOutlier;
  ExechonCalibrationOptions options;
  for (int k = kExechonBaseParameter; k < kExechonParameters; ++k)
    options.free[static_cast<std::size_t>(k)] = false;
  options.loss = RobustLoss::kCauchy;
  options.loss_scale = 0.01;
  const ExechonCalibrationSummary sum = calibrateExechon(f.nominal_model, data, options);
  ASSERT_FALSE(sum.worst.empty());
  EXPECT_EQ(sum.worst.front().index, 17u);
  EXPECT_EQ(sum.worst.front().source, "sim.csv:19");
  EXPECT_NEAR(sum.worst.front().residual, kOutlier, 0.05);
  const ExechonModel est =
      withExechonParameters(f.nominal_model, sum.parameters, f.nominal_model.world_T_zoppi);
  const auto hold = setup(30, 0.0, "holdout");
  EXPECT_LT(heldOutError(est, f.simulate(hold), hold), 0.02);
}

TEST(ExechonCalibration, DiagnosesBadData) {
  Fixture f;
  const auto s = setup(20, 0.0, "bad");
  ExechonCalibrationData data = toData(f.simulate(s), s, false);
  // Too few observations for the unknowns.
  ExechonCalibrationData few = data;
  few.observations.resize(4);
  EXPECT_THROW((void)calibrateExechon(f.nominal_model, few), InvalidArgument);
  // Leg readings in inches instead of mm: flagged as implausible, never silently accepted.
  ExechonCalibrationData inches = data;
  for (auto& o : inches.observations) o.joints.readings /= 25.4;
  try {
    const ExechonCalibrationSummary sum = calibrateExechon(f.nominal_model, inches);
    EXPECT_FALSE(sum.large_changes.empty() && sum.warnings.empty());
    if (!sum.warnings.empty())
      EXPECT_NE(sum.warnings.front().find("units"), std::string::npos) << sum.warnings.front();
  } catch (const InvalidArgument& e) {  // or refused outright when the model cannot assemble
    EXPECT_NE(std::string(e.what()).find("units"), std::string::npos) << e.what();
  }
  // Wrist angles given in degrees where radians are expected: the model cannot assemble or the
  // fit is implausible.
  ExechonCalibrationData degrees = data;
  for (auto& o : degrees.observations) o.joints.a *= 180.0 / M_PI;
  try {
    const ExechonCalibrationSummary sum = calibrateExechon(f.nominal_model, degrees);
    EXPECT_FALSE(sum.large_changes.empty() && sum.warnings.empty());
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("units"), std::string::npos) << e.what();
  }
  // A non-unit direction names its source.
  ExechonCalibrationData dir = data;
  dir.observations[2].direction = Eigen::Vector3d(0, 0, 2);
  try {
    (void)calibrateExechon(f.nominal_model, dir);
    ADD_FAILURE() << "expected an error";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("sim.csv:4"), std::string::npos) << e.what();
  }
}

TEST(ExechonCalibration, DirectionsAddEquationsAndAgree) {
  Fixture f;
  const auto s = setup(40, 0.0, "dir");
  const auto readings = f.simulate(s);
  ExechonCalibrationData data = toData(readings, s, false);
  kinematics::ExechonData work(f.true_model);
  for (std::size_t k = 0; k < readings.size(); ++k) {
    ASSERT_TRUE(
        kinematics::toolForwardKinematics(f.true_model, work, readings[k].joints, f.true_model.home)
            .ok());
    data.observations[k].direction = work.world_u_tool;
  }
  EXPECT_EQ(data.equations(), 6u * readings.size());
  ExechonCalibrationOptions options;
  for (int k = kExechonBaseParameter; k < kExechonParameters; ++k)
    options.free[static_cast<std::size_t>(k)] = false;
  const ExechonCalibrationSummary sum = calibrateExechon(f.nominal_model, data, options);
  EXPECT_LT(sum.after.max, kExactFit);
  EXPECT_LT(sum.final_cost, 1e-10);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration

namespace pkm::calibration {
namespace PKM_TEST_NS {

TEST(ExechonCalibration, ConvergesInAFewIterationsOnNoisyTrackerData) {
  // Tracker points in the tracker's frame (5 µm), the frame estimated with the 26 parameters, the
  // Jacobian by central differences through the FK: the stopping rules must be reachable at the
  // floor those set, not only on exact data.
  constexpr int kMaxIterations = 15;       ///< LM iterations (rejected steps included)
  constexpr double kTolStationary = 1e-6;  ///< mm / rad: default vs strict stopping rules
  Fixture f;
  const auto s = setup(200, kNoise, "fit-convergence");
  ExechonCalibrationData data = toData(f.simulate(s), s, true);
  data.measurement_frame = initialExechonMeasurementFrame(f.nominal_model, data);
  const ExechonCalibrationSummary sum = calibrateExechon(f.nominal_model, data);
  EXPECT_TRUE(sum.converged) << sum.termination;
  EXPECT_LE(sum.iterations, kMaxIterations) << sum.termination;
  RecordProperty("iterations", sum.iterations);
  EXPECT_NEAR(sum.after.rms, kNoise, 0.3 * kNoise);
  // Stationary: stopping rules far below the noise floor find the same minimum.
  ExechonCalibrationOptions strict;
  strict.function_tolerance = 1e-16;
  strict.gradient_tolerance = 1e-16;
  strict.parameter_tolerance = 1e-16;
  strict.max_iterations = 200;
  const ExechonCalibrationSummary tight = calibrateExechon(f.nominal_model, data, strict);
  EXPECT_LT((tight.parameters - sum.parameters).cwiseAbs().maxCoeff(), kTolStationary);
  EXPECT_NEAR(tight.after.rms, sum.after.rms, 1e-6 * sum.after.rms);
  ExechonCalibrationOptions bad;
  bad.parameter_tolerance = -1.0;
  EXPECT_THROW((void)calibrateExechon(f.nominal_model, data, bad), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
