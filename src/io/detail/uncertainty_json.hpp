/// @file
/// @brief Internal: uncertainty budgets as JSON members of the analysis documents
/// (docs/formats.md, "Uncertainty in result documents").
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pkm/metrology/conformance.hpp"
#include "pkm/metrology/monte_carlo.hpp"
#include "pkm/metrology/uncertainty_budget.hpp"

namespace pkm::io::detail {

/// An analysis document as the files hold it: two-space indented, one final newline.
inline std::string documentText(const nlohmann::ordered_json& document) {
  return document.dump(2) + "\n";
}

/// {"value", "unit", "U", "u_c", "k", "budget": [{"name", "value", "unit", "distribution",
/// "divisor", "standard_uncertainty", "sensitivity", "contribution", "source"}, ...]}.
nlohmann::ordered_json budgetJson(const metrology::UncertaintyBudget& budget);

/// The "uncertainty" member: {"coverage_factor": k, "<quantity>": budgetJson, ...}; an empty
/// object when there are no budgets.
nlohmann::ordered_json uncertaintyJson(const std::vector<metrology::UncertaintyBudget>& budgets);

/// uncertaintyJson with each budget's Monte Carlo propagation (GUM S1; monte_carlo[i] belongs to
/// budgets[i]) as its "monte_carlo" member: {"mean", "u", "U" (= k u), "low", "high", "trials"}.
nlohmann::ordered_json uncertaintyJson(const std::vector<metrology::UncertaintyBudget>& budgets,
                                       const std::vector<metrology::MonteCarloResult>& monte_carlo);

/// The "conformance" member: [{"quantity", "value", "U", "tolerance", "decision"}, ...].
nlohmann::ordered_json conformanceJson(const std::vector<metrology::ConformanceResult>& results);

/// The lines of the tables: "uncertainty (k = K)", then per budget "NAME<TAB>VALUE ± U UNIT<TAB>
/// largest: CONTRIBUTOR" (6 significant digits), then conditionsText; "" when there are no
/// budgets.
std::string uncertaintyText(const std::vector<metrology::UncertaintyBudget>& budgets);

/// The conditions of the first budget that has any, one line each: "condition<TAB>NAME<TAB>VALUE
/// UNIT<TAB>recorded: NOTE" or "…<TAB>assumed (default)" / "assumed (stated)"; "" when none has.
std::string conditionsText(const std::vector<metrology::UncertaintyBudget>& budgets);

/// One line per Monte Carlo propagation: "monte carlo<TAB>NAME<TAB>U = U UNIT<TAB>95 % interval
/// [LOW, HIGH], M trials"; "" when there are none.
std::string monteCarloText(const std::vector<metrology::UncertaintyBudget>& budgets,
                           const std::vector<metrology::MonteCarloResult>& monte_carlo);

/// One line per decision: "conformance<TAB>NAME<TAB>VALUE ± U against T<TAB>DECISION".
std::string conformanceText(const std::vector<metrology::ConformanceResult>& results);

}  // namespace pkm::io::detail
