// `pkm campaign sensitivity CAMPAIGN --source PATH --values V1,V2,... --out DIR [--seed N]
// [--environment BASE] [--uncertainty FILE] [--force]`: parses the arguments, runs
// workflow::runSensitivity (docs/campaign.md, "Sensitivity study") and prints its progress, a
// table of every summary figure after compensation, ± U, per value, and the coefficients.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "campaign_options.hpp"
#include "cli_common.hpp"
#include "pkm/workflow/campaign_sensitivity.hpp"

namespace pkm::cli {
namespace {

struct SensitivityArgs {
  workflow::SensitivityOptions options;
  std::string out;
  CampaignSettingArgs settings;  ///< --environment (the base), --uncertainty, --seed
};

/// "AFTER ± U" of a row (the before-value, marked, where there is no after-value); "-" without
/// either.
std::string sensitivityCell(const workflow::CampaignRow& r) {
  const bool after = std::isfinite(r.after);
  const double v = after ? r.after : r.before;
  const double u = after ? r.after_U : r.before_U;
  if (!std::isfinite(v)) return "-";
  const std::string text =
      std::isfinite(u) ? fmt::format("{:.4g} ± {:.2g}", v, u) : fmt::format("{:.4g}", v);
  return after ? text : text + " (b)";
}

/// The table: one line per summary quantity, one column per value.
std::string sensitivityTable(const workflow::SensitivityResult& r) {
  std::vector<std::pair<std::string, std::string>> keys;
  for (const workflow::SensitivityRow& row : r.rows) {
    const std::pair<std::string, std::string> key{row.step, row.row.quantity};
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  std::string t = fmt::format(
      "\nafter compensation ± U (k = 2) for each value of {} ({}); (b): before, "
      "where nothing is measured after\n{:<10} {:<52}",
      r.source,
      r.unit,
      "step",
      "quantity");
  for (const double v : r.values) t += fmt::format(" {:>22}", fmt::format("{:g}", v));
  t += "  unit\n";
  for (const auto& [step, quantity] : keys) {
    t += fmt::format("{:<10} {:<52}", step, quantity);
    std::string unit;
    for (const double v : r.values) {
      std::string cell = "-";
      for (const workflow::SensitivityRow& row : r.rows)
        if (row.value == v && row.step == step && row.row.quantity == quantity) {
          cell = sensitivityCell(row.row);
          unit = row.row.unit;
        }
      t += fmt::format(" {:>22}", cell);
    }
    t += fmt::format("  {}\n", unit);
  }
  return t;
}

/// "VALUE" with 4 significant digits, "-" when not finite.
std::string coefficientText(double v) { return std::isfinite(v) ? fmt::format("{:.4g}", v) : "-"; }

/// The coefficients: one line per summary quantity, d(before)/dx and d(after)/dx.
std::string coefficientTable(const workflow::SensitivityResult& r) {
  std::string t = fmt::format(
      "\nsensitivity coefficients (least-squares slope per {} of {})\n{:<10} {:<52} {:>14} {:>14}  "
      "unit\n",
      r.unit,
      r.source,
      "step",
      "quantity",
      "d(before)",
      "d(after)");
  for (const workflow::SensitivityCoefficient& c : r.coefficients)
    t += fmt::format("{:<10} {:<52} {:>14} {:>14}  {}/{}\n",
                     c.step,
                     c.quantity,
                     coefficientText(c.before),
                     coefficientText(c.after),
                     c.unit,
                     r.unit);
  return t;
}

void runSensitivityCommand(SensitivityArgs a) {
  a.options.out = a.out;
  workflow::CampaignOptions settings;
  a.settings.apply(settings);
  if (settings.environment) {
    a.options.base = *settings.environment;
    a.options.base_source = settings.environment_source;
  }
  a.options.uncertainty = settings.uncertainty;
  a.options.uncertainty_source = settings.uncertainty_source;
  a.options.seed = settings.seed;
  workflow::RunControl control;
  control.progress = [](const workflow::ProgressEvent& e) {
    fmt::print("  [{}/{} {} {:5.1f} s] {}\n", e.index, e.count, e.stage, e.elapsed, e.message);
    std::fflush(stdout);
  };
  fmt::print("pkm campaign sensitivity '{}': {} = {} ({} values, base environment {}) -> {}\n",
             a.options.campaign,
             a.options.source,
             fmt::join(a.options.values, ", "),
             a.options.values.size(),
             a.options.base_source,
             a.out);
  const workflow::SensitivityResult r = workflow::runSensitivity(a.options, control);
  fmt::print("{}", sensitivityTable(r));
  fmt::print("{}", coefficientTable(r));
  fmt::print("\n{} runs in {:.2f} s; sensitivity.json, sensitivity.csv; report: {}\n",
             r.values.size(),
             r.seconds,
             r.report.string());
}

}  // namespace

void addCampaignSensitivityCommand(CLI::App& campaign) {
  auto a = std::make_shared<SensitivityArgs>();
  CLI::App* cmd = campaign.add_subcommand(
      "sensitivity",
      "run a campaign once per value of one environment error source and plot how each result "
      "and its U respond (docs/campaign.md)");
  cmd->add_option(
      "campaign", a->options.campaign, "campaign file or built-in name (default: default)");
  cmd->add_option("--source",
                  a->options.source,
                  "the error source: a dotted key path of the environment JSON, e.g. "
                  "air.temperature_sensor.offset (an unknown path lists the valid ones)")
      ->required();
  cmd->add_option("--values",
                  a->options.values,
                  "the source's values in its unit, comma-separated (e.g. -0.2,0,0.2)")
      ->required()
      ->delimiter(',');
  cmd->add_option("--out,-o", a->out, "output directory (sensitivity.json/.csv, report.html)")
      ->required();
  cmd->add_flag("--force", a->options.force, "write into a non-empty output directory");
  a->settings.add(*cmd,
                  "the base environment the source is set on: a preset (ideal, realistic) or an "
                  "environment file (default: realistic)");
  cmd->callback([a] { runSensitivityCommand(*a); });
}

}  // namespace pkm::cli
