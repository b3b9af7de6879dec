/// @file
/// @brief `pkm calibrate hexapod` as a workflow (docs/calibration.md): the 42 kinematic parameters
/// of a hexapod from laser-tracker pose/point files, dial-gauge and distance files; the acceptance
/// rule; the held-out check; the outlier ranking; the TCP error map of the workspace; optionally
/// a Monte Carlo of the calibration; then the calibrated machine file, its LinuxCNC setp block and
/// the summary, and optionally a record in the result store.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pkm/io/calibration_report.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// A hexapod calibration request.
struct HexapodCalibrationRequest {
  std::string machine = "default";  ///< machine file, LinuxCNC .hal, or built-in name
  /// A machine already loaded (a second front end's object): used instead of `machine` when set.
  std::optional<io::HexapodMachine> loaded;
  std::string ini;  ///< the LinuxCNC INI of a .hal machine ("" : found from it)
  /// Calibration files, read whole or uploaded (required; io::addCalibrationFile).
  std::vector<io::NamedText> data;
  std::vector<io::NamedText> holdout;  ///< tracker files kept out of the fit
  /// CAL.json; CAL.hal and CAL.summary.json beside it. "" : nothing written (a front end that
  /// keeps the result; writeHexapodCalibration writes it later); needs `db` empty.
  std::string out;
  std::string frame = "auto";  ///< tracker readings: "auto" (files' metadata), "world", "tracker"
  /// The tracker's readings of fiducial nests on the table from the placement of the --data and
  /// --holdout files (io::parseRegistrationCsv): fixes world_T_tracker, so the calibrated model is
  /// in the machine's world frame. Without it, tracker-frame data give a model marked
  /// "world_frame": "unregistered", which nothing that feeds a controller accepts.
  std::optional<io::NamedText> registration;
  /// The tracker target in the tool frame; default the files' `smr offset mm`.
  std::optional<Eigen::Vector3d> target_offset;
  std::vector<std::string> fix;  ///< parameters held at their initial value (e.g. "offset0")
  std::string loss = "none";     ///< robust loss: "none", "huber", "cauchy"
  double loss_scale = 0.0;       ///< robust loss scale, machine unit
  bool force = false;            ///< replace existing output files
  /// Write a result whose parameters moved implausibly far from the machine file
  /// (calibration::kPlausibleChangeFraction); refused without it.
  bool allow_large_changes = false;
  bool backlash = false;           ///< also estimate a per-strut backlash
  double prior_sigma = 0.0;        ///< Tikhonov prior σ_θ, machine unit (0: none)
  double measurement_sigma = 0.0;  ///< residual σ for the prior and covariance (0: estimated)
  /// The machine file's geometry as an input of the uncertainty budgets, σ per parameter, machine
  /// unit (0: prior_sigma; calibration::HexapodCalibrationOptions::prior_uncertainty).
  double prior_uncertainty = 0.0;
  int monte_carlo = 0;                  ///< Monte Carlo trials (0: none; else 2 … 100000)
  double sigma_position = 0.0;          ///< Monte Carlo position noise (0: the fitted σ)
  double sigma_orientation_urad = 0.0;  ///< Monte Carlo 6-DOF orientation noise, µrad
  double sigma_gauge = 0.0;             ///< Monte Carlo gauge noise (0: the fitted σ)
  int threads =
      0;  ///< worker threads: Monte Carlo trials, workspace sampling beside the fit (0: all cores)
  std::string db;  ///< result store to record the calibration in ("" : none)
  /// Instruments of the uncertainty budgets (`--uncertainty FILE`; default: typical datasheet
  /// values; docs/calibration.md, "Uncertainty budgets").
  metrology::UncertaintySources uncertainty;
  std::string uncertainty_name;  ///< the sources file's name ("" : the typical values)
  /// GUM Supplement 1 Monte Carlo of the budgets: the adaptive procedure's trial limit (0: the
  /// linear budgets only; else >= 20).
  int uncertainty_trials = 0;
  /// Throws pkm::InvalidArgument naming the option for an unusable setting.
  void validate() const;
};

/// What a hexapod calibration produced.
struct HexapodCalibrationResult {
  io::HexapodCalibrationReport report;  ///< every figure (io::hexapodCalibrationJson)
  std::string summary_json;             ///< the summary document, as written
  io::HexapodMachine calibrated;        ///< the calibrated machine, as written
  std::vector<std::string> notices;     ///< the machine reader's notes and the data files' notes
};

/// The output paths for `--out CAL.json`: CAL.json, CAL.hal (the genhexkins setp block),
/// CAL.summary.json, and CAL.pkmhexkins.hal (the pkmhexkins setp block; hexapods only).
struct CalibrationOutputs {
  std::string machine, hal, summary, pkmhexkins;
};
[[nodiscard]] CalibrationOutputs calibrationOutputs(const std::string& out);

/// Runs the calibration and, with request.out, writes its files (writeHexapodCalibration).
/// Progress: Monte Carlo trials ("Monte Carlo N/M"), with cancellation checked between them. Throws
/// pkm::IoError for unreadable files (FILE:LINE), pkm::InvalidArgument for a bad request, too few
/// observations or a fit that does not explain the data (calibration::explainsData) — in which case
/// nothing is written.
[[nodiscard]] HexapodCalibrationResult calibrateHexapod(const HexapodCalibrationRequest& request,
                                                        const RunControl& control = {});

/// Writes a calibration's files as `pkm calibrate hexapod --out OUT` does: the calibrated machine
/// OUT (io::writeHexapodJson), the genhexkins and pkmhexkins setp blocks and the summary (its
/// outputs set to these paths first: result.report.out_* and result.summary_json are updated).
/// Atomic writes; throws pkm::IoError when a file exists and not `force` (checked for all four
/// before any is written) or cannot be written.
void writeHexapodCalibration(HexapodCalibrationResult& result, const std::string& out, bool force);

}  // namespace pkm::workflow
