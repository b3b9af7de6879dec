#include "pkm/metrology/circular_uncertainty.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

constexpr double kRelTolSigma = 0.05;  ///< noise σ recovered from 3600 readings, relative
constexpr double kTolExactMm = 1e-15;  ///< contributor values computed in closed form, mm

/// r(θ) = R + a·cos 2θ + shift + N(0, σ²) sampled at n equal angles about c, in the order read.
std::vector<Point2> noisyOval(const Point2& c,
                              double r,
                              double a,
                              double shift,
                              double sigma,
                              int n,
                              bool cw,
                              std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<Point2> p;
  for (int k = 0; k < n; ++k) {
    const double t = (cw ? -1.0 : 1.0) * 2.0 * std::numbers::pi * k / n;
    const double radius = r + a * std::cos(2.0 * t) + shift + noise(rng);
    p.emplace_back(c + radius * Point2(std::cos(t), std::sin(t)));
  }
  return p;
}

std::map<std::string, UncertaintyBudget> byName(const std::vector<UncertaintyBudget>& budgets) {
  std::map<std::string, UncertaintyBudget> m;
  for (const UncertaintyBudget& b : budgets) m[b.quantity] = b;
  return m;
}

const UncertaintyContributor& contributor(const UncertaintyBudget& b, const std::string& name) {
  for (const UncertaintyContributor& c : b.contributors)
    if (c.name == name) return c;
  throw std::runtime_error("no contributor " + name + " in " + b.quantity);
}

bool has(const UncertaintyBudget& b, const std::string& name) {
  for (const UncertaintyContributor& c : b.contributors)
    if (c.name == name) return true;
  return false;
}

TEST(SuccessiveDifferenceSigma, RecoversWhiteNoiseUnderASmoothProfileAndIgnoresATrend) {
  std::mt19937 rng(test::kSeed);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::vector<double> v, line;
  for (int k = 0; k < 20000; ++k) {
    v.push_back(0.01 * std::sin(2.0 * std::numbers::pi * k / 20000.0) + noise(rng));
    line.push_back(3.0 + 0.25 * k);
  }
  EXPECT_NEAR(successiveDifferenceSigma(v), 1e-3, 0.02e-3);
  EXPECT_NEAR(successiveDifferenceSigma(line), 0.0, 1e-12);
  EXPECT_EQ(successiveDifferenceSigma(std::vector<double>{1.0, 2.0}), 0.0);
}

TEST(CircularTestUncertainty, BudgetsFollowTheBallbarTheNoiseAndTheCentre) {
  std::mt19937 rng(test::kSeed);
  const Point2 c(5.0, -2.0);
  const double r = 100.0, a = 0.005, delta = 0.002, sigma = 0.2e-3;
  const int n = 3600;
  const auto cw = noisyOval(c, r, a, 0.0, sigma, n, true, rng);
  const auto ccw = noisyOval(c, r, a, delta, sigma, n, false, rng);
  CircularTestOptions opt;
  opt.nominal_radius = r;
  opt.nominal_center = c;
  const CircularTestResult result = evaluateCircularTest(cw, ccw, opt);
  UncertaintySources src;
  const auto budgets = byName(circularTestUncertainty(cw, ccw, result, src));
  for (const char* q :
       {"G_cw", "G_ccw", "G_bidirectional", "H", "F_max_cw", "F_min_cw", "F_max_ccw", "F_min_ccw"})
    ASSERT_TRUE(budgets.count(q)) << q;

  const UncertaintyBudget& g = budgets.at("G_cw");
  EXPECT_EQ(g.value, result.cw.circular_deviation);
  // Two readings of the sensor at the extremes: ±a rectangular each (ISO/TR 230-9 §5.2).
  const UncertaintyContributor& sensor = contributor(g, "ballbar sensor accuracy");
  EXPECT_NEAR(sensor.contribution(),
              std::sqrt(2.0) * src.ballbar.sensor_accuracy_mm / std::sqrt(3.0),
              kTolExactMm);
  // The noise σ from the data, at two readings.
  const UncertaintyContributor& noise = contributor(g, "non-repeatable noise");
  EXPECT_NEAR(noise.value, sigma, kRelTolSigma * sigma);
  EXPECT_NEAR(noise.sensitivity, std::sqrt(2.0), test::kTolExact);
  // The least-squares centre of n equally spaced points: u(c_x) = u(c_y) = σ √(2/n).
  EXPECT_NEAR(contributor(g, "least-squares centre x").value,
              sigma * std::sqrt(2.0 / n),
              kRelTolSigma * sigma * std::sqrt(2.0 / n));
  EXPECT_NEAR(contributor(g, "least-squares centre y").value,
              sigma * std::sqrt(2.0 / n),
              kRelTolSigma * sigma * std::sqrt(2.0 / n));
  // The bar's temperature change during the test: α·R·ΔT (rectangular).
  EXPECT_NEAR(
      contributor(g, "bar temperature change during the test").value,
      src.environment.expansion_coefficient_per_k * r * src.environment.air_temperature_variation_k,
      1e-9);
  // U = k·u_c by the GUM's law of propagation, with the stated k.
  EXPECT_NEAR(g.expandedUncertainty(), 2.0 * g.combinedStandardUncertainty(), test::kTolExact);

  // H compares the two runs at one angle with the same sensor: its accuracy cancels.
  EXPECT_FALSE(has(budgets.at("H"), "ballbar sensor accuracy"));
  EXPECT_TRUE(has(budgets.at("H"), "non-repeatable noise"));
  // F is an absolute reading against R0: the bar's length calibration (k = 2) counts.
  const UncertaintyContributor& length =
      contributor(budgets.at("F_max_cw"), "ballbar length calibration");
  EXPECT_NEAR(length.standardUncertainty(), src.ballbar.length_uncertainty_mm / 2.0, kTolExactMm);
  EXPECT_FALSE(has(g, "ballbar length calibration"));
}

TEST(CircularTestUncertainty, MinimumZoneAndNominalCentresHaveNoCentreTerm) {
  std::mt19937 rng(test::kSeed);
  const auto cw = noisyOval(Point2::Zero(), 50.0, 0.003, 0.0, 0.1e-3, 720, true, rng);
  const auto ccw = noisyOval(Point2::Zero(), 50.0, 0.003, 0.0, 0.1e-3, 720, false, rng);
  for (const CircularCentre centre : {CircularCentre::kMinimumZone, CircularCentre::kNominal}) {
    CircularTestOptions opt;
    opt.centre = centre;
    opt.nominal_center = Point2::Zero();
    const CircularTestResult result = evaluateCircularTest(cw, ccw, opt);
    const auto budgets = byName(circularTestUncertainty(cw, ccw, result, {}));
    EXPECT_FALSE(has(budgets.at("G_cw"), "least-squares centre x"));
    EXPECT_FALSE(budgets.count("F_max_cw"));  // no nominal radius, no F
  }
}

TEST(CircularTestUncertainty, RefusesInvalidSourcesAndShortRuns) {
  std::mt19937 rng(test::kSeed);
  const auto cw = noisyOval(Point2::Zero(), 50.0, 0.003, 0.0, 0.1e-3, 36, true, rng);
  const CircularTestResult result = evaluateCircularTest(cw, cw, {});
  UncertaintySources bad;
  bad.ballbar.sensor_accuracy_mm = -1.0;
  EXPECT_THROW((void)circularTestUncertainty(cw, cw, result, bad), InvalidArgument);
  const std::vector<Point2> three(cw.begin(), cw.begin() + 3);
  EXPECT_THROW((void)circularTestUncertainty(three, cw, result, {}), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
