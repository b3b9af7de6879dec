// Uncertainty budgets of ISO 230-2 results (metrology/positioning_uncertainty.hpp).
#include "pkm/metrology/positioning_uncertainty.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

constexpr double kTolBudget = 1e-12;  // mm: the same arithmetic in a different order

// Five targets 0..400 mm, five runs per direction; the up means rise 2 µm per 100 mm, the down
// means are 3 µm lower (reversal), the runs scatter by ±(0, 0.5, −0.5, 1, −1) µm.
std::vector<PositioningSample> cycle(bool both_directions = true) {
  const double scatter[] = {0.0, 0.5e-3, -0.5e-3, 1e-3, -1e-3};
  std::vector<PositioningSample> out;
  for (int i = 0; i < 5; ++i) {
    const double target = 100.0 * i;
    for (int run = 1; run <= 5; ++run) {
      const double up = 2e-3 * i + scatter[run - 1];
      out.push_back({target, 1, run, target + up});
      if (both_directions) out.push_back({target, -1, run, target + up - 3e-3});
    }
  }
  return out;
}

const UncertaintyContributor* find(const UncertaintyBudget& b, const std::string& name) {
  for (const UncertaintyContributor& c : b.contributors)
    if (c.name == name) return &c;
  return nullptr;
}

TEST(PositioningUncertainty, BudgetsOfEMABR) {
  const Iso230_2Result r = evaluateIso230_2(cycle());
  UncertaintySources src;
  src.environment.material_temperature_c = 22.0;
  src.environment.setup_repeatability_mm = 0.2e-3;
  const std::vector<UncertaintyBudget> budgets = iso230_2Uncertainty(r, src);
  ASSERT_EQ(budgets.size(), 5u);
  EXPECT_EQ(budgets[0].quantity, "E");
  EXPECT_EQ(budgets[1].quantity, "M");
  EXPECT_EQ(budgets[2].quantity, "A");
  EXPECT_EQ(budgets[3].quantity, "B");
  EXPECT_EQ(budgets[4].quantity, "R");
  const UncertaintyBudget& E = budgets[0];
  EXPECT_EQ(E.value, r.E);
  // E runs from the down mean at 0 mm (−3 µm) to the up mean at 400 mm (+8 µm): L = 400 mm.
  // Wavelength: 400 mm × 0.05e-6 / √3; expansion coefficient: 400 × |22 − 20| × 1e-6 / √3.
  EXPECT_NEAR(find(E, "laser wavelength (vacuum)")->contribution(),
              400.0 * 0.05e-6 / std::sqrt(3.0),
              kTolBudget);
  EXPECT_NEAR(find(E, "expansion coefficient")->contribution(),
              400.0 * 2.0 * 1e-6 / std::sqrt(3.0),
              kTolBudget);
  EXPECT_NEAR(find(E, "set-up repeatability")->contribution(), 0.2e-3, kTolBudget);
  // s of the scatter (0, ±0.5, ±1 µm): √(2.5e-6/4) = 0.790569 µm at every target-direction; the
  // two extreme means: √(2 s²/5).
  const double s = std::sqrt(2.5e-6 / 4.0);
  EXPECT_NEAR(find(E, "sampling of the extreme means (s/sqrt(n))")->contribution(),
              std::sqrt(2.0 * s * s / 5.0),
              kTolBudget);
  EXPECT_EQ(find(E, "dead path (air change during the test)"), nullptr);  // no dead path given
  for (const UncertaintyBudget& b : budgets) {
    EXPECT_GT(b.expandedUncertainty(), 0.0) << b.quantity;
    EXPECT_EQ(b.coverage_factor, 2.0);
  }
  // B has no length term: statistics and the two readings' resolution only.
  EXPECT_EQ(find(budgets[3], "laser wavelength (vacuum)"), nullptr);
  EXPECT_NEAR(budgets[3].contributors[0].contribution(), std::sqrt(2.0 * s * s / 5.0), kTolBudget);
}

TEST(PositioningUncertainty, FewRunsGiveStudentsTFactorsFromWelchSatterthwaite) {
  // Three runs per direction, scatter (0, +1, −1) µm: s = 1 µm, each mean's variance s²/3 with
  // ν = 2. B's statistic adds two of them: ν = 4 (Welch–Satterthwaite); the Type B terms
  // (resolution, E_VE) raise the budget's ν_eff above that. GUM G.4.1, Table G.2.
  const double scatter[] = {0.0, 1e-3, -1e-3};
  std::vector<PositioningSample> samples;
  for (int i = 0; i < 5; ++i)
    for (int run = 1; run <= 3; ++run) {
      const double target = 100.0 * i;
      samples.push_back({target, 1, run, target + 2e-3 * i + scatter[run - 1]});
      samples.push_back({target, -1, run, target + 2e-3 * i + scatter[run - 1] - 3e-3});
    }
  const Iso230_2Result r = evaluateIso230_2(samples);
  const std::vector<UncertaintyBudget> budgets = iso230_2Uncertainty(r, UncertaintySources{});
  const UncertaintyBudget& B = budgets[3];
  ASSERT_EQ(B.quantity, "B");
  const UncertaintyContributor* stat =
      find(B, "sampling of the two means at the target (s/sqrt(n))");
  ASSERT_NE(stat, nullptr);
  EXPECT_NEAR(stat->degrees_of_freedom, 4.0, test::kTolExact);
  const double u_stat = stat->contribution(), u_c = B.combinedStandardUncertainty();
  EXPECT_NEAR(u_stat, std::sqrt(2.0 / 3.0) * 1e-3, kTolBudget);
  const double nu = std::pow(u_c, 4) / (std::pow(u_stat, 4) / 4.0);
  EXPECT_NEAR(B.effectiveDegreesOfFreedom() / nu, 1.0, test::kTolExact);
  const double p9545 = std::erf(std::sqrt(2.0));
  EXPECT_NEAR(B.coverageFactor(), studentT(p9545, nu), test::kTolExact);
  EXPECT_GT(B.coverageFactor(), 2.5);  // not the large-sample 2
  EXPECT_NEAR(B.expandedUncertainty() / (B.coverageFactor() * u_c), 1.0, test::kTolExact);
  // R = 2k s at one direction or the bidirectional sum: its s terms have ν = 2 each, the Type B
  // terms raise ν_eff to about 6 (k ≈ 2.5 rather than 2).
  const UncertaintyBudget& R = budgets[4];
  EXPECT_LT(R.effectiveDegreesOfFreedom(), 10.0);
  EXPECT_GT(R.coverageFactor(), 2.3);
}

TEST(PositioningUncertainty, NoiseFloorCoversBAndROfAPerfectlyRepeatableAxis) {
  // A perfect axis (no reversal, no scatter) read by a laser with the default reading noise
  // (σ = 0.01 µm), 15 targets, 3 runs each way, 200 trials: B and R read only the noise and
  // their truth is 0. U must cover 0 in about 95 % of the trials (docs/coverage.md's criterion,
  // 92 % at N = 200); without the noise floor it did in 75-90 %.
  const UncertaintySources src{};
  std::mt19937 rng{test::kSeed};
  std::normal_distribution<double> noise(0.0, src.laser.reading_noise_mm);
  constexpr int kTrials = 200, kTargets = 15, kRuns = 3;
  int b_covered = 0, r_covered = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    std::vector<PositioningSample> samples;
    for (int i = 0; i < kTargets; ++i)
      for (int run = 1; run <= kRuns; ++run)
        for (int direction : {1, -1}) {
          const double target = 50.0 * i;
          samples.push_back({target, direction, run, target + noise(rng)});
        }
    const Iso230_2Result r = evaluateIso230_2(samples);
    const std::vector<UncertaintyBudget> b = iso230_2Uncertainty(r, src);
    if (std::abs(r.B) <= b[3].expandedUncertainty()) ++b_covered;
    if (r.R <= b[4].expandedUncertainty()) ++r_covered;
  }
  EXPECT_GE(b_covered, 184) << "of " << kTrials;
  EXPECT_GE(r_covered, 184) << "of " << kTrials;
}

TEST(PositioningUncertainty, AirSensorsActThroughTheEdlenSensitivity) {
  UncertaintyBudget b;
  const UncertaintySources src;
  addLaserLengthContributors(b, 1000.0, src);
  const AirIndexSensitivity dn = edlenSensitivity(src.environment.air);
  // ±0.2 K on a 1 m beam: 1000 mm × 0.93e-6 /K × 0.2/√3 ≈ 0.107 µm.
  EXPECT_NEAR(find(b, "air temperature sensor")->contribution(),
              1000.0 * std::abs(dn.per_kelvin) * 0.2 / std::sqrt(3.0),
              kTolBudget);
  EXPECT_NEAR(find(b, "air temperature sensor")->contribution(), 0.107e-3, 0.005e-3);
  // Cosine error of 50 µrad over 1 m: 1000 × (50e-6)²/2 = 1.25 nm half-width.
  EXPECT_NEAR(find(b, "cosine error (beam misalignment)")->value, 1.25e-6, kTolBudget);
  EXPECT_THROW(addLaserLengthContributors(b, -1.0, src), InvalidArgument);
}

TEST(PositioningUncertainty, UnidirectionalDataHaveTheirDirectionsBudgets) {
  // Up only: E↑ from 0 to 8 µm over 400 mm, the same scatter at every target:
  // s = √(Σ scatter² / 4) = √0.625 µm, n = 5.
  const Iso230_2Result r = evaluateIso230_2(cycle(false));
  const std::vector<UncertaintyBudget> budgets = iso230_2Uncertainty(r, UncertaintySources{});
  ASSERT_EQ(budgets.size(), 3u);
  EXPECT_EQ(budgets[0].quantity, "E_up");
  EXPECT_EQ(budgets[1].quantity, "A_up");
  EXPECT_EQ(budgets[2].quantity, "R_up");
  EXPECT_EQ(budgets[0].value, r.E_up);
  const double s = std::sqrt(0.625) * 1e-3;
  EXPECT_NEAR(find(budgets[0], "laser wavelength (vacuum)")->contribution(),
              400.0 * 0.05e-6 / std::sqrt(3.0),
              kTolBudget);
  EXPECT_NEAR(find(budgets[0], "sampling of the extreme means (s/sqrt(n))")->contribution(),
              s * std::sqrt(2.0 / 5.0),
              kTolBudget);
  // R↑ = 2k s: u(s) = s/√(2(n − 1)) times 2k (k = 2).
  EXPECT_NEAR(find(budgets[2], "sampling of the standard deviation at the target")->contribution(),
              4.0 * s / std::sqrt(8.0),
              kTolBudget);
  EXPECT_EQ(find(budgets[2], "laser wavelength (vacuum)"), nullptr);  // taken at one target
  // Their conformance decisions; the bidirectional names have no budget here.
  EXPECT_EQ(decideIso230_2Conformance(budgets, {{"E_up", 1.0}})[0].decision,
            ConformanceDecision::kConforms);
  EXPECT_THROW((void)decideIso230_2Conformance(budgets, {{"E", 1.0}}), InvalidArgument);
}

TEST(PositioningUncertainty, ConformanceOfEachToleratedQuantity) {
  const Iso230_2Result r = evaluateIso230_2(cycle());
  const std::vector<UncertaintyBudget> budgets = iso230_2Uncertainty(r, UncertaintySources{});
  const double U = budgets[0].expandedUncertainty();
  const std::vector<ConformanceResult> d =
      decideIso230_2Conformance(budgets, {{"E", r.E + 2 * U}, {"B", r.B}, {"R", 0.5 * r.R}});
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0].decision, ConformanceDecision::kConforms);
  EXPECT_EQ(d[1].decision, ConformanceDecision::kUndecided);  // B exactly at its limit
  EXPECT_EQ(d[2].decision, ConformanceDecision::kDoesNotConform);
  EXPECT_NEAR(d[0].expanded_u, U, test::kTolExact);
  EXPECT_THROW((void)decideIso230_2Conformance(budgets, {{"Q", 1.0}}), InvalidArgument);
}

TEST(PositioningUncertainty, RejectsInvalidSources) {
  UncertaintySources src;
  EXPECT_TRUE(src.isValid());
  src.laser.wavelength_accuracy_ppm = -1.0;
  std::string why;
  EXPECT_FALSE(src.isValid(&why));
  EXPECT_NE(why.find("wavelength_accuracy_ppm"), std::string::npos);
  EXPECT_THROW((void)iso230_2Uncertainty(evaluateIso230_2(cycle()), src), InvalidArgument);
  src = UncertaintySources{};
  src.environment.air.pressure_pa = 0.0;
  EXPECT_FALSE(src.isValid());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
