/// @file
/// @brief `pkm calibrate exechon` as a workflow (docs/calibration.md, "Exechon"): the 26
/// kinematic parameters of an Exechon (Zoppi's tripod dimensions with leg B's base-joint offsets,
/// leg offsets, wrist zeros, tool length, base placement) from PKM tracker files, and/or the four
/// squareness errors of the hybrid machine from hybrid tracker files; the acceptance rule, the
/// held-out checks, the working-box error map, optionally a Monte Carlo; then the calibrated
/// machine file, CAL.errors.json with hybrid data, the summary and optionally a result-store
/// record.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pkm/io/exechon_calibration_report.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// An Exechon calibration request.
struct ExechonCalibrationRequest {
  std::string machine = "mxt700s-like";  ///< Exechon machine file or built-in name
  /// A machine already loaded (a second front end's object): used instead of `machine` when set.
  std::optional<io::ExechonMachine> loaded;
  /// Exechon and hybrid tracker files, read whole or uploaded (required).
  std::vector<io::NamedText> data;
  std::vector<io::NamedText> holdout;  ///< tracker files kept out of the fit
  /// CAL.json; CAL.summary.json (and CAL.errors.json) beside it. "" : nothing written (a front
  /// end that keeps the result; writeExechonCalibration writes it later); needs `db` empty.
  std::string out;
  std::string frame = "auto";  ///< tracker readings: "auto", "world", "tracker"
  /// The tracker target in the tool frame; default the files' `smr offset mm`.
  std::optional<Eigen::Vector3d> target_offset;
  std::vector<std::string> fix;  ///< parameters held at their initial value (e.g. "tripod.hx")
  std::string loss = "none";     ///< robust loss: "none", "huber", "cauchy"
  double loss_scale = 0.0;       ///< robust loss scale, machine unit
  std::string errors;  ///< hybrid: the known geometric errors (PDGE) under the squareness fit
  bool force = false;  ///< replace existing output files
  /// Write a result whose parameters moved implausibly far from the machine file
  /// (calibration::kPlausibleChangeFraction); refused without it.
  bool allow_large_changes = false;
  int monte_carlo = 0;                  ///< Monte Carlo trials of the tripod fit (0: none)
  double sigma_position = 0.0;          ///< Monte Carlo point noise (0: the fitted σ)
  double sigma_orientation_urad = 0.0;  ///< Monte Carlo tool-direction noise, µrad
  int threads = 0;                      ///< Monte Carlo worker threads (0: all cores)
  std::string db;                       ///< result store to record the calibration in ("" : none)
  /// Instruments of the tripod fit's uncertainty budgets (`--uncertainty FILE`; default:
  /// typical datasheet values; docs/calibration.md, "Uncertainty budgets").
  metrology::UncertaintySources uncertainty;
  std::string uncertainty_name;  ///< the sources file's name ("" : the typical values)
  /// GUM Supplement 1 re-fits of the budgets (calibration::exechonBudgetMonteCarlo), the adaptive
  /// procedure's limit (0: none); workers from `threads`.
  int uncertainty_trials = 0;
  /// Throws pkm::InvalidArgument naming the option for an unusable setting.
  void validate() const;
};

/// What an Exechon calibration produced.
struct ExechonCalibrationResult {
  io::ExechonCalibrationReport report;  ///< every figure (io::exechonCalibrationJson)
  std::string summary_json;             ///< the summary document, as written
  io::ExechonMachine calibrated;        ///< the calibrated machine, as written
  /// With hybrid data: the estimated geometric errors (CAL.errors.json,
  /// io::writeGeometricErrorsJson).
  std::string errors_json;
  std::vector<std::string> written;  ///< the files written, in order (none without request.out)
};

/// CAL.errors.json for `--out CAL.json`.
[[nodiscard]] std::string calibrationErrorsOutput(const std::string& out);

/// Runs the calibration and, with request.out, writes its files (writeExechonCalibration). Notices:
/// the machine reader's and the data files' notes. Progress: Monte Carlo trials, cancellation
/// checked after them. Throws pkm::IoError for unreadable files (FILE:LINE), pkm::InvalidArgument
/// for a bad request, hybrid data without a hybrid machine, or a fit that does not explain the data
/// or is implausible — in which case nothing is written.
[[nodiscard]] ExechonCalibrationResult calibrateExechon(const ExechonCalibrationRequest& request,
                                                        const RunControl& control = {});

/// Writes a calibration's files as `pkm calibrate exechon --out OUT` does: the calibrated machine
/// OUT (io::writeExechonJson), CAL.errors.json with hybrid data, and the summary (its outputs set
/// to these paths first: result.report.out_*, result.summary_json and result.written are
/// updated). Atomic writes; throws pkm::IoError when a file exists and not `force` (checked for
/// all before any is written) or cannot be written.
void writeExechonCalibration(ExechonCalibrationResult& result, const std::string& out, bool force);

}  // namespace pkm::workflow
