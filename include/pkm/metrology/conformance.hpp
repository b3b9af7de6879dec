/// @file
/// @brief Decision rules for proving conformance or nonconformance with a specification when the
/// measurement has an uncertainty (ISO 14253-1:2017 §5-6): the conformance zone is the
/// specification zone reduced by the expanded uncertainty U on each specified side, the
/// nonconformance zone is outside the specification zone extended by U; in between, neither can
/// be proved. ISO 230-2:2014 tolerances (E, M, A, B, R, ...) are upper limits with a natural zero,
/// so only the upper side is reduced. docs/analysis.md, "Conformance (ISO 14253-1)".
#pragma once

#include <string>

namespace pkm::metrology {

/// The outcome of a conformance test per ISO 14253-1.
enum class ConformanceDecision {
  kConforms,        ///< value <= T − U: conformance proved
  kDoesNotConform,  ///< value > T + U: nonconformance proved
  kUndecided,       ///< T − U < value <= T + U: neither can be proved within U
};

/// "conforms", "does not conform" or "not decidable within U".
[[nodiscard]] const char* toString(ConformanceDecision decision);

/// The decision for a result `value` with expanded uncertainty `expanded_u` (>= 0) against the
/// upper specification limit `upper_limit` (ISO 14253-1:2017 §5.2 and §6.2 for one upper limit).
/// Throws pkm::InvalidArgument for a non-finite input or a negative U.
[[nodiscard]] ConformanceDecision decideConformance(double value,
                                                    double expanded_u,
                                                    double upper_limit);

/// One quantity tested against its tolerance.
struct ConformanceResult {
  std::string quantity;     ///< "E", "M", ...
  double value = 0.0;       ///< the measured value
  double expanded_u = 0.0;  ///< its U (k = 2)
  double tolerance = 0.0;   ///< the upper specification limit T
  ConformanceDecision decision = ConformanceDecision::kUndecided;
};

}  // namespace pkm::metrology
