// Uncertainty budgets (metrology/uncertainty_budget.hpp): the law of propagation of uncertainty.
#include "pkm/metrology/uncertainty_budget.hpp"

#include <cmath>

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

double UncertaintyBudget::expandedUncertainty() const {
  return coverage_factor * combinedStandardUncertainty();
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
