/// @file
/// @brief The campaign's step kinds (workflow/campaign.hpp, docs/campaign.md): measure ->
/// analyse -> calibrate -> compensate -> re-measure -> report. A campaign (`pkm.campaign/1`) is a
/// list of steps; each step kind (src/workflow/campaign/campaign_<kind>.cpp) simulates its
/// scenario's measurements on the virtual machine (or reads measured files), analyses them, writes
/// the controller compensation, applies it to the virtual machine, measures again and returns its
/// before/after figures and report section.
#pragma once

#include <fmt/format.h>

#include <filesystem>
#include <functional>
#include <list>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/metrology/iso230_2.hpp"
#include "pkm/metrology/recorded_conditions.hpp"
#include "pkm/metrology/uncertainty_budget.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"
#include "pkm/simulation/campaign.hpp"
#include "pkm/simulation/touch_probe.hpp"
#include "pkm/store/result_store.hpp"
#include "pkm/workflow/campaign.hpp"

namespace pkm::workflow::campaign {

using Json = nlohmann::ordered_json;

/// One line of the summary table.
using SummaryRow = CampaignRow;

/// What one step produced.
struct StepOutcome {
  std::string id;     ///< the step's id
  std::string title;  ///< one line
  std::vector<SummaryRow> rows;
  Json section;  ///< the report section (pkm.report/1 "sections" entry)
  /// What goes into the result store besides the summary rows (the command adds those).
  store::CampaignRecord record;
  std::vector<std::string> files;  ///< files written, relative to the campaign's --out
};

/// What a step gets.
struct StepContext {
  Json spec;                       ///< the step's JSON object
  std::string source;              ///< "CAMPAIGN_FILE: steps[k]" for messages
  std::filesystem::path out;       ///< the campaign's output directory
  std::filesystem::path dir;       ///< out / id: the step's own directory
  std::filesystem::path base_dir;  ///< the campaign file's directory (relative data paths)
  /// The campaign-level environment replacing the step's and its scenario's (stepScenario).
  std::optional<simulation::Environment> environment;
  /// The campaign-level seed replacing the step's and its scenario's (stepScenario).
  std::optional<std::uint64_t> seed;
  /// The instruments and environment of the step's uncertainty budgets.
  metrology::UncertaintySources sources;
  /// Reports one progress line (and checks for cancellation).
  std::function<void(const std::string&)> progress;
  /// Writes `text` to dir / `name` (creating folders) and records it in `outcome.files`.
  void write(StepOutcome& outcome, const std::string& name, const std::string& text) const;
  /// write(), and records the file as a compensation of kind `kind` for the result store.
  void writeCompensation(StepOutcome& outcome,
                         const std::string& kind,
                         const std::string& name,
                         const std::string& text) const;
};

/// A step kind: runs one step. Throws pkm::IoError / pkm::InvalidArgument for bad input.
using StepRunner = StepOutcome (*)(const StepContext& context);

/// The step kinds: "hybrid-squareness" (MXT700S parallelism paper), "cartesian-diagonals"
/// (Hwang et al., "Analysis of multi-axis volumetric errors"), "probe-offset" (Lee et al. 2019),
/// "hexapod-calibration" (Lee et al., "Development of a Parallel-Typed CNC Machine").
StepOutcome runHybridSquarenessStep(const StepContext& context);
StepOutcome runCartesianDiagonalsStep(const StepContext& context);
StepOutcome runProbeOffsetStep(const StepContext& context);
StepOutcome runHexapodCalibrationStep(const StepContext& context);
/// "hexapod-calibration" with "data" (measured files) instead of "scenario".
StepOutcome runHexapodCalibrationFiles(const StepContext& context);

/// A report plot (pkm.report/1).
Json plot(const std::string& id,
          const std::string& title,
          const std::string& kind,
          const std::string& x_label,
          const std::string& y_label);
/// Adds a series {label, x, y} to `plot`.
void addSeries(Json& plot,
               const std::string& label,
               const std::vector<double>& x,
               const std::vector<double>& y);
/// A report table.
Json table(const std::string& title, const std::vector<std::string>& columns);
/// A number rounded to `digits` significant digits for a report cell (null when not finite).
Json cell(double value, int digits = 4);
/// A report section with id, title and paragraphs.
Json section(const std::string& id, const std::string& title, std::vector<std::string> text);
/// Whether the row's improvement exceeds its combined U (CampaignRow::significant): true, false
/// or null.
Json significantJson(const SummaryRow& row);
/// The report's last section: every summary row with U (k = 2) before and after and the
/// improvement, or "not significant" (docs/campaign.md, "Uncertainty"); `sources_file` names the
/// uncertainty sources given ("": the typical values).
Json uncertaintySection(const std::vector<StepOutcome>& outcomes, const std::string& sources_file);

}  // namespace pkm::workflow::campaign

namespace pkm::workflow::campaign {

/// The line measurements of a scenario by name, with their results.
struct LineData {
  std::vector<simulation::MeasurementResult> results;
  /// Records not in the readings: the set-up's (dead path, beam alignment) from the environment of
  /// a simulated step (setupRecords); a measured step's files' environment columns and metadata.
  metrology::RecordedConditions records;
  /// The runs of measurement `name`; throws pkm::IoError naming `source` when there is none.
  [[nodiscard]] const std::vector<simulation::LineRun>& runs(const std::string& name,
                                                             const std::string& source) const;
  /// Whether measurement `name` is there.
  [[nodiscard]] bool has(const std::string& name) const;
  /// The set-up of measurement `name` (throws as runs).
  [[nodiscard]] const simulation::LineSetup& setup(const std::string& name,
                                                   const std::string& source) const;
};

/// The set-up records of a simulated measurement in `environment`: its dead path when the air
/// source is on, its beam alignment bound when the set-up source is on (docs/formats.md,
/// "Environment records"); empty otherwise.
[[nodiscard]] metrology::RecordedConditions setupRecords(
    const simulation::Environment& environment);

/// What the linear readings of `data` recorded (their compensation unit's sensors,
/// simulation::SensedConditions) with `data.records`.
[[nodiscard]] metrology::RecordedConditions recordedConditions(const LineData& data);

/// `sources` at the conditions `data` recorded (metrology::withRecordedConditions): the budgets
/// of a campaign's laser rows use the measurement's own conditions.
[[nodiscard]] metrology::UncertaintySources sourcesAt(const metrology::UncertaintySources& sources,
                                                      const LineData& data);

/// Writes every run of `data` into `folder` of the step (`name_runK.csv`, the simulator format).
void writeLineFiles(const StepContext& context,
                    StepOutcome& outcome,
                    const std::string& folder,
                    const io::Scenario& scenario,
                    std::uint64_t seed,
                    const LineData& data);

/// ISO 230-2 of line runs (reading − target = deviation), coverage k = 2.
[[nodiscard]] metrology::Iso230_2Result iso230_2(const std::vector<simulation::LineRun>& runs);

/// A summary row's target (docs/campaign.md, "Targets"): on an ideal virtual machine (every error
/// one the analysis models) compensation must come down to the instruments' noise, `ideal`; on a
/// machine with the unmodelled error sources of a non-ideal environment (docs/simulation-errors.md)
/// it must reach what the paper reached on its real machine, `paper`.
[[nodiscard]] inline double stepTarget(const io::Scenario& scenario, double ideal, double paper) {
  return scenario.campaign.environment.active() ? paper : ideal;
}

/// The expanded uncertainty U (k = 2) of the budget of `quantity` in `budgets`; NaN when there
/// is none.
[[nodiscard]] double expandedU(const std::vector<metrology::UncertaintyBudget>& budgets,
                               const std::string& quantity);

/// "NAME SHARE %, NAME SHARE %": the (at most) two largest contributors of `budget` with their
/// shares of u_c² (correlations left out of the shares); "" for an empty budget.
[[nodiscard]] std::string largestContributors(const metrology::UncertaintyBudget& budget);

/// The largest contributors (largestContributors) of the budget of `quantity` in `budgets`; ""
/// when there is none.
[[nodiscard]] std::string largestContributors(
    const std::vector<metrology::UncertaintyBudget>& budgets, const std::string& quantity);

/// U (k = 2, mm) of ISO 230-2's `quantity` ("E", "M", "A", "B", "R") of `result` with the
/// instrument and environment `sources` (metrology::iso230_2Uncertainty); NaN for unidirectional
/// data.
[[nodiscard]] double iso230_2U(const metrology::Iso230_2Result& result,
                               const std::string& quantity,
                               const metrology::UncertaintySources& sources);

/// Sets `row`'s after_U and after_limit from the ISO 230-2 budget of `quantity` of `after`.
void setIso230_2AfterU(SummaryRow& row,
                       const metrology::Iso230_2Result& after,
                       const std::string& quantity,
                       const metrology::UncertaintySources& sources);

/// Per target: (target, mean over runs and both directions of the reading), sorted by target.
void meanReadings(const std::vector<simulation::LineRun>& runs,
                  std::vector<double>& targets,
                  std::vector<double>& means);

/// The seed of the re-measurement after compensation: seed + 1, so that the instruments and the
/// machine's repeatability draw new noise (a table made from one measurement must not be checked
/// against the same noise).
[[nodiscard]] inline std::uint64_t remeasureSeed(std::uint64_t seed) { return seed + 1; }

/// The scenario of the re-measurement after compensation: the same, one campaign duration later
/// on its environment's clock (simulation::Environment::elapsed_h; nothing changes in the ideal
/// environment), so that drifts and warm-up are not the ones the compensation was made from.
[[nodiscard]] inline io::Scenario remeasureScenario(io::Scenario scenario) {
  scenario.campaign.environment.elapsed_h += scenario.campaign.environment.duration_h;
  return scenario;
}

/// Laser measurement files (the `pkm simulate` line format, any number of runs per measurement)
/// read from a folder, with set-ups rebuilt from their metadata. `data` points into `setups`
/// (list nodes keep their addresses when the struct is moved).
struct LineFiles {
  std::list<simulation::LineSetup> setups;
  LineData data;
  std::vector<std::string> paths;
};
/// Reads every `*.csv` of `folder` whose `# format` is pkm.measurement/1, grouped by
/// `# measurement`: quantity from `# quantity`, line from `# line start`/`# line direction`,
/// noise from `# noise` (sigma and ppm, when given), the cycle from the targets; runs from the
/// `run` column. Throws pkm::IoError "FILE:LINE: message" for malformed metadata or rows, and
/// naming the folder when it holds no measurement file.
[[nodiscard]] LineFiles readLineFolder(const StepContext& context, const std::string& folder);
/// The step's "data": {"folder": DIR}; throws pkm::IoError naming the step otherwise.
[[nodiscard]] std::string dataFolder(const StepContext& context);

/// Measured touch-probe files of a "probe-offset" step ("data": {"offset", "circle_before",
/// "circle_after"}; the `pkm simulate` format): the set-up from their metadata and the touches.
struct ProbeFiles {
  simulation::TouchProbeSetup setup;
  std::vector<simulation::TouchRecord> offset, before, after;
  std::vector<std::string> paths;  ///< offset, circle_before, circle_after
};
/// Reads them; throws pkm::IoError "FILE:LINE: message" for a missing column or metadata key, a
/// bad number, or a set-up that cannot be (a ball larger than the ring, a tilted tool).
[[nodiscard]] ProbeFiles readProbeFiles(const StepContext& context);

/// The virtual machine of `scenario` as a `Machine` (simulation::CartesianMachine, ...). Throws
/// pkm::IoError "SOURCE: scenario 'NAME' is not a KIND scenario" when it is another kind.
template <class Machine>
[[nodiscard]] std::shared_ptr<Machine> scenarioMachine(const StepContext& context,
                                                       const io::Scenario& scenario,
                                                       std::string_view kind) {
  auto vm = std::dynamic_pointer_cast<Machine>(scenario.campaign.machine);
  if (!vm)
    throw IoError(fmt::format(
        "{}: scenario '{}' is not a {} scenario", context.source, scenario.campaign.name, kind));
  return vm;
}

/// The scenario named by the step's "scenario" (a file relative to the campaign's folder, or a
/// built-in name) and the seed ("seed", default the scenario's; the campaign's seed, when set,
/// replaces both); the step's "environment" (a preset name, simulation::environmentPreset)
/// replaces the scenario's environment, and the campaign's environment, when set, replaces both.
[[nodiscard]] io::Scenario stepScenario(const StepContext& context, std::uint64_t& seed);

}  // namespace pkm::workflow::campaign
