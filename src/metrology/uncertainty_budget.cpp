// Uncertainty budgets (metrology/uncertainty_budget.hpp): the law of propagation of uncertainty.
#include "pkm/metrology/uncertainty_budget.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <utility>

#include "pkm/core/error.hpp"

namespace pkm::metrology {

const char* toString(Distribution distribution) {
  switch (distribution) {
    case Distribution::kNormal:
      return "normal";
    case Distribution::kRectangular:
      return "rectangular";
    case Distribution::kTriangular:
      return "triangular";
    case Distribution::kUShaped:
      return "u-shaped";
  }
  return "normal";
}

std::optional<Distribution> parseDistribution(std::string_view name) {
  for (Distribution d : {Distribution::kNormal,
                         Distribution::kRectangular,
                         Distribution::kTriangular,
                         Distribution::kUShaped}) {
    if (name == toString(d)) return d;
  }
  return std::nullopt;
}

double UncertaintyContributor::divisor() const {
  switch (distribution) {
    case Distribution::kNormal:
      return normal_k;
    case Distribution::kRectangular:
      return std::sqrt(3.0);
    case Distribution::kTriangular:
      return std::sqrt(6.0);
    case Distribution::kUShaped:
      return std::sqrt(2.0);
  }
  return normal_k;
}

double UncertaintyContributor::standardUncertainty() const { return value / divisor(); }

double UncertaintyContributor::contribution() const {
  return std::abs(sensitivity) * standardUncertainty();
}

void UncertaintyBudget::validate() const {
  for (const UncertaintyContributor& c : contributors) {
    PKM_CHECK(std::isfinite(c.value) && c.value >= 0.0,
              "uncertainty budget '{}': contributor '{}' needs a finite value >= 0, got {}",
              quantity,
              c.name,
              c.value);
    PKM_CHECK(
        c.distribution != Distribution::kNormal || (std::isfinite(c.normal_k) && c.normal_k > 0),
        "uncertainty budget '{}': contributor '{}' needs a coverage factor > 0, got {}",
        quantity,
        c.name,
        c.normal_k);
    PKM_CHECK(std::isfinite(c.sensitivity),
              "uncertainty budget '{}': contributor '{}' has a non-finite sensitivity",
              quantity,
              c.name);
    PKM_CHECK(c.degrees_of_freedom > 0.0,
              "uncertainty budget '{}': contributor '{}' needs degrees of freedom > 0, got {}",
              quantity,
              c.name,
              c.degrees_of_freedom);
  }
  for (const Correlation& r : correlations) {
    PKM_CHECK(r.i < contributors.size() && r.j < contributors.size() && r.i != r.j,
              "uncertainty budget '{}': correlation between contributors {} and {} of {}",
              quantity,
              r.i,
              r.j,
              contributors.size());
    PKM_CHECK(std::isfinite(r.r) && std::abs(r.r) <= 1.0,
              "uncertainty budget '{}': correlation coefficient {} outside [-1, 1]",
              quantity,
              r.r);
  }
  PKM_CHECK(std::isfinite(coverage_factor) && coverage_factor > 0.0,
            "uncertainty budget '{}': coverage factor must be > 0, got {}",
            quantity,
            coverage_factor);
}

double UncertaintyBudget::combinedStandardUncertainty() const {
  validate();
  double variance = 0.0;
  for (const UncertaintyContributor& c : contributors) {
    const double ci_ui = c.sensitivity * c.standardUncertainty();
    variance += ci_ui * ci_ui;
  }
  for (const Correlation& r : correlations) {
    const UncertaintyContributor& a = contributors[r.i];
    const UncertaintyContributor& b = contributors[r.j];
    variance += 2.0 * a.sensitivity * b.sensitivity * a.standardUncertainty() *
                b.standardUncertainty() * r.r;
  }
  return std::sqrt(std::max(variance, 0.0));
}

double UncertaintyBudget::effectiveDegreesOfFreedom() const {
  validate();
  std::vector<double> variance, dof;
  for (const UncertaintyContributor& c : contributors) {
    const double u = c.contribution();
    variance.push_back(u * u);
    dof.push_back(c.degrees_of_freedom);
  }
  return welchSatterthwaite(variance, dof);
}

double UncertaintyBudget::coverageFactor() const {
  validate();
  const double nu = effectiveDegreesOfFreedom();
  if (std::isinf(nu)) return coverage_factor;
  const double p =
      2.0 * boost::math::cdf(boost::math::normal_distribution<double>(), coverage_factor) - 1.0;
  return studentT(p, nu);
}

double UncertaintyBudget::expandedUncertainty() const {
  return coverageFactor() * combinedStandardUncertainty();
}

double studentT(double p, double degrees_of_freedom) {
  PKM_CHECK(p > 0.0 && p < 1.0, "Student's t: coverage probability {} outside (0, 1)", p);
  PKM_CHECK(degrees_of_freedom > 0.0,
            "Student's t: degrees of freedom must be > 0, got {}",
            degrees_of_freedom);
  const double q = 0.5 + p / 2.0;
  if (std::isinf(degrees_of_freedom))
    return boost::math::quantile(boost::math::normal_distribution<double>(), q);
  return boost::math::quantile(boost::math::students_t_distribution<double>(degrees_of_freedom), q);
}

namespace {

/// ∫₀^hi f by Simpson's rule with `intervals` (even) intervals.
template <class F>
double simpson(F f, double hi, int intervals) {
  const double h = hi / intervals;
  double sum = f(0.0) + f(hi);
  for (int i = 1; i < intervals; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * f(i * h);
  return sum * h / 3.0;
}

/// `compute()` once per key: the integrals are pure and the budgets ask for the same few (targets,
/// runs) over and over (a coverage run evaluates thousands of budgets).
template <class Key, class F>
double memoised(const Key& key, F compute) {
  static std::mutex mutex;
  static std::map<Key, double> cache;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  const double value = compute();
  const std::lock_guard<std::mutex> lock(mutex);
  cache.emplace(key, value);
  return value;
}

}  // namespace

double expectedNormalRange(std::size_t n) {
  PKM_CHECK(n >= 2, "expected range: needs n >= 2 values, got {}", n);
  const double count = static_cast<double>(n);
  // On [-12, 12] (beyond it the integrand is below 1e-30 for n up to 1e9), shifted to [0, 24].
  return simpson(
      [count](double t) {
        const double x = t - 12.0;
        const double below = 0.5 * std::erfc(-x / std::sqrt(2.0));
        const double above = 0.5 * std::erfc(x / std::sqrt(2.0));
        return 1.0 - std::pow(below, count) - std::pow(above, count);
      },
      24.0,
      4800);
}

double expectedMaxAbsNormal(std::size_t m) {
  PKM_CHECK(m >= 1, "expected maximum: needs m >= 1 values, got {}", m);
  const double count = static_cast<double>(m);
  return memoised(std::pair<std::size_t, int>{m, 0}, [count] {
    return simpson(
        [count](double x) { return 1.0 - std::pow(std::erf(x / std::sqrt(2.0)), count); },
        12.0,
        4800);
  });
}

double expectedMaxSampleSigma(std::size_t m, int n) {
  PKM_CHECK(
      m >= 1 && n >= 2, "expected maximum of s/sigma: needs m >= 1 and n >= 2, got {}, {}", m, n);
  return memoised(std::pair<std::size_t, int>{m, n}, [m, n] {
    const double dof = n - 1.0, count = static_cast<double>(m);
    const boost::math::chi_squared_distribution<double> chi2(dof);
    // s/σ = √(χ²/ν): P(s/σ ≤ x) = P(χ² ≤ ν x²). Beyond x = 12 (ν ≥ 1) the tail is below 1e-30.
    return simpson(
        [&](double x) { return 1.0 - std::pow(boost::math::cdf(chi2, dof * x * x), count); },
        12.0,
        4800);
  });
}

double welchSatterthwaite(const std::vector<double>& variance,
                          const std::vector<double>& degrees_of_freedom) {
  PKM_CHECK(variance.size() == degrees_of_freedom.size(),
            "Welch-Satterthwaite: {} variances and {} degrees of freedom",
            variance.size(),
            degrees_of_freedom.size());
  double total = 0.0, denominator = 0.0;
  for (std::size_t i = 0; i < variance.size(); ++i) {
    total += variance[i];
    if (std::isfinite(degrees_of_freedom[i]))
      denominator += variance[i] * variance[i] / degrees_of_freedom[i];
  }
  if (!(denominator > 0.0) || !(total > 0.0)) return std::numeric_limits<double>::infinity();
  return total * total / denominator;
}

std::optional<std::size_t> UncertaintyBudget::largestContributor() const {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < contributors.size(); ++i) {
    if (!best || contributors[i].contribution() > contributors[*best].contribution()) best = i;
  }
  return best;
}

void addContributor(UncertaintyBudget& budget, UncertaintyContributor c) {
  if (c.contribution() != 0.0) budget.contributors.push_back(std::move(c));
}

}  // namespace pkm::metrology
