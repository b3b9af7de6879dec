// Uncertainty budgets as JSON members of the analysis documents (io/detail/uncertainty_json.hpp).
#include "io/detail/uncertainty_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace pkm::io::detail {

using Json = nlohmann::ordered_json;

namespace {

/// Degrees of freedom as JSON: null for infinite (a Type B value taken as exact).
Json dofJson(double nu) { return std::isfinite(nu) ? Json(nu) : Json(nullptr); }

}  // namespace

Json budgetJson(const metrology::UncertaintyBudget& budget) {
  Json rows = Json::array();
  for (const metrology::UncertaintyContributor& c : budget.contributors) {
    rows.push_back(Json{{"name", c.name},
                        {"value", c.value},
                        {"unit", c.unit},
                        {"distribution", metrology::toString(c.distribution)},
                        {"divisor", c.divisor()},
                        {"standard_uncertainty", c.standardUncertainty()},
                        {"sensitivity", c.sensitivity},
                        {"contribution", c.contribution()},
                        {"degrees_of_freedom", dofJson(c.degrees_of_freedom)},
                        {"source", c.source}});
  }
  Json out{{"value", budget.value},
           {"unit", budget.unit},
           {"U", budget.expandedUncertainty()},
           {"u_c", budget.combinedStandardUncertainty()},
           {"k", budget.coverageFactor()},
           {"nu_eff", dofJson(budget.effectiveDegreesOfFreedom())},
           {"budget", std::move(rows)}};
  if (!budget.conditions.empty()) {
    Json conditions = Json::array();
    for (const metrology::BudgetCondition& c : budget.conditions)
      conditions.push_back(Json{{"name", c.name},
                                {"value", c.value},
                                {"unit", c.unit},
                                {"origin", c.origin},
                                {"note", c.note}});
    out["conditions"] = std::move(conditions);
  }
  return out;
}

Json uncertaintyJson(const std::vector<metrology::UncertaintyBudget>& budgets) {
  Json out = Json::object();
  if (budgets.empty()) return out;
  out["coverage_factor"] = budgets.front().coverage_factor;
  for (const metrology::UncertaintyBudget& b : budgets) out[b.quantity] = budgetJson(b);
  return out;
}

Json uncertaintyJson(const std::vector<metrology::UncertaintyBudget>& budgets,
                     const std::vector<metrology::MonteCarloResult>& monte_carlo) {
  Json out = uncertaintyJson(budgets);
  for (std::size_t i = 0; i < budgets.size() && i < monte_carlo.size(); ++i) {
    const metrology::MonteCarloResult& m = monte_carlo[i];
    out[budgets[i].quantity]["monte_carlo"] =
        Json{{"mean", m.mean},
             {"u", m.standard_uncertainty},
             {"U", budgets[i].coverage_factor * m.standard_uncertainty},
             {"low", m.low},
             {"high", m.high},
             {"trials", m.trials}};
  }
  return out;
}

Json conformanceJson(const std::vector<metrology::ConformanceResult>& results) {
  Json out = Json::array();
  for (const metrology::ConformanceResult& r : results) {
    out.push_back(Json{{"quantity", r.quantity},
                       {"value", r.value},
                       {"U", r.expanded_u},
                       {"tolerance", r.tolerance},
                       {"decision", metrology::toString(r.decision)}});
  }
  return out;
}

std::string uncertaintyText(const std::vector<metrology::UncertaintyBudget>& budgets) {
  if (budgets.empty()) return {};
  // k of the header holds at infinite degrees of freedom; a line with a finite ν_eff prints the
  // Student's t factor it used.
  std::string out = fmt::format("uncertainty (k = {})\n", budgets.front().coverage_factor);
  for (const metrology::UncertaintyBudget& b : budgets) {
    const auto largest = b.largestContributor();
    const double nu = b.effectiveDegreesOfFreedom();
    const std::string k =
        std::isfinite(nu) ? fmt::format(" (nu_eff {:.3g}, k {:.3g})", nu, b.coverageFactor()) : "";
    out += fmt::format("{}\t{:.6g} ± {:.2g} {}{}\tlargest: {}\n",
                       b.quantity,
                       b.value,
                       b.expandedUncertainty(),
                       b.unit,
                       k,
                       largest ? b.contributors[*largest].name : "-");
  }
  out += conditionsText(budgets);
  return out;
}

std::string conditionsText(const std::vector<metrology::UncertaintyBudget>& budgets) {
  const auto with = std::find_if(
      budgets.begin(), budgets.end(), [](const auto& b) { return !b.conditions.empty(); });
  if (with == budgets.end()) return {};
  std::string out;
  for (const metrology::BudgetCondition& c : with->conditions) {
    const std::string origin = c.origin == "recorded" ? "recorded" : "assumed (" + c.origin + ")";
    out += fmt::format("condition\t{}\t{:.6g} {}\t{}{}\n",
                       c.name,
                       c.value,
                       c.unit,
                       origin,
                       c.note.empty() ? "" : ": " + c.note);
  }
  return out;
}

std::string monteCarloText(const std::vector<metrology::UncertaintyBudget>& budgets,
                           const std::vector<metrology::MonteCarloResult>& monte_carlo) {
  std::string out;
  for (std::size_t i = 0; i < budgets.size() && i < monte_carlo.size(); ++i) {
    const metrology::MonteCarloResult& m = monte_carlo[i];
    out +=
        fmt::format("monte carlo\t{}\tU = {:.2g} {}\t95 % interval [{:.6g}, {:.6g}], {} trials\n",
                    budgets[i].quantity,
                    budgets[i].coverage_factor * m.standard_uncertainty,
                    budgets[i].unit,
                    m.low,
                    m.high,
                    m.trials);
  }
  return out;
}

std::string conformanceText(const std::vector<metrology::ConformanceResult>& results) {
  std::string out;
  for (const metrology::ConformanceResult& r : results) {
    out += fmt::format("conformance\t{}\t{:.6g} ± {:.2g} against {:.6g}\t{}\n",
                       r.quantity,
                       r.value,
                       r.expanded_u,
                       r.tolerance,
                       metrology::toString(r.decision));
  }
  return out;
}

}  // namespace pkm::io::detail
