// Monte Carlo propagation (metrology/monte_carlo.hpp) against the law of propagation.
#include "pkm/metrology/monte_carlo.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

constexpr double kTolMcRelative = 0.01;  // Monte Carlo u vs linear u on 1e5 trials (about 0.3 %)
constexpr double kTolIntervalRelative = 0.02;  // 95 % interval half-width vs 1.96 u
constexpr double kZ95 = 1.959964;              // the 97.5 % quantile of the normal law

UncertaintyBudget oneInput(Distribution d, double value) {
  UncertaintyBudget b{.quantity = "x"};
  b.contributors.push_back({.name = "x", .value = value, .distribution = d, .estimate = 10.0});
  return b;
}

TEST(MonteCarlo, EachDistributionHasTheStandardUncertaintyOfItsDivisor) {
  const MeasurementModel identity = [](std::span<const double> x) { return x[0]; };
  for (Distribution d : {Distribution::kNormal,
                         Distribution::kRectangular,
                         Distribution::kTriangular,
                         Distribution::kUShaped}) {
    const UncertaintyBudget b = oneInput(d, 2.0);
    const MonteCarloResult r = propagateMonteCarlo(identity, b);
    EXPECT_NEAR(
        r.standard_uncertainty / b.contributors[0].standardUncertainty(), 1.0, kTolMcRelative)
        << toString(d);
    EXPECT_NEAR(r.mean, 10.0, 4 * r.standard_uncertainty / std::sqrt(r.trials)) << toString(d);
    EXPECT_LE(r.high, 12.0 + (d == Distribution::kNormal ? 4.0 : 0.0));
  }
}

// A near-linear model, the length of a scale at temperature: y = L0 (1 + α (t − 20)) + d with
// L0 = 500 mm, α = 11.5e-6 /K ± 1e-6 (rectangular), t = 23 K ± 0.1 (rectangular), d a set-up
// offset 0 ± 0.5 µm (normal). The product α·t makes it non-linear, weakly: Monte Carlo and the
// linear budget (GUM §5) must agree (JCGM 101 §8: validation of the GUM uncertainty framework).
TEST(MonteCarlo, AgreesWithTheLinearBudgetOnANearLinearModel) {
  UncertaintyBudget inputs{.quantity = "y", .unit = "mm"};
  inputs.contributors.push_back({.name = "alpha",
                                 .value = 1e-6,
                                 .distribution = Distribution::kRectangular,
                                 .estimate = 11.5e-6});
  inputs.contributors.push_back(
      {.name = "t", .value = 0.1, .distribution = Distribution::kRectangular, .estimate = 23.0});
  inputs.contributors.push_back({.name = "d", .value = 0.5e-3, .estimate = 0.0});
  const MeasurementModel model = [](std::span<const double> x) {
    return 500.0 * (1.0 + x[0] * (x[1] - 20.0)) + x[2];
  };
  const UncertaintyBudget linear = linearizeModel(model, inputs);
  // c_alpha = 500·3 = 1500 mm·K, c_t = 500·11.5e-6 = 5.75e-3 mm/K, c_d = 1.
  EXPECT_NEAR(linear.contributors[0].sensitivity / 1500.0, 1.0, test::kTolFiniteDiff);
  EXPECT_NEAR(linear.contributors[1].sensitivity / 5.75e-3, 1.0, test::kTolFiniteDiff);
  EXPECT_NEAR(linear.contributors[2].sensitivity, 1.0, test::kTolFiniteDiff);
  EXPECT_NEAR(linear.value, 500.01725, test::kTolRoundTrip);
  const double u = linear.combinedStandardUncertainty();
  const MonteCarloResult mc = propagateMonteCarlo(model, inputs);
  EXPECT_NEAR(mc.standard_uncertainty / u, 1.0, kTolMcRelative);
  EXPECT_NEAR(mc.mean, linear.value, 0.05 * u);
  // The output is dominated by a rectangular input: its 95 % interval is narrower than ±1.96 u.
  EXPECT_LT((mc.high - mc.low) / 2.0, kZ95 * u);
  EXPECT_GT((mc.high - mc.low) / 2.0, 1.5 * u);
}

TEST(MonteCarlo, NormalDominatedIntervalIsPlusMinus1point96U) {
  UncertaintyBudget inputs{.quantity = "y"};
  inputs.contributors.push_back({.name = "a", .value = 1.0, .estimate = 1.0});
  inputs.contributors.push_back({.name = "b", .value = 2.0, .estimate = 2.0});
  const MeasurementModel model = [](std::span<const double> x) { return x[0] + 0.5 * x[1]; };
  const double u = linearizeModel(model, inputs).combinedStandardUncertainty();  // √2
  const MonteCarloResult mc = propagateMonteCarlo(model, inputs);
  EXPECT_NEAR((mc.high - mc.low) / 2.0 / (kZ95 * u), 1.0, kTolIntervalRelative);
}

TEST(MonteCarlo, IsReproducibleWithItsSeed) {
  const UncertaintyBudget b = oneInput(Distribution::kTriangular, 1.0);
  const MeasurementModel square = [](std::span<const double> x) { return x[0] * x[0]; };
  const MonteCarloOptions options{.trials = 1000};
  const MonteCarloResult a = propagateMonteCarlo(square, b, options);
  const MonteCarloResult c = propagateMonteCarlo(square, b, options);
  EXPECT_EQ(a.mean, c.mean);
  EXPECT_EQ(a.low, c.low);
  MonteCarloOptions other = options;
  other.seed += 1;
  EXPECT_NE(propagateMonteCarlo(square, b, other).mean, a.mean);
}

TEST(MonteCarlo, RejectsInvalidOptionsAndModels) {
  EXPECT_TRUE(MonteCarloOptions{}.isValid());
  EXPECT_FALSE(MonteCarloOptions{.trials = 10}.isValid());
  EXPECT_FALSE(MonteCarloOptions{.coverage_probability = 1.0}.isValid());
  const UncertaintyBudget b = oneInput(Distribution::kNormal, 1.0);
  EXPECT_THROW((void)propagateMonteCarlo(MeasurementModel{}, b), InvalidArgument);
  EXPECT_THROW(
      (void)propagateMonteCarlo(
          b.contributors.empty() ? MeasurementModel{} : [](std::span<const double>) { return NAN; },
          b),
      InvalidArgument);
  EXPECT_THROW((void)linearizeModel(MeasurementModel{}, b), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
