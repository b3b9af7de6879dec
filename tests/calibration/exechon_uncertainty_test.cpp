#include "pkm/calibration/exechon_uncertainty.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/simulation/exechon_tracker.hpp"
#include "pkm/simulation/hybrid_tripod_errors.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using kinematics::ExechonModel;

constexpr double kNoise = 0.005;   // mm: tracker noise per coordinate
constexpr int kObservations = 20;  // 60 equations for 18 unknowns
constexpr int kTrials = 30;
/// With 30 trials a sample std scatters by ~1/√(2·29) ≈ 13 % about the true std: a ratio outside
/// [0.5, 2] is a > 3.8σ event, not sampling noise.
constexpr double kRatioLow = 0.5;
constexpr double kRatioHigh = 2.0;
/// The mean ratio over parameters averages the scatter down (~2 %), leaving the nonlinearity.
constexpr double kMeanRatioTolerance = 0.2;
constexpr double kDeg = M_PI / 180.0;

ExechonModel nominal() { return io::loadExechonMachine("mxt700s-like").model; }

simulation::ExechonTripodErrors errors() {
  simulation::ExechonTripodErrors e;
  e.dA = 1.2;
  e.dB = -0.8;
  e.pA = 0.6;
  e.hz = -0.6;
  e.length_offset = Eigen::Vector3d(0.8, -1.1, 0.5);
  e.c0 = 0.8e-3;
  e.a0 = -0.6e-3;
  e.tool_length = 0.3;
  return e;
}

simulation::ExechonTrackerSetup setup(int count, const std::string& name) {
  simulation::ExechonTrackerSetup s;
  s.name = name;
  s.count = count;
  s.box_min = Eigen::Vector3d(-300, -300, -100);
  s.box_max = Eigen::Vector3d(300, 300, 300);
  s.max_tilt = 30 * kDeg;
  s.smr_offset = Eigen::Vector3d(40, 0, 20);
  s.noise.range_sigma = kNoise;
  s.noise.angle_sigma = kNoise / 2000.0;  // about kNoise at 2 m
  return s;
}

/// A small world-frame calibration (base placement known) and its estimate.
struct Problem {
  ExechonModel initial = nominal();
  ExechonCalibrationData data;
  ExechonCalibrationOptions options;
  ExechonCalibrationSummary fit;
  ExechonModel estimate;
  std::vector<kinematics::ExechonJoints> workspace;
  Problem() {
    const ExechonModel truth = simulation::perturbedExechon(initial, errors());
    const auto s = setup(kObservations, "mc-fit");
    simulation::RandomStream rng(test::kSeed, s.name);
    const auto readings = simulation::simulateExechonTracker(initial, truth, {}, s, rng);
    data.target_offset = s.smr_offset;
    for (const auto& r : readings) {
      ExechonObservation o;
      o.joints = r.joints;
      o.point = r.measured;  // world_T_tracker is the identity: world data
      data.observations.push_back(o);
    }
    for (int k = kExechonBaseParameter; k < kExechonParameters; ++k)
      options.free[static_cast<std::size_t>(k)] = false;
    options.measurement_sigma = kNoise;  // the linearised covariance for the simulated noise
    fit = calibrateExechon(initial, data, options);
    estimate = withExechonParameters(initial, fit.parameters, initial.world_T_zoppi);
    const auto w = setup(8, "mc-workspace");
    simulation::RandomStream wrng(test::kSeed, w.name);
    for (const auto& r : simulation::simulateExechonTracker(initial, truth, {}, w, wrng))
      workspace.push_back(r.joints);
  }
  [[nodiscard]] ExechonMonteCarloSummary run(int trials, int threads) const {
    ExechonMonteCarloOptions mc;
    mc.trials = trials;
    mc.threads = threads;
    mc.seed = test::kSeed;
    mc.position_sigma = kNoise;
    return monteCarloExechon(initial, data, estimate, std::nullopt, workspace, options, mc);
  }
};

const Problem& problem() {
  static const Problem p;
  return p;
}

TEST(ExechonMonteCarlo, ParameterSpreadAgreesWithTheLinearisedCovariance) {
  const Problem& p = problem();
  ASSERT_EQ(p.fit.identifiability.rank, p.fit.identifiability.parameters);
  const ExechonMonteCarloSummary mc = p.run(kTrials, 2);
  EXPECT_EQ(mc.trials, kTrials);
  EXPECT_EQ(mc.failures, 0);
  EXPECT_EQ(mc.not_converged, 0);
  double sum = 0.0, lowest = kRatioHigh, highest = 0.0;
  int free = 0;
  for (int k = 0; k < kExechonParameters; ++k) {
    if (!p.options.free[static_cast<std::size_t>(k)]) {
      EXPECT_EQ(mc.standard_deviation(k), 0.0) << exechonParameterName(k);
      continue;
    }
    const double ratio = mc.standard_deviation(k) / p.fit.standard_deviation(k);
    EXPECT_GT(ratio, kRatioLow) << exechonParameterName(k);
    EXPECT_LT(ratio, kRatioHigh) << exechonParameterName(k);
    sum += ratio;
    lowest = std::min(lowest, ratio);
    highest = std::max(highest, ratio);
    ++free;
  }
  EXPECT_NEAR(sum / free, 1.0, kMeanRatioTolerance);
  RecordProperty("mean_std_ratio", std::to_string(sum / free));
  RecordProperty("min_std_ratio", std::to_string(lowest));
  RecordProperty("max_std_ratio", std::to_string(highest));
  // The per-configuration tool-point spread against the linearised √trace(J·Σ·Jᵀ).
  ASSERT_EQ(mc.configurations, static_cast<int>(p.workspace.size()));
  std::vector<double> linear;
  for (const auto& q : p.workspace) {
    const auto u = exechonTargetUncertainty(
        p.estimate, p.fit.covariance, q, Eigen::Vector3d::Zero(), p.estimate.home);
    ASSERT_TRUE(u.has_value());
    linear.push_back(*u);
  }
  const TcpErrorStatistics lin = tcpErrorStatistics(linear);
  EXPECT_EQ(mc.tool_sigma.samples, mc.configurations);
  EXPECT_NEAR(mc.tool_sigma.mean / lin.mean, 1.0, kMeanRatioTolerance);
  RecordProperty("tool_sigma_mean_mm", std::to_string(mc.tool_sigma.mean));
  RecordProperty("linearised_tool_sigma_mean_mm", std::to_string(lin.mean));
  RecordProperty("seconds", std::to_string(mc.seconds));
  EXPECT_EQ(mc.tcp.samples, kTrials * mc.configurations);
  // A 3-D deviation's RMS is the 3-D spread; its mean is smaller (χ₃: mean/RMS ≈ 0.92).
  EXPECT_GT(mc.tcp.mean, kRatioLow * mc.tool_sigma.mean);
  EXPECT_LT(mc.tcp.mean, mc.tool_sigma.mean * kRatioHigh);
  EXPECT_LE(mc.tcp.p95, mc.tcp.max);
  EXPECT_GT(mc.seconds, 0.0);
}

TEST(ExechonMonteCarlo, DoesNotDependOnTheThreadCount) {
  const Problem& p = problem();
  constexpr int kFew = 2;
  const ExechonMonteCarloSummary one = p.run(kFew, 1);
  const ExechonMonteCarloSummary two = p.run(kFew, 2);
  EXPECT_EQ(one.trials, two.trials);
  for (int k = 0; k < kExechonParameters; ++k) {
    EXPECT_EQ(one.mean(k), two.mean(k)) << exechonParameterName(k);
    EXPECT_EQ(one.standard_deviation(k), two.standard_deviation(k)) << exechonParameterName(k);
  }
  EXPECT_EQ(one.tcp.mean, two.tcp.mean);
  EXPECT_EQ(one.tool_sigma.max, two.tool_sigma.max);
  EXPECT_GT(one.standard_deviation(0), 0.0);
}

TEST(ExechonMonteCarlo, RefusesBadOptions) {
  const Problem& p = problem();
  ExechonMonteCarloOptions mc;
  mc.position_sigma = kNoise;
  const auto run = [&](const ExechonMonteCarloOptions& o) {
    return monteCarloExechon(
        p.initial, p.data, p.estimate, std::nullopt, p.workspace, p.options, o);
  };
  ExechonMonteCarloOptions bad = mc;
  bad.trials = 1;
  EXPECT_THROW((void)run(bad), InvalidArgument);
  bad = mc;
  bad.threads = -1;
  EXPECT_THROW((void)run(bad), InvalidArgument);
  bad = mc;
  bad.position_sigma = 0.0;
  EXPECT_THROW((void)run(bad), InvalidArgument);
  bad = mc;
  bad.direction_sigma = std::nan("");
  EXPECT_THROW((void)run(bad), InvalidArgument);
  // A frame without a measurement frame in the data.
  EXPECT_THROW((void)monteCarloExechon(p.initial,
                                       p.data,
                                       p.estimate,
                                       geometry::RigidTransform::Identity(),
                                       p.workspace,
                                       p.options,
                                       mc),
               InvalidArgument);
  ExechonCalibrationOptions calibration = p.options;
  calibration.max_iterations = 0;
  EXPECT_THROW((void)monteCarloExechon(
                   p.initial, p.data, p.estimate, std::nullopt, p.workspace, calibration, mc),
               InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
