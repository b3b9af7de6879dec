// workflow::validateCoverage (workflow/coverage.hpp): the statistics on constructed trials, the
// perfect-instrument truth of a short run, and the outputs.
#include "pkm/workflow/coverage.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "pkm/core/error.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/uncertainty_sources.hpp"
#include "pkm/simulation/environment.hpp"
#include "support/tolerances.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// A quantity whose errors are −2, −1, 0, 1, 2 with U = 1.5 and u_c = 1 (three of five covered).
CoverageQuantity constructed() {
  CoverageQuantity q{"s", "g", "E", "mm", "perfect instrument", {}};
  for (int k = -2; k <= 2; ++k)
    q.trials.push_back({static_cast<std::uint64_t>(k + 3), 10.0 + k, 10.0, 1.5, 1.0, 1.5});
  return q;
}

TEST(Coverage, StatisticsOfConstructedTrials) {
  const CoverageQuantity q = constructed();
  EXPECT_NEAR(q.coverage(), 0.6, test::kTolExact);
  EXPECT_NEAR(q.bias(), 0.0, test::kTolExact);
  EXPECT_NEAR(q.errorRms(), std::sqrt(2.0), test::kTolExact);
  EXPECT_NEAR(q.meanU(), 1.5, test::kTolExact);
  EXPECT_NEAR(q.meanZ(), 0.0, test::kTolExact);
  EXPECT_NEAR(q.spreadZ(), std::sqrt(10.0 / 4.0), test::kTolExact);
  EXPECT_FALSE(q.holds());
  EXPECT_FALSE(q.wide());
  CoverageQuantity wide = q;
  for (CoverageTrial& t : wide.trials) t.U = 5.0;
  EXPECT_TRUE(wide.holds());
  EXPECT_TRUE(wide.wide());  // 5 > 3 √2
}

TEST(Coverage, AcceptableCoverageIsNinetyTwoPercentAtTwoHundredSeeds) {
  CoverageQuantity q = constructed();
  q.trials.resize(200, q.trials.front());
  // 0.95 − 2 √(0.95 · 0.05 / 200) = 0.9192
  EXPECT_NEAR(q.acceptableCoverage(), 0.95 - 2.0 * std::sqrt(0.0475 / 200.0), test::kTolExact);
  EXPECT_GT(q.acceptableCoverage(), 0.919);
}

TEST(Coverage, ShortRunComparesWithThePerfectInstrument) {
  CoverageOptions o;
  o.scenarios = {"seed001-diagonals"};
  o.seeds = 3;
  o.only = {"linear-x "};
  const CoverageResult r = validateCoverage(o);
  ASSERT_EQ(r.quantities.size(), 5u);  // E, M, A, B, R of linear-x
  for (const CoverageQuantity& q : r.quantities) {
    EXPECT_EQ(q.group, "linear-x");
    EXPECT_EQ(q.truth_kind, "perfect instrument");
    ASSERT_EQ(q.trials.size(), 3u);
    for (const CoverageTrial& t : q.trials) {
      EXPECT_GT(t.U, 0.0) << q.quantity;
      EXPECT_TRUE(std::isfinite(t.truth)) << q.quantity;
    }
  }
  // The perfect instrument changes the reading of E, not the machine: the true E is the same
  // machine's, so it is close to the measured one (the XL-80's noise is a few tenths of a µm).
  const CoverageQuantity& E = r.quantities.front();
  EXPECT_EQ(E.quantity, "E");
  constexpr double kNoiseBound = 5e-3;  // mm: far above the instrument's noise, far below E
  for (const CoverageTrial& t : E.trials) EXPECT_NEAR(t.value, t.truth, kNoiseBound);
  EXPECT_THAT(coverageText(r), HasSubstr("linear-x\tE\t3\t"));
  const auto j = nlohmann::json::parse(coverageJson(r));
  EXPECT_EQ(j["schema"], "pkm.coverage/1");
  EXPECT_EQ(j["quantities"].size(), 5u);
  EXPECT_EQ(j["quantities"][0]["trials"].size(), 3u);
}

TEST(Coverage, CalibrationsAreComparedWithTheTrueGeometry) {
  // The hexapod scenario's tracker and dial-gauge calibrations: every parameter against the
  // virtual machine's true one, the TCP at each held-out pose against the predicted U.
  CoverageOptions o;
  o.scenarios = {"seed004-hexapod-calibration"};
  o.seeds = 3;
  o.only = {"calibration "};
  const CoverageResult r = validateCoverage(o);
  constexpr std::size_t kFits = 2, kParameters = 42, kHeldOut = 50;
  ASSERT_EQ(r.quantities.size(), kFits * (kParameters + 1));
  std::size_t covered = 0, parameter_trials = 0;
  for (const CoverageQuantity& q : r.quantities) {
    EXPECT_EQ(q.truth_kind, "true geometry") << q.quantity;
    EXPECT_TRUE(q.claimed());
    const bool tcp = q.quantity == "TCP error at the held-out poses";
    EXPECT_EQ(q.trials.size(), tcp ? 3 * kHeldOut * 3 : 3u) << q.group << " " << q.quantity;
    if (tcp) {
      EXPECT_TRUE(q.holds()) << q.group << " " << q.coverage();
      continue;
    }
    for (const CoverageTrial& t : q.trials) covered += t.covered() ? 1 : 0;
    parameter_trials += q.trials.size();
  }
  // Three seeds are too few to judge one parameter (the 200-seed figures are in docs); the 252
  // (parameter, seed) pairs together must reach the 92 % a 200-seed row must.
  EXPECT_GE(static_cast<double>(covered), 0.92 * static_cast<double>(parameter_trials));
  // The gauges do not see the base's placement in x and y: there the estimate is the machine
  // file's, 12 mm off the truth, and only the prior's stated 20 mm covers it.
  for (const CoverageQuantity& q : r.quantities)
    if (q.group == "calibration constrained-motion" && q.quantity == "base0.x") {
      EXPECT_GT(std::abs(q.bias()), 5.0);
      EXPECT_GT(q.meanU(), std::abs(q.bias()));
    }
}

TEST(Coverage, TheExechonCalibrationIsComparedWithTheTrueTripod) {
  CoverageOptions o;
  o.scenarios = {"exechon-calibration"};
  o.seeds = 2;
  const CoverageResult r = validateCoverage(o);
  // 14 tripod dimensions, 3 leg offsets, 3 wrist parameters, the tool point, and the hybrid
  // machine's four squareness errors.
  ASSERT_EQ(r.quantities.size(), 25u);
  std::size_t covered = 0;
  for (const CoverageQuantity& q : r.quantities) {
    EXPECT_EQ(q.truth_kind, "true geometry");
    if (q.group == "calibration hybrid squareness") {
      // With the calibrated tripod's own uncertainty carried into u (σ of the fit alone covered
      // 1 of 4 at 10 seeds: 0–20 % for sxP, syP, szP).
      for (const CoverageTrial& t : q.trials) EXPECT_TRUE(t.covered()) << q.quantity;
      continue;
    }
    EXPECT_EQ(q.group, "calibration exechon tracker");
    if (q.quantity == "tool point at the held-out poses") {
      EXPECT_EQ(q.trials.size(), 2u * 50u * 3u);
      EXPECT_TRUE(q.holds());
      continue;
    }
    for (const CoverageTrial& t : q.trials) covered += t.covered() ? 1 : 0;
  }
  EXPECT_GE(covered, 38u);  // of 40 (parameter, seed) pairs: 95 %
}

TEST(Coverage, TheRealisticWorkshopsStatedScrewsAndWeightsCoverTheTripod) {
  // The realistic workshop's lead errors and the head's weight bend the Exechon calibration's
  // parameters (their own tool length by −192 µm in every seed); stated in the sources file
  // (data/uncertainty/realistic-workshop.json) they enter the budgets. Three seeds: every
  // parameter and squareness trial covered (the 200-seed figures, 95.5–100 %, are in
  // docs/coverage.md). Without the statement, the tool length is missed in every seed.
  CoverageOptions o;
  o.scenarios = {"exechon-calibration"};
  o.seeds = 3;
  o.environment = simulation::environmentPreset("realistic");
  o.environment_source = "realistic";
  o.uncertainty = io::readUncertaintySources(
      io::readNamedText(std::string(PKM_SOURCE_DIR) + "/data/uncertainty/realistic-workshop.json"));
  const CoverageResult stated = validateCoverage(o);
  ASSERT_EQ(stated.quantities.size(), 25u);
  for (const CoverageQuantity& q : stated.quantities)
    for (const CoverageTrial& t : q.trials) EXPECT_TRUE(t.covered()) << q.quantity;
  o.uncertainty = {};
  o.only = {"tool_length"};
  const CoverageResult typical = validateCoverage(o);
  ASSERT_EQ(typical.quantities.size(), 1u);
  EXPECT_EQ(typical.quantities.front().coverage(), 0.0);
}

TEST(Coverage, SquarenessIsAlsoComparedWithTheInjectedOne) {
  CoverageOptions o;
  o.scenarios = {"seed001-diagonals"};
  o.seeds = 2;
  o.only = {"body diagonals squareness_xy"};
  const CoverageResult r = validateCoverage(o);
  ASSERT_EQ(r.quantities.size(), 2u);
  EXPECT_EQ(r.quantities[0].quantity, "squareness_xy");
  EXPECT_EQ(r.quantities[1].quantity, "squareness_xy vs injected");
  EXPECT_EQ(r.quantities[1].truth_kind, "injected");
  EXPECT_TRUE(r.quantities[0].claimed());
  EXPECT_FALSE(r.quantities[1].claimed());  // the method's bias, not a claim of U
  EXPECT_EQ(r.claims(), 1u);
  constexpr double kInjectedXy = 50e-6;  // rad, data/scenarios/seed001-diagonals.json
  EXPECT_NEAR(r.quantities[1].trials[0].truth, kInjectedXy, test::kTolExact);
}

TEST(Coverage, RejectsFewSeedsAndWritesOnlyWithForce) {
  CoverageOptions o;
  o.seeds = 1;
  EXPECT_THROW(o.validate(), InvalidArgument);
  const CoverageResult r{.seeds = 2, .quantities = {constructed()}};
  const auto dir = std::filesystem::temp_directory_path() / "pkm-coverage-test";
  std::filesystem::remove_all(dir);
  writeCoverage(r, dir, false);
  EXPECT_TRUE(std::filesystem::exists(dir / "coverage.json"));
  EXPECT_TRUE(std::filesystem::exists(dir / "report.html"));
  EXPECT_THROW(writeCoverage(r, dir, false), IoError);
  writeCoverage(r, dir, true);
  std::filesystem::remove_all(dir);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
