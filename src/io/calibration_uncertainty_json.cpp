// The "uncertainty" member of the calibration summaries and its text lines
// (io/detail/calibration_uncertainty_json.hpp).
#include "io/detail/calibration_uncertainty_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "io/detail/uncertainty_json.hpp"

namespace pkm::io::detail {

using Json = nlohmann::ordered_json;

namespace {

/// The adaptive rule, as the summary states it.
constexpr const char* kRule =
    "JCGM 101:2008 7.9: batches until 2 s(u)/sqrt(h) <= delta for every unknown, or max trials";

Json tcpJson(const CalibrationUncertaintyView& v) {
  Json per_pose = Json::array();
  for (const double u : v.tcp.expanded) per_pose.push_back(std::isfinite(u) ? Json(u) : Json());
  return Json{{"poses", v.tcp_poses},
              {"count", v.tcp.poses},
              {"unit", v.unit},
              {"U_max", v.tcp.max},
              {"U_mean", v.tcp.mean},
              {"U_remainder", v.tcp.remainder},
              {"U", std::move(per_pose)}};
}

}  // namespace

Json calibrationUncertaintyJson(const CalibrationUncertaintyView& v) {
  Json j;
  j["coverage_factor"] = v.linear.budgets.empty() ? 2.0 : v.linear.budgets.front().coverage_factor;
  j["sources"] = v.sources;
  j["instrument_sigma"] = v.linear.instrument_sigma;
  j["fit_sigma"] = v.linear.fit_sigma;
  std::vector<metrology::MonteCarloResult> mc;
  if (v.monte_carlo != nullptr) mc = v.monte_carlo->unknowns;
  Json parameters = uncertaintyJson(v.linear.budgets, mc);
  parameters.erase("coverage_factor");
  j["parameters"] = std::move(parameters);
  if (v.monte_carlo != nullptr)
    j["monte_carlo"] = Json{{"trials", v.monte_carlo->trials},
                            {"failures", v.monte_carlo->failures},
                            {"batches", v.monte_carlo->batches},
                            {"stabilised", v.monte_carlo->stabilised},
                            {"seconds", v.monte_carlo->seconds},
                            {"rule", kRule}};
  j["tcp"] = tcpJson(v);
  return j;
}

std::string calibrationUncertaintyText(const CalibrationUncertaintyView& v) {
  const auto& budgets = v.linear.budgets;
  if (budgets.empty()) return {};
  std::string t = fmt::format("calibrated parameters (k = {:g}; sources: {}): value ± U\n",
                              budgets.front().coverage_factor,
                              v.sources);
  std::size_t widest = 0;
  for (std::size_t k = 0; k < std::min(budgets.size(), v.text_budgets); ++k) {
    const metrology::UncertaintyBudget& b = budgets[k];
    const auto largest = b.largestContributor();
    t += fmt::format("  {:<12} {:.6f} ± {:.2g} {}\tlargest: {}\n",
                     b.quantity,
                     b.value,
                     b.expandedUncertainty(),
                     b.unit,
                     largest ? b.contributors[*largest].name : "-");
    if (b.unit == budgets[widest].unit &&
        b.expandedUncertainty() > budgets[widest].expandedUncertainty())
      widest = k;
  }
  const metrology::UncertaintyBudget& w = budgets[widest];
  t += fmt::format(
      "budget of {} (U = {:.2g} {}): contributor, value, distribution, sensitivity, "
      "contribution\n",
      w.quantity,
      w.expandedUncertainty(),
      w.unit);
  for (const metrology::UncertaintyContributor& c : w.contributors)
    t += fmt::format("  {}\t{:.3g} {}\t{}\t{:.3g}\t{:.2g} {}\n",
                     c.name,
                     c.value,
                     c.unit,
                     metrology::toString(c.distribution),
                     c.sensitivity,
                     c.contribution(),
                     w.unit);
  if (v.monte_carlo != nullptr) {
    double ratio = 0.0;
    int n = 0;
    for (std::size_t k = 0; k < budgets.size() && k < v.monte_carlo->unknowns.size(); ++k)
      if (const double u = budgets[k].combinedStandardUncertainty(); u > 0.0) {
        ratio += v.monte_carlo->unknowns[k].standard_uncertainty / u;
        ++n;
      }
    t += fmt::format("monte carlo (GUM S1, {} re-fits, {}): u(MC)/u(linear) = {:.3f} on average\n",
                     v.monte_carlo->trials,
                     v.monte_carlo->stabilised ? "stabilised" : "not stabilised at the trial limit",
                     n > 0 ? ratio / n : 0.0);
  }
  t += fmt::format(
      "predicted TCP uncertainty after calibration (k = {:g}, {} {} poses): max {:.2g}, mean "
      "{:.2g} {}\n",
      budgets.front().coverage_factor,
      v.tcp.poses,
      v.tcp_poses,
      v.tcp.max,
      v.tcp.mean,
      v.unit);
  if (v.tcp.remainder > 0.0)
    t += fmt::format("  of which the model's remainder at the held-out poses: {:.2g} {}\n",
                     v.tcp.remainder,
                     v.unit);
  return t;
}

}  // namespace pkm::io::detail
