// Monte Carlo propagation of distributions (metrology/monte_carlo.hpp, GUM Supplement 1).
#include "pkm/metrology/monte_carlo.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

/// Uniform on [0, 1) from the 53 high bits of one draw.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// Standard normal by Box-Muller (one of the pair).
double standardNormal(std::mt19937_64& rng) {
  const double u1 = 1.0 - uniform(rng);  // (0, 1]: the logarithm stays finite
  const double u2 = uniform(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

/// One draw of contributor `c` around its estimate.
double draw(const UncertaintyContributor& c, std::mt19937_64& rng) {
  switch (c.distribution) {
    case Distribution::kNormal:
      return c.estimate + c.standardUncertainty() * standardNormal(rng);
    case Distribution::kRectangular:
      return c.estimate + c.value * (2.0 * uniform(rng) - 1.0);
    case Distribution::kTriangular:
      return c.estimate + c.value * (uniform(rng) + uniform(rng) - 1.0);
    case Distribution::kUShaped:
      return c.estimate + c.value * std::sin(2.0 * std::numbers::pi * uniform(rng));
  }
  return c.estimate;
}

/// The p-quantile of sorted values (JCGM 101 §7.7: the ⌈pM⌉-th smallest value).
double quantile(const std::vector<double>& sorted, double p) {
  const auto m = static_cast<double>(sorted.size());
  const auto index = static_cast<std::size_t>(std::clamp(std::ceil(p * m) - 1.0, 0.0, m - 1.0));
  return sorted[index];
}

}  // namespace

bool MonteCarloOptions::isValid(std::string* why) const {
  const auto fail = [&](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (trials < 100) return fail("Monte Carlo: trials must be >= 100");
  if (!(coverage_probability > 0.0 && coverage_probability < 1.0))
    return fail("Monte Carlo: coverage_probability must be in (0, 1)");
  return true;
}

MonteCarloResult propagateMonteCarlo(const MeasurementModel& model,
                                     const UncertaintyBudget& inputs,
                                     const MonteCarloOptions& options) {
  std::string why;
  PKM_CHECK(options.isValid(&why), "{}", why);
  PKM_CHECK(static_cast<bool>(model), "Monte Carlo: no measurement model");
  inputs.validate();
  std::mt19937_64 rng(options.seed);
  std::vector<double> x(inputs.contributors.size());
  std::vector<double> y(options.trials);
  double sum = 0.0;
  for (double& yk : y) {
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = draw(inputs.contributors[i], rng);
    yk = model(x);
    PKM_CHECK(std::isfinite(yk), "Monte Carlo: the model value is not finite");
    sum += yk;
  }
  MonteCarloResult result;
  result.trials = y.size();
  result.mean = sum / static_cast<double>(y.size());
  double squares = 0.0;
  for (double yk : y) squares += (yk - result.mean) * (yk - result.mean);
  result.standard_uncertainty = std::sqrt(squares / static_cast<double>(y.size() - 1));
  std::sort(y.begin(), y.end());
  result.low = quantile(y, (1.0 - options.coverage_probability) / 2.0);
  result.high = quantile(y, (1.0 + options.coverage_probability) / 2.0);
  return result;
}

UncertaintyBudget linearizeModel(const MeasurementModel& model, const UncertaintyBudget& inputs) {
  PKM_CHECK(static_cast<bool>(model), "linear propagation: no measurement model");
  inputs.validate();
  UncertaintyBudget budget = inputs;
  std::vector<double> x;
  for (const UncertaintyContributor& c : inputs.contributors) x.push_back(c.estimate);
  budget.value = model(x);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double u = inputs.contributors[i].standardUncertainty();
    const double h = u > 0.0 ? 1e-3 * u : 1e-6;
    std::vector<double> plus = x, minus = x;
    plus[i] += h;
    minus[i] -= h;
    budget.contributors[i].sensitivity = (model(plus) - model(minus)) / (2.0 * h);
  }
  return budget;
}

}  // namespace pkm::metrology
