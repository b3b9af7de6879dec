#include "pkm/calibration/uncertainty.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using kinematics::HexapodData;
using kinematics::HexapodModel;

constexpr double kSigma = 0.005;  ///< mm, simulated tracker position noise
constexpr int kTrials = 24;       ///< Monte Carlo trials in the test
/// Monte Carlo and linearised covariance agree within sampling error: the standard deviation of a
/// 24-sample standard deviation is ~15 %, averaged over 42 parameters ~3 %; allow 20 %.
constexpr double kSpreadRatioTolerance = 0.2;

std::vector<kinematics::PoseRpy> poses(const HexapodModel& m, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<kinematics::PoseRpy> out;
  for (int k = 0; k < count; ++k) out.push_back(test::randomPose(rng, m.home, 120.0, 0.12));
  return out;
}

TEST(TcpErrorStatistics, NearestRankPercentile) {
  std::vector<double> e;
  for (int k = 20; k >= 1; --k) e.push_back(k);
  const TcpErrorStatistics s = tcpErrorStatistics(e);
  EXPECT_EQ(s.samples, 20);
  EXPECT_DOUBLE_EQ(s.mean, 10.5);
  EXPECT_DOUBLE_EQ(s.p95, 19.0);
  EXPECT_DOUBLE_EQ(s.max, 20.0);
  EXPECT_EQ(tcpErrorStatistics({}).samples, 0);
  EXPECT_THROW((void)tcpErrorStatistics({1.0, std::nan("")}), InvalidArgument);
}

TEST(TcpErrorOverWorkspace, ShiftedBaseMovesEveryTcpByTheShift) {
  const HexapodModel controller = test::millingModel();
  HexapodModel truth = controller;
  for (auto& s : truth.struts) s.world_p_base.z() += 0.3;  // the whole base 0.3 mm higher
  const auto ws = poses(controller, 30, test::kSeed);
  const TcpErrorStatistics same = tcpErrorOverWorkspace(controller, controller, ws);
  EXPECT_EQ(same.samples, 30);
  EXPECT_LT(same.max, test::kTolRoundTrip);
  const TcpErrorStatistics shifted = tcpErrorOverWorkspace(controller, truth, ws);
  EXPECT_NEAR(shifted.mean, 0.3, test::kTolRoundTrip);
  EXPECT_NEAR(shifted.max, 0.3, test::kTolRoundTrip);
}

TEST(MonteCarlo, AgreesWithTheLinearisedCovarianceAndIsThreadIndependent) {
  const HexapodModel nominal = test::millingModel();
  HexapodParameterVector p = hexapodParameters(nominal);
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int k = 0; k < kHexapodParameters; ++k) p(k) += u(rng);
  const HexapodModel truth = withHexapodParameters(nominal, p);
  HexapodCalibrationData data;
  HexapodData work(truth);
  for (const auto& pose : poses(truth, 80, test::kSeed + 1)) {
    PoseObservation o;
    o.readings = kinematics::inverseKinematics(truth, work, pose);
    o.pose = pose;
    data.poses.push_back(o);
  }
  HexapodCalibrationOptions calibration;
  calibration.measurement_sigma = kSigma;
  const HexapodCalibrationSummary fit = calibrateHexapod(nominal, data, calibration);
  const HexapodModel estimate = withHexapodParameters(nominal, fit.parameters);
  MonteCarloOptions mc;
  mc.trials = kTrials;
  mc.position_sigma = kSigma;
  mc.threads = 2;
  int last_done = -1, calls = 0;
  mc.progress = [&](int finished, int total) {
    EXPECT_EQ(total, kTrials);
    EXPECT_GE(finished, last_done);
    last_done = finished;
    ++calls;
  };
  const auto ws = poses(nominal, 40, test::kSeed + 2);
  const MonteCarloSummary a =
      monteCarloHexapod(nominal, data, estimate, std::nullopt, ws, calibration, mc);
  EXPECT_EQ(a.trials, kTrials);
  EXPECT_EQ(a.failures, 0);
  EXPECT_EQ(last_done, kTrials);
  EXPECT_GE(calls, 1);
  // Position noise only: the covariance of calibrateHexapod with σ on every IK residual is the
  // linearised counterpart; compare the mean ratio of standard deviations.
  double ratio = 0.0;
  for (int k = 0; k < kHexapodParameters; ++k)
    ratio += a.standard_deviation(k) / fit.standard_deviation(k);
  ratio /= kHexapodParameters;
  RecordProperty("spread_ratio", std::to_string(ratio));
  RecordProperty("tcp_p95_mm", std::to_string(a.tcp.p95));
  EXPECT_NEAR(ratio, 1.0, kSpreadRatioTolerance);
  EXPECT_GT(a.tcp.max, 0.0);
  EXPECT_LT(a.tcp.p95, 3 * kSigma);
  // One thread gives bitwise the same result.
  mc.threads = 1;
  mc.progress = nullptr;
  const MonteCarloSummary b =
      monteCarloHexapod(nominal, data, estimate, std::nullopt, ws, calibration, mc);
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_EQ(a.standard_deviation, b.standard_deviation);
  mc.trials = 1;
  EXPECT_THROW((void)monteCarloHexapod(nominal, data, estimate, std::nullopt, ws, calibration, mc),
               InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
