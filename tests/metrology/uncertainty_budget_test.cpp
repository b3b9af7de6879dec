// Uncertainty budgets (metrology/uncertainty_budget.hpp) against hand calculations.
#include "pkm/metrology/uncertainty_budget.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

constexpr double kTolHand = 1e-9;  // mm: the hand calculation's rounding (12 digits kept)

UncertaintyContributor rect(const char* name, double a, const char* unit, double c) {
  return {.name = name,
          .value = a,
          .unit = unit,
          .distribution = Distribution::kRectangular,
          .sensitivity = c};
}

TEST(UncertaintyBudget, DivisorsOfTheFourDistributions) {
  UncertaintyContributor c{.value = 6.0};
  c.distribution = Distribution::kNormal;
  c.normal_k = 2.0;
  EXPECT_DOUBLE_EQ(c.standardUncertainty(), 3.0);  // U = 6 at k = 2
  c.distribution = Distribution::kRectangular;
  EXPECT_DOUBLE_EQ(c.divisor(), std::sqrt(3.0));
  c.distribution = Distribution::kTriangular;
  EXPECT_DOUBLE_EQ(c.divisor(), std::sqrt(6.0));
  c.distribution = Distribution::kUShaped;
  EXPECT_DOUBLE_EQ(c.divisor(), std::sqrt(2.0));
  for (Distribution d : {Distribution::kNormal,
                         Distribution::kRectangular,
                         Distribution::kTriangular,
                         Distribution::kUShaped})
    EXPECT_EQ(parseDistribution(toString(d)), d);
  EXPECT_FALSE(parseDistribution("gaussian"));
}

// A worked example in the manner of ISO/TR 230-9 (own numbers): the bidirectional systematic
// positional deviation E of a 500 mm steel axis measured with a laser interferometer, the
// machine at 23 °C (corrected to 20 °C with the nominal α = 11.5 µm/(m·K)).
//   laser vacuum wavelength ±0.05 ppm, rectangular:
//     u = 0.05/√3 = 0.028868 ppm, c = 500 mm × 1e-6 /ppm = 5e-4 mm/ppm -> 1.4433757e-5 mm
//   material temperature sensor ±0.1 K, rectangular:
//     u = 0.1/√3 = 0.057735 K, c = 500 × 11.5e-6 = 5.75e-3 mm/K -> 3.3197640e-4 mm
//   expansion coefficient ±1e-6 /K, rectangular, |23 − 20| = 3 K:
//     u = 1e-6/√3 = 5.7735e-7 /K, c = 500 × 3 = 1500 mm·K -> 8.6602540e-4 mm
//   set-up repeatability, normal, standard uncertainty 0.5 µm -> 5e-4 mm
// u_c² = 2.0833e-10 + 1.10208e-7 + 7.5e-7 + 2.5e-7 = 1.1104166e-6 mm²
// u_c = 1.0537631e-3 mm, U = 2 u_c = 2.1075262e-3 mm (2.1 µm, k = 2).
TEST(UncertaintyBudget, WorkedExampleOfALaserPositioningBudget) {
  UncertaintyBudget b{.quantity = "E", .unit = "mm", .value = 0.0123};
  b.contributors.push_back(rect("laser wavelength (vacuum)", 0.05, "ppm", 500 * 1e-6));
  b.contributors.push_back(rect("material temperature sensor", 0.1, "K", 500 * 11.5e-6));
  b.contributors.push_back(rect("expansion coefficient", 1e-6, "1/K", 500 * 3.0));
  b.contributors.push_back({.name = "set-up repeatability", .value = 0.5e-3, .unit = "mm"});
  EXPECT_NEAR(b.contributors[0].contribution(), 1.4433757e-5, kTolHand);
  EXPECT_NEAR(b.contributors[1].contribution(), 3.3197640e-4, kTolHand);
  EXPECT_NEAR(b.contributors[2].contribution(), 8.6602540e-4, kTolHand);
  EXPECT_NEAR(b.combinedStandardUncertainty(), 1.0537631e-3, kTolHand);
  EXPECT_NEAR(b.expandedUncertainty(), 2.1075262e-3, kTolHand);
  EXPECT_EQ(b.largestContributor(), 2u);  // the expansion coefficient dominates at 3 K off 20 °C
}

TEST(UncertaintyBudget, CorrelatedInputsAddOrCancel) {
  // Two readings of one scale (GUM §5.2.2): with r = +1 the contributions add linearly
  // (0.3 + 0.4 = 0.7), with r = −1 they subtract (0.1); uncorrelated: √(0.09 + 0.16) = 0.5.
  UncertaintyBudget b{.quantity = "y"};
  b.contributors.push_back({.name = "a", .value = 0.3});
  b.contributors.push_back({.name = "b", .value = 0.4});
  EXPECT_NEAR(b.combinedStandardUncertainty(), 0.5, test::kTolExact);
  b.correlations.push_back({0, 1, 1.0});
  EXPECT_NEAR(b.combinedStandardUncertainty(), 0.7, test::kTolExact);
  b.correlations[0].r = -1.0;
  EXPECT_NEAR(b.combinedStandardUncertainty(), 0.1, test::kTolExact);
  b.contributors[1].sensitivity = -1.0;  // a difference of positively correlated readings
  EXPECT_NEAR(b.combinedStandardUncertainty(), 0.7, test::kTolExact);
}

TEST(UncertaintyBudget, RejectsInvalidBudgets) {
  UncertaintyBudget b{.quantity = "y"};
  b.contributors.push_back({.name = "a", .value = -1.0});
  EXPECT_THROW((void)b.combinedStandardUncertainty(), InvalidArgument);
  b.contributors[0].value = 1.0;
  b.contributors[0].normal_k = 0.0;
  EXPECT_THROW(b.validate(), InvalidArgument);
  b.contributors[0].normal_k = 1.0;
  b.correlations.push_back({0, 0, 0.5});
  EXPECT_THROW(b.validate(), InvalidArgument);
  b.correlations[0] = {0, 3, 0.5};
  EXPECT_THROW(b.validate(), InvalidArgument);
  b.correlations.clear();
  b.coverage_factor = 0.0;
  EXPECT_THROW(b.validate(), InvalidArgument);
}

// GUM Table G.2 prints t_p(ν) to 2 decimals.
constexpr double kTolTableG2 = 0.005;

TEST(UncertaintyBudget, StudentTAgreesWithGumTableG2) {
  const double p9545 = std::erf(2.0 / std::sqrt(2.0));  // the coverage of k = 2 at ν = ∞
  EXPECT_NEAR(studentT(p9545, 1.0), 13.97, kTolTableG2);
  EXPECT_NEAR(studentT(p9545, 2.0), 4.53, kTolTableG2);
  EXPECT_NEAR(studentT(p9545, 3.0), 3.31, kTolTableG2);
  EXPECT_NEAR(studentT(p9545, 10.0), 2.28, kTolTableG2);
  EXPECT_NEAR(studentT(p9545, 50.0), 2.05, kTolTableG2);
  EXPECT_NEAR(studentT(0.95, 2.0), 4.30, kTolTableG2);
  EXPECT_NEAR(studentT(0.95, 10.0), 2.23, kTolTableG2);
  EXPECT_NEAR(studentT(p9545, std::numeric_limits<double>::infinity()), 2.0, test::kTolExact);
  EXPECT_THROW((void)studentT(1.0, 3.0), InvalidArgument);
  EXPECT_THROW((void)studentT(0.95, 0.0), InvalidArgument);
}

TEST(UncertaintyBudget, WelchSatterthwaiteOfTwoTypeATerms) {
  const double inf = std::numeric_limits<double>::infinity();
  // Two equal variances with ν = 2 each: (2v)² / (2 v²/2) = 4.
  EXPECT_NEAR(welchSatterthwaite({1.0, 1.0}, {2.0, 2.0}), 4.0, test::kTolExact);
  // A Type B term adds variance, no denominator: (1 + 3)² / (1/2) = 32.
  EXPECT_NEAR(welchSatterthwaite({1.0, 3.0}, {2.0, inf}), 32.0, test::kTolExact);
  EXPECT_TRUE(std::isinf(welchSatterthwaite({1.0, 3.0}, {inf, inf})));
  EXPECT_TRUE(std::isinf(welchSatterthwaite({}, {})));
}

TEST(UncertaintyBudget, FiniteDegreesOfFreedomWidenTheCoverageFactor) {
  UncertaintyBudget b;
  b.quantity = "B";
  b.unit = "mm";
  UncertaintyContributor a{.name = "repeatability", .value = 0.4e-3, .unit = "mm"};
  a.degrees_of_freedom = 2.0;
  b.contributors.push_back(a);
  b.contributors.push_back(rect("resolution", 0.3e-3, "mm", 1.0));
  const double ua = 0.4e-3, ub = 0.3e-3 / std::sqrt(3.0);
  const double uc = std::hypot(ua, ub);
  const double nu = std::pow(uc, 4) / (std::pow(ua, 4) / 2.0);
  EXPECT_NEAR(b.effectiveDegreesOfFreedom() / nu, 1.0, test::kTolExact);
  const double p9545 = std::erf(2.0 / std::sqrt(2.0));
  EXPECT_NEAR(b.coverageFactor(), studentT(p9545, nu), test::kTolExact);
  EXPECT_GT(b.coverageFactor(), 3.0);
  EXPECT_NEAR(b.expandedUncertainty() / (b.coverageFactor() * uc), 1.0, test::kTolExact);
  b.contributors[0].degrees_of_freedom = std::numeric_limits<double>::infinity();
  EXPECT_EQ(b.coverageFactor(), 2.0);
  b.contributors[0].degrees_of_freedom = 0.0;
  EXPECT_THROW((void)b.expandedUncertainty(), InvalidArgument);
}

TEST(UncertaintyBudget, AddContributorLeavesOutSourcesThatDoNotApply) {
  UncertaintyBudget b;
  addContributor(b, {.name = "dead path", .value = 0.5, .sensitivity = 0.0});
  addContributor(b, {.name = "set-up", .value = 0.0});
  addContributor(b, {.name = "laser", .value = 1.0});
  ASSERT_EQ(b.contributors.size(), 1u);
  EXPECT_EQ(b.contributors[0].name, "laser");
  EXPECT_FALSE(UncertaintyBudget{}.largestContributor());
}

}  // namespace PKM_TEST_NS
TEST(UncertaintyBudget, ExpectedNormalRangeMatchesTheControlChartTable) {
  // d2(2) = 2/√π exactly; d2(10) = 3.078 (control-chart tables, 3 decimals); d2(180) = 5.421858
  // (scipy.integrate.quad of the same integral).
  constexpr double kTolQuadrature = 1e-9;
  constexpr double kTolTable = 5e-4;
  EXPECT_NEAR(expectedNormalRange(2), 2.0 / std::sqrt(std::numbers::pi), kTolQuadrature);
  EXPECT_NEAR(expectedNormalRange(10), 3.078, kTolTable);
  EXPECT_NEAR(expectedNormalRange(180), 5.421858078682337, 1e-7);
  EXPECT_THROW((void)expectedNormalRange(1), InvalidArgument);
}

TEST(UncertaintyBudget, ExpectedMaximaMatchTheirClosedFormsAndScipy) {
  // E|Z| = √(2/π); E[s/σ] for n = 3 is c4(3) = √π/2 (the control-chart constant); for 15
  // targets: 2.0508974 and 1.7914200 (scipy.integrate.quad of the same integrals).
  constexpr double kTolQuadrature = 1e-9;
  EXPECT_NEAR(expectedMaxAbsNormal(1), std::sqrt(2.0 / std::numbers::pi), kTolQuadrature);
  EXPECT_NEAR(expectedMaxSampleSigma(1, 3), std::sqrt(std::numbers::pi) / 2.0, kTolQuadrature);
  EXPECT_NEAR(expectedMaxAbsNormal(15), 2.0508974035321548, 1e-7);
  EXPECT_NEAR(expectedMaxSampleSigma(15, 3), 1.7914199700771325, 1e-6);
  EXPECT_NEAR(expectedMaxSampleSigma(11, 5), 1.520741554968009, 1e-6);
  EXPECT_THROW((void)expectedMaxAbsNormal(0), InvalidArgument);
  EXPECT_THROW((void)expectedMaxSampleSigma(3, 1), InvalidArgument);
}

}  // namespace pkm::metrology
