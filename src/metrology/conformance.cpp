// ISO 14253-1 decision rules (metrology/conformance.hpp).
#include "pkm/metrology/conformance.hpp"

#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::metrology {

const char* toString(ConformanceDecision decision) {
  switch (decision) {
    case ConformanceDecision::kConforms:
      return "conforms";
    case ConformanceDecision::kDoesNotConform:
      return "does not conform";
    case ConformanceDecision::kUndecided:
      return "not decidable within U";
  }
  return "not decidable within U";
}

ConformanceDecision decideConformance(double value, double expanded_u, double upper_limit) {
  PKM_CHECK(std::isfinite(value) && std::isfinite(expanded_u) && std::isfinite(upper_limit),
            "conformance: value {}, U {} and limit {} must be finite",
            value,
            expanded_u,
            upper_limit);
  PKM_CHECK(expanded_u >= 0.0, "conformance: U must be >= 0, got {}", expanded_u);
  if (value <= upper_limit - expanded_u) return ConformanceDecision::kConforms;
  if (value > upper_limit + expanded_u) return ConformanceDecision::kDoesNotConform;
  return ConformanceDecision::kUndecided;
}

}  // namespace pkm::metrology
