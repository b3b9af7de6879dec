/// @file
/// @brief Internal: one contributor of a calibration budget as its builders state it (the
/// hexapod's and the Exechon's instrument, set-up, actuator and weight sources).
#pragma once

#include <string>
#include <utility>

#include "pkm/metrology/uncertainty_budget.hpp"

namespace pkm::calibration::detail {

/// A contributor with its name, stated value (for kNormal a standard uncertainty, normal_k = 1),
/// unit, distribution and where the value comes from.
inline metrology::UncertaintyContributor makeContributor(std::string name,
                                                         double value,
                                                         std::string unit,
                                                         metrology::Distribution distribution,
                                                         std::string source) {
  metrology::UncertaintyContributor c;
  c.name = std::move(name);
  c.value = value;
  c.unit = std::move(unit);
  c.distribution = distribution;
  c.normal_k = 1.0;
  c.source = std::move(source);
  return c;
}

}  // namespace pkm::calibration::detail
