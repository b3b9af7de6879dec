/// @file
/// @brief A sensitivity study of a campaign (`pkm campaign sensitivity`, docs/campaign.md): one
/// error source of the simulated environment (docs/simulation-errors.md), named by the dotted path
/// of its key in the environment JSON (io::environmentParameters), is set to each of a list of
/// values on top of a base environment, the campaign runs once per value, and every summary row's
/// before/after value and U are collected: sensitivity.json, sensitivity.csv and a self-contained
/// report.html with one plot per summary quantity (the after-value and its ±U band against the
/// source's value).
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "pkm/metrology/uncertainty_sources.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/workflow/campaign.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// A sensitivity study.
struct SensitivityOptions {
  std::string campaign = "default";  ///< a pkm.campaign/1 file or a built-in campaign's name
  /// The campaign document itself, used instead of reading `campaign` when not empty
  /// (CampaignOptions::campaign_text).
  std::string campaign_text;
  /// The swept parameter: a dotted key path of the environment JSON, e.g.
  /// "air.temperature_sensor.offset" (io::environmentParameters lists them).
  std::string source;
  std::vector<double> values;  ///< the values of `source` (its JSON unit), distinct, finite
  std::filesystem::path out;   ///< the output directory (required)
  bool force = false;          ///< write into a non-empty output directory
  /// The environment the source is set on (every other value kept, the source's group switched
  /// on): default the "realistic" preset.
  simulation::Environment base = *simulation::environmentPreset("realistic");
  std::string base_source = "realistic";  ///< how `base` was given, for the outputs
  /// The instruments and environment of the uncertainty budgets; nullopt: typical values.
  std::optional<metrology::UncertaintySources> uncertainty;
  std::string uncertainty_source;     ///< its file, for the outputs
  std::optional<std::uint64_t> seed;  ///< every simulated step's seed; nullopt: each step's own
  /// Throws pkm::IoError "give --out DIR" without `out`; pkm::InvalidArgument for an unknown
  /// source (listing the valid paths), no values, a non-finite or repeated value, or a value the
  /// environment refuses (naming it and the reason).
  void validate() const;
};

/// One row of the study: a summary row of the campaign run with `value`.
struct SensitivityRow {
  double value = 0.0;  ///< the source's value
  std::string step;    ///< the campaign step's id
  CampaignRow row;     ///< its summary row (before, after, U, ...)
};

/// The sensitivity coefficient of one summary quantity: the least-squares slope of its before- and
/// after-value against the source's value, in the row's unit per unit of the source; NaN where
/// fewer than two values are finite.
struct SensitivityCoefficient {
  std::string step;                                          ///< the campaign step's id
  std::string quantity;                                      ///< the summary row's quantity
  std::string unit;                                          ///< the row's unit
  double before = std::numeric_limits<double>::quiet_NaN();  ///< d(before)/d(source)
  double after = std::numeric_limits<double>::quiet_NaN();   ///< d(after)/d(source)
};

/// The least-squares slope of y against x over the pairs whose y is finite: Σ(x − x̄)(y − ȳ) /
/// Σ(x − x̄)²; NaN with fewer than two such pairs.
[[nodiscard]] double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y);

/// What the study produced.
struct SensitivityResult {
  std::string campaign;  ///< the campaign's name
  std::string source;    ///< the swept parameter's path
  std::string unit;      ///< its unit
  std::vector<double> values;
  std::vector<SensitivityRow> rows;  ///< per value (in the given order), the summary rows
  /// One per summary quantity, in the order of the rows.
  std::vector<SensitivityCoefficient> coefficients;
  std::filesystem::path report;  ///< report.html, absolute
  std::string json;              ///< the text of sensitivity.json, as written
  double seconds = 0.0;          ///< wall-clock time
};

/// Runs the study: for each value k, the campaign with CampaignOptions::environment = base with the
/// source set (io::setEnvironmentParameter), written to out/runs/value-K/ (no result store); then
/// out/sensitivity.json (pkm.sensitivity/1), out/sensitivity.csv (value, step, quantity, unit,
/// before, after, before_U, after_U) and out/report.html, with the coefficients. Progress: an event
/// per run (stage "value-K", message "SOURCE = VALUE") and the campaign's own events. Throws as
/// SensitivityOptions::validate and runCampaign; workflow::Cancelled.
[[nodiscard]] SensitivityResult runSensitivity(const SensitivityOptions& options,
                                               const RunControl& control = {});

}  // namespace pkm::workflow
