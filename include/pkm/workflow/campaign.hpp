/// @file
/// @brief The end-to-end campaign (docs/campaign.md): every step of a `pkm.campaign/1` file
/// measures on a virtual machine with known errors (or reads measured files), analyses,
/// calibrates, writes the controller compensation, measures again through the compensating
/// controller, and reports its before/after figures; then the campaign's summary.json,
/// report-data.json, self-contained report.html and, optionally, the result store.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "pkm/metrology/uncertainty_sources.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// One line of a campaign's summary table.
struct CampaignRow {
  std::string quantity;  ///< what, e.g. "parallelism Y2-PY (horizontal)"
  std::string unit;      ///< "mm", "µm", "mrad" ...
  double before = 0.0;   ///< measured before compensation (NaN: not measured)
  double after = 0.0;    ///< measured after compensation on the virtual machine (NaN: none)
  /// The campaign's target for `after` (|after| <= target), when there is one.
  std::optional<double> target;
  std::string paper;  ///< the paper's published before -> after, as text ("" when none)
  std::string noise;  ///< the instrument noise of the measurement
  /// True when there is no target or |after| <= target.
  [[nodiscard]] bool pass() const;
  /// Expanded uncertainty (k = 2, GUM; docs/analysis.md "Measurement uncertainty") of `before`
  /// and `after`, in `unit`; NaN where the value has none (not measured, or no budget yet).
  double before_U = std::numeric_limits<double>::quiet_NaN();
  double after_U = std::numeric_limits<double>::quiet_NaN();
  /// What limits `after`'s U: its budget's largest contributors with their shares of u_c², e.g.
  /// "laser straightness optics 71 %, fit statistics 24 %" ("" when not known); the report sets it
  /// beside the part of `after` beyond U (docs/campaign.md, "Uncertainty").
  std::string after_limit{};
  /// The improvement |before| − |after| in `unit` (an error's size; negative when it grew).
  [[nodiscard]] double improvement() const;
  /// Whether the row shows a significant improvement: improvement() >= the combined uncertainty
  /// √(U_before² + U_after²) (the two measurements independent). A worsening, however large, is
  /// not a significant improvement: false. nullopt when a value or a U is missing.
  [[nodiscard]] std::optional<bool> significant() const;
  /// √(U_before² + U_after²), in `unit`; NaN when either is missing.
  [[nodiscard]] double combinedU() const;
};

/// What one step produced.
struct CampaignStepResult {
  std::string id;     ///< the step's id
  std::string title;  ///< one line
  std::vector<CampaignRow> rows;
  std::vector<std::string> files;  ///< files written, relative to the output directory
};

/// A campaign run.
struct CampaignOptions {
  std::string campaign = "default";  ///< a pkm.campaign/1 file or a built-in campaign's name
  std::filesystem::path out;         ///< the output directory (required)
  bool force = false;                ///< write into a non-empty output directory
  std::string db;                    ///< the result store (SQLite) to add to; empty: none
  /// The campaign document itself (pkm.campaign/1 JSON, e.g. from a front end's dict), used
  /// instead of reading `campaign` when not empty; `campaign` then names it in messages and in
  /// summary.json's "source", and relative file names in it are taken from the current directory.
  std::string campaign_text;
  /// The environment of every simulated step, replacing the step's "environment" and its
  /// scenario's (docs/simulation-errors.md); nullopt: each step's own. Steps on measured files
  /// have none.
  std::optional<simulation::Environment> environment;
  /// How `environment` was given (a preset name or a file), for summary.json and the report.
  std::string environment_source;
  /// The instruments and environment of every step's uncertainty budgets (the U of the summary
  /// rows, docs/analysis.md); nullopt: the typical datasheet values.
  std::optional<metrology::UncertaintySources> uncertainty;
  /// How `uncertainty` was given (its file), for summary.json and the report.
  std::string uncertainty_source;
  /// The random seed of every simulated step, replacing the step's "seed" and its scenario's;
  /// nullopt: each step's own.
  std::optional<std::uint64_t> seed;
  /// Called with each step's result as soon as the step is done, in order (a front end shows the
  /// results as they arrive); may be empty. The step's files are written at the end.
  std::function<void(const CampaignStepResult&)> on_step{};
  /// Throws pkm::IoError "give --out DIR" when `out` is empty, pkm::InvalidArgument for an
  /// environment or uncertainty sources that are not valid (naming the reason).
  void validate() const;
};

/// What a campaign run produced.
struct CampaignResult {
  /// The campaign-level settings in effect, as recorded in summary.json: the environment's source
  /// and name ("" when each step keeps its own), the uncertainty sources' file ("" for the typical
  /// values), the seed (nullopt when each step keeps its own).
  std::string environment_source, environment_name, uncertainty_source;
  std::optional<std::uint64_t> seed;
  std::string name;         ///< the campaign's "name"
  std::string source;       ///< the campaign file, or "builtin:NAME"
  std::string description;  ///< the campaign's "description"
  std::vector<CampaignStepResult> steps;
  int targets = 0;               ///< summary rows with a target
  bool all_pass = true;          ///< every target met
  double seconds = 0.0;          ///< wall-clock time of the run
  std::filesystem::path report;  ///< report.html, absolute
  /// The text of summary.json (pkm.campaign-summary/1, docs/campaign.md), as written.
  std::string summary_json;
};

/// A campaign's name, number of steps and description (`pkm campaign list`).
struct CampaignInfo {
  std::string name;
  std::size_t steps = 0;
  std::string description;
};

/// The built-in campaigns' names (data/campaigns/*.json), sorted.
[[nodiscard]] std::vector<std::string> builtinCampaignNames();

/// Loads and checks the campaign `spec` (a file or a built-in name). Throws pkm::IoError
/// "FILE:LINE: ..." for invalid JSON, a wrong schema, a bad step id or an unknown step kind.
[[nodiscard]] CampaignInfo describeCampaign(const std::string& spec);

/// Runs the campaign. Progress: first an event with index 0, count = the number of steps and
/// message = the campaign's name, once the output directory is ready; then, per step, events
/// with stage = the step's id, index = its 1-based number, elapsed = seconds since the start,
/// ending with "done in X.XX s". Cancellation is checked at every progress event.
/// Throws pkm::IoError for a bad campaign, step or data file (naming it) and for an output
/// directory that is a file or is not empty without `force`; workflow::Cancelled.
/// A missed target is not an error: see CampaignResult::all_pass.
[[nodiscard]] CampaignResult runCampaign(const CampaignOptions& options,
                                         const RunControl& control = {});

}  // namespace pkm::workflow
