// The uncertainty of a campaign's summary rows (workflow/campaign.hpp, campaign_steps.hpp):
// significance of an improvement and the report's uncertainty section (docs/campaign.md,
// "Uncertainty").
#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <vector>

#include "campaign_steps.hpp"
#include "pkm/workflow/campaign.hpp"

namespace pkm::workflow {

double CampaignRow::combinedU() const { return std::hypot(before_U, after_U); }

double CampaignRow::improvement() const { return std::abs(before) - std::abs(after); }

std::optional<bool> CampaignRow::significant() const {
  const double u = combinedU();
  if (!std::isfinite(before) || !std::isfinite(after) || !std::isfinite(u)) return std::nullopt;
  return improvement() >= u;
}

namespace campaign {
namespace {

/// The improvement |before| − |after| ± its combined U, "not significant" when smaller than
/// that U (a worsening is never significant), null without both values and both U.
Json improvementJson(const SummaryRow& r) {
  const std::optional<bool> significant = r.significant();
  if (!significant) return nullptr;
  if (!*significant) return "not significant";
  return fmt::format("{:.4g} ± {:.2g}", r.improvement(), r.combinedU());
}

}  // namespace

Json significantJson(const SummaryRow& row) {
  const std::optional<bool> s = row.significant();
  return s ? Json(*s) : Json(nullptr);
}

Json uncertaintySection(const std::vector<StepOutcome>& outcomes, const std::string& sources_file) {
  const std::string sources =
      sources_file.empty()
          ? std::string("the typical instruments and environment of docs/analysis.md")
          : fmt::format("the instruments and environment of {}", sources_file);
  Json sec = section(
      "uncertainty",
      "Measurement uncertainty of the summary figures",
      {fmt::format(
          "Expanded uncertainties U (k = 2, GUM; ISO/TR 230-9) with {}. An improvement smaller "
          "than the combined uncertainty sqrt(U_before^2 + U_after^2) is not significant. A TCP "
          "error's U before calibration is the tracker's reading and registration; after "
          "calibration it also carries the calibration's predicted TCP uncertainty (the "
          "calibration step's budget table).",
          sources)});
  Json t = table("Before and after with U (k = 2)",
                 {"step",
                  "quantity",
                  "unit",
                  "before",
                  "U before",
                  "after",
                  "U after",
                  "improvement (before - after)"});
  for (const StepOutcome& s : outcomes)
    for (const SummaryRow& r : s.rows)
      t["rows"].push_back({s.id,
                           r.quantity,
                           r.unit,
                           cell(r.before),
                           cell(r.before_U, 2),
                           cell(r.after),
                           cell(r.after_U, 2),
                           improvementJson(r)});
  sec["tables"].push_back(t);
  // What limits each after-value: within its U the measurement does (its budget's largest
  // contributors say what would have to improve); beyond it, the rest is error of the machine that
  // the compensation's models do not represent (the environment's unmodelled sources).
  Json limits = table(
      "What limits the after-values: within U the measurement; beyond U, the unmodelled remainder",
      {"step",
       "quantity",
       "unit",
       "after",
       "U after",
       "beyond U (unmodelled remainder)",
       "largest contributors to U after"});
  for (const StepOutcome& s : outcomes)
    for (const SummaryRow& r : s.rows) {
      if (!std::isfinite(r.after) || !std::isfinite(r.after_U)) continue;
      const double beyond = std::abs(r.after) - r.after_U;
      limits["rows"].push_back({s.id,
                                r.quantity,
                                r.unit,
                                cell(r.after),
                                cell(r.after_U, 2),
                                beyond > 0.0 ? cell(beyond, 2) : Json("within U"),
                                r.after_limit.empty() ? Json("-") : Json(r.after_limit)});
    }
  sec["tables"].push_back(limits);
  return sec;
}

}  // namespace campaign
}  // namespace pkm::workflow
