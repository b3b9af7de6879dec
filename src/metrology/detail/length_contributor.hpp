/// @file
/// @brief Internal: an uncertainty contributor, and an empty budget, stated in mm (the budgets of
/// straightness, parallelism, circles and circular tests build theirs this way).
#pragma once

#include <string>
#include <utility>

#include "pkm/metrology/uncertainty_budget.hpp"

namespace pkm::metrology::detail {

/// A contributor `name` of `value` mm with `distribution`, sensitivity coefficient `sensitivity`
/// (result unit per mm) and coverage factor `normal_k` for a normal value, from `source`.
inline UncertaintyContributor lengthContributor(std::string name,
                                                double value,
                                                Distribution distribution,
                                                double sensitivity,
                                                std::string source,
                                                double normal_k = 1.0) {
  UncertaintyContributor c;
  c.name = std::move(name);
  c.value = value;
  c.unit = "mm";
  c.distribution = distribution;
  c.normal_k = normal_k;
  c.sensitivity = sensitivity;
  c.source = std::move(source);
  return c;
}

/// A rectangular contributor `name` of half-width `half_width` in `unit` (a datasheet's ±),
/// sensitivity `sensitivity` (result unit per `unit`), from `source`.
inline UncertaintyContributor boundedContributor(
    std::string name, double half_width, std::string unit, double sensitivity, std::string source) {
  UncertaintyContributor c;
  c.name = std::move(name);
  c.value = half_width;
  c.unit = std::move(unit);
  c.distribution = Distribution::kRectangular;
  c.sensitivity = sensitivity;
  c.source = std::move(source);
  return c;
}

/// An empty budget of a result `quantity` = `value` mm, expanded with `coverage_factor` (the
/// sources' k at infinite degrees of freedom).
inline UncertaintyBudget lengthBudget(std::string quantity, double value, double coverage_factor) {
  UncertaintyBudget b;
  b.quantity = std::move(quantity);
  b.unit = "mm";
  b.value = value;
  b.coverage_factor = coverage_factor;
  return b;
}

}  // namespace pkm::metrology::detail
