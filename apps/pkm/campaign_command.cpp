// `pkm campaign run CAMPAIGN --out DIR [--db FILE | --no-db] [--force] [--environment PRESET|FILE]
// [--uncertainty FILE] [--seed N]` and `pkm campaign list`: parses the arguments, runs
// workflow::runCampaign (docs/campaign.md) and prints its progress, summary table and closing
// lines. `pkm campaign sensitivity` is in campaign_sensitivity_command.cpp.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "campaign_options.hpp"
#include "cli_common.hpp"
#include "pkm/workflow/campaign.hpp"

namespace pkm::cli {
namespace {

struct RunArgs {
  workflow::CampaignOptions options;
  std::string out;
  std::string db = "pkm.db";
  bool no_db = false;
  CampaignSettingArgs settings;  ///< --environment, --uncertainty, --seed
};

std::string numText(double v) {
  if (!std::isfinite(v)) return "-";
  return fmt::format("{:.4g}", v);
}

std::string targetText(const workflow::CampaignRow& r) {
  return r.target ? fmt::format("<= {:g}", *r.target) : "";
}

/// The summary table printed after the steps.
std::string summaryTable(const workflow::CampaignResult& result) {
  std::string table = fmt::format("\n{:<10} {:<52} {:>10} {:>10} {:>9} {:<6} {}\n",
                                  "step",
                                  "quantity",
                                  "before",
                                  "after",
                                  "target",
                                  "unit",
                                  "result");
  for (const workflow::CampaignStepResult& s : result.steps)
    for (const workflow::CampaignRow& r : s.rows)
      table += fmt::format("{:<10} {:<52} {:>10} {:>10} {:>9} {:<6} {}\n",
                           s.id,
                           r.quantity,
                           numText(r.before),
                           numText(r.after),
                           targetText(r),
                           r.unit,
                           r.target ? (r.pass() ? "PASS" : "FAIL") : "");
  return table;
}

/// "VALUE ± U" (4 and 2 significant digits), "VALUE" without U, "-" without a value.
std::string withU(double value, double u) {
  if (!std::isfinite(value)) return "-";
  if (!std::isfinite(u)) return numText(value);
  return fmt::format("{:.4g} ± {:.2g}", value, u);
}

/// The rows with an expanded uncertainty: before ± U -> after ± U and the improvement, or "not
/// significant" when it is smaller than √(U_before² + U_after²), then the paper's figures.
std::string uncertaintyTable(const workflow::CampaignResult& result) {
  std::string table = "\nuncertainty (k = 2): before -> after, improvement\n";
  for (const workflow::CampaignStepResult& s : result.steps)
    for (const workflow::CampaignRow& r : s.rows) {
      if (!std::isfinite(r.before_U) && !std::isfinite(r.after_U)) continue;
      const std::optional<bool> significant = r.significant();
      table += fmt::format("{:<10} {:<52} {} -> {} {}",
                           s.id,
                           r.quantity,
                           withU(r.before, r.before_U),
                           withU(r.after, r.after_U),
                           r.unit);
      if (significant)
        table += *significant
                     ? fmt::format("  improvement {}", withU(r.before - r.after, r.combinedU()))
                     : std::string("  not significant");
      if (!r.paper.empty()) table += fmt::format("  (paper: {})", r.paper);
      table += "\n";
    }
  return table;
}

/// Per row with an after-value and its U: whether the after-value lies within U (then the
/// measurement limits it) or beyond (the remainder is error the compensation's models do not
/// represent), and the largest contributors to U.
std::string limitTable(const workflow::CampaignResult& result) {
  std::string table = "\nwhat limits the after-values (k = 2):\n";
  for (const workflow::CampaignStepResult& s : result.steps)
    for (const workflow::CampaignRow& r : s.rows) {
      if (!std::isfinite(r.after) || !std::isfinite(r.after_U)) continue;
      const double beyond = std::abs(r.after) - r.after_U;
      table += fmt::format("{:<10} {:<52} ", s.id, r.quantity);
      table += beyond > 0.0
                   ? fmt::format("{:.2g} {} beyond U: unmodelled remainder", beyond, r.unit)
                   : std::string("within U: the measurement");
      if (!r.after_limit.empty()) table += fmt::format("; U from {}", r.after_limit);
      table += "\n";
    }
  return table;
}

/// Runs the campaign; returns false when a target was missed.
bool runCampaign(RunArgs a) {
  a.options.out = a.out;
  a.options.db = a.no_db ? std::string() : a.db;
  a.settings.apply(a.options);
  workflow::RunControl control;
  control.progress = [&a](const workflow::ProgressEvent& e) {
    if (e.index == 0)
      fmt::print("pkm campaign '{}': {} steps -> {}\n", e.message, e.count, a.out);
    else
      fmt::print("  [{}/{} {} {:5.1f} s] {}\n", e.index, e.count, e.stage, e.elapsed, e.message);
    std::fflush(stdout);
  };
  const workflow::CampaignResult r = workflow::runCampaign(a.options, control);
  if (!r.environment_source.empty())
    fmt::print(
        "environment of every simulated step: {} ({})\n", r.environment_source, r.environment_name);
  if (!r.uncertainty_source.empty())
    fmt::print("uncertainty budgets: instruments and environment of {}\n", r.uncertainty_source);
  fmt::print("{}", summaryTable(r));
  fmt::print("{}", uncertaintyTable(r));
  fmt::print("{}", limitTable(r));
  fmt::print("\n{} in {:.2f} s; report: {}\n",
             r.targets == 0 ? "no targets (nothing measured after compensation)"
             : r.all_pass   ? fmt::format("all targets met ({})", r.targets)
                            : std::string("SOME TARGETS MISSED"),
             r.seconds,
             r.report.string());
  if (!a.no_db)
    fmt::print("results stored in {} (pkm history --machine NAME --db {})\n", a.db, a.db);
  if (!r.all_pass) {
    std::fflush(stdout);
    fmt::print(stderr, "pkm: a campaign target was missed (see the summary)\n");
  }
  return r.all_pass;
}

void addCampaign(CLI::App& app) {
  CLI::App* group = app.add_subcommand("campaign",
                                       "end-to-end campaign: measure, analyse, calibrate, "
                                       "compensate, re-measure, report (docs/campaign.md)");
  group->require_subcommand(1);
  auto a = std::make_shared<RunArgs>();
  CLI::App* run =
      group->add_subcommand("run", "run a campaign (a pkm.campaign/1 file or a built-in name)");
  run->add_option(
      "campaign", a->options.campaign, "campaign file or built-in name (default: default)");
  run->add_option("--out,-o", a->out, "output directory (report.html, summary.json, step folders)")
      ->required();
  run->add_option("--db", a->db, "result store (SQLite), default pkm.db");
  run->add_flag("--no-db", a->no_db, "do not store the results");
  run->add_flag("--force", a->options.force, "write into a non-empty output directory");
  a->settings.add(*run,
                  "the environment of every simulated step, replacing the steps' own: a preset "
                  "(ideal, realistic) or an environment file (docs/simulation-errors.md)");
  run->callback([a] {
    if (!runCampaign(*a)) throw ExitCode{kExitCheckFailed};
  });
  addCampaignSensitivityCommand(*group);
  CLI::App* list = group->add_subcommand("list", "list the built-in campaigns");
  list->callback([] {
    for (const std::string& name : workflow::builtinCampaignNames()) {
      const workflow::CampaignInfo info = workflow::describeCampaign(name);
      fmt::print("{}\t{} steps\t{}\n", name, info.steps, info.description);
    }
  });
}

const CommandRegistration kRegisterCampaign{110, "campaign", &addCampaign};

}  // namespace
}  // namespace pkm::cli
