/// @file
/// @brief `pkm validate coverage` (docs/coverage.md): pkm's simulator proves its own uncertainty
/// statements. Each scenario is simulated over many seeds; every quantity an analysis reports with
/// an expanded uncertainty U is compared with the simulator's true value of the same measurand —
/// the value the same test gives on the same virtual machine, in the same thermal and structural
/// state, read by a perfect instrument (no noise, exact air and material compensation to 20 °C,
/// no set-up error; simulation::Environment::perfect_instrument) — and, for a squareness, with
/// the injected squareness too. Per
/// quantity: the coverage (fraction of seeds with |value − truth| <= U), the mean and spread of the
/// normalised errors (value − truth)/u_c, the bias, and whether U is absurdly wide.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "pkm/metrology/uncertainty_sources.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// The scenarios `pkm validate coverage` runs by default: the built-in scenarios whose analyses
/// report a U (the MXT700S parallelism paper's parallelism, Hwang et al.'s ("Analysis of multi-axis
/// volumetric errors") diagonals, Lee et al.'s (2019) probe and ring, on an ideal and on an
/// uncalibrated PKM, the calibrations of Lee et al.'s ("Development of a Parallel-Typed CNC
/// Machine") hexapod and the Exechon's tracker calibration).
[[nodiscard]] std::vector<std::string> defaultCoverageScenarios();

/// A coverage run.
struct CoverageOptions {
  std::vector<std::string> scenarios;  ///< scenario files or built-in names; empty: the default
  int seeds = 20;                      ///< simulated seeds per scenario, >= 2
  std::uint64_t first_seed = 1;        ///< the seeds are first_seed, first_seed + 1, ...
  /// The workshop environment of the measured runs (a preset or file); nullopt: each scenario's
  /// own. The truth runs keep it (the same machine state) and read it with a perfect instrument.
  std::optional<simulation::Environment> environment;
  std::string environment_source;  ///< how `environment` was given, for the outputs
  /// The instruments of every budget (what `--uncertainty FILE` gives the analyses).
  metrology::UncertaintySources uncertainty{};
  std::string uncertainty_source;  ///< its file ("" for the typical values)
  /// Only quantities whose "group quantity" name contains one of these (empty: all).
  std::vector<std::string> only;
  /// Throws pkm::InvalidArgument for fewer than 2 seeds, pkm::IoError for a scenario that
  /// cannot be loaded, pkm::InvalidArgument for invalid uncertainty sources.
  void validate() const;
};

/// One seed's reading of one quantity.
struct CoverageTrial {
  std::uint64_t seed = 0;
  double value = 0.0;  ///< the analysis' value
  double truth = 0.0;  ///< the true value of the measurand
  double U = 0.0;      ///< the stated expanded uncertainty
  double u_c = 0.0;    ///< its combined standard uncertainty
  double k = 2.0;      ///< the coverage factor used (Student's t at nu_eff)
  /// |value − truth| <= U.
  [[nodiscard]] bool covered() const;
};

/// One quantity over all seeds.
struct CoverageQuantity {
  std::string scenario;  ///< the scenario's name
  std::string group;     ///< the measurement (or analysis) it comes from, e.g. "linear-x"
  std::string quantity;  ///< the budget's quantity, e.g. "E"; "… vs injected" for a squareness
  std::string unit;
  std::string truth_kind;  ///< "perfect instrument" or "injected"
  std::vector<CoverageTrial> trials;
  [[nodiscard]] double coverage() const;  ///< fraction of covered trials
  [[nodiscard]] double bias() const;      ///< mean of value − truth, in `unit`
  [[nodiscard]] double errorRms() const;  ///< RMS of value − truth, in `unit`
  [[nodiscard]] double meanU() const;     ///< mean stated U, in `unit`
  [[nodiscard]] double meanZ() const;     ///< mean of (value − truth)/u_c
  [[nodiscard]] double spreadZ() const;   ///< standard deviation of (value − truth)/u_c
  /// The lowest coverage consistent with 95 % at this number of trials: 0.95 − 2σ of a binomial
  /// proportion, √(0.95·0.05/N) (92 % at N = 200).
  [[nodiscard]] double acceptableCoverage() const;
  /// coverage() >= acceptableCoverage().
  [[nodiscard]] bool holds() const;
  /// Whether pkm's U claims to cover this truth: every quantity against the perfect instrument.
  /// Not a squareness against the injected one: the diagonal methods cannot separate squareness
  /// from the machine's other geometric errors (ISO 230-6:2002 §1; docs/coverage.md), so those
  /// rows measure the method's bias on the virtual machine.
  [[nodiscard]] bool claimed() const;
  /// meanU() > 3 × errorRms() (and errorRms() > 0): a U that covers by width, not by
  /// knowledge; a finding to explain (docs/coverage.md).
  [[nodiscard]] bool wide() const;
};

/// What a coverage run produced.
struct CoverageResult {
  int seeds = 0;
  std::uint64_t first_seed = 1;
  std::vector<std::string> scenarios;
  std::string environment;  ///< the environment's source ("" : each scenario's own)
  std::string uncertainty;  ///< the uncertainty sources' file ("" : typical values)
  std::vector<CoverageQuantity> quantities;
  double seconds = 0.0;
  /// Claimed quantities (CoverageQuantity::claimed) that hold (holds()).
  [[nodiscard]] std::size_t holding() const;
  /// The number of claimed quantities.
  [[nodiscard]] std::size_t claims() const;
};

/// Runs the scenarios over the seeds. Progress: one event per scenario and seed (stage = the
/// scenario, index = the seed's number, count = seeds). Throws as CoverageOptions::validate,
/// pkm::InvalidArgument when an analysis refuses a simulated file (naming it), Cancelled.
[[nodiscard]] CoverageResult validateCoverage(const CoverageOptions& options,
                                              const RunControl& control = {});

/// The terminal table: one line per quantity (scenario, group, quantity, N, coverage, mean U,
/// bias, RMS error, mean and spread of z, flags), then the count that holds.
[[nodiscard]] std::string coverageText(const CoverageResult& result);
/// coverage.json (schema pkm.coverage/1, docs/coverage.md), every trial included.
[[nodiscard]] std::string coverageJson(const CoverageResult& result);
/// A pkm.report/1 document: the table and a plot of coverage per quantity with the 95 % line.
[[nodiscard]] std::string coverageReportData(const CoverageResult& result);

/// Writes coverage.json, report-data.json and report.html into `dir` (created); without `force`
/// refuses (pkm::IoError naming the file) when one of them exists, before writing anything.
void writeCoverage(const CoverageResult& result, const std::filesystem::path& dir, bool force);

}  // namespace pkm::workflow
