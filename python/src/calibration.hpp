/// @file
/// @brief What the calibration binding files share (calibration.cpp: the requests from arrays;
/// calibration_result.cpp: the result object; calibration_plan.cpp: pose planning;
/// calibration_module.cpp: the registration and docstrings). No domain
/// logic: the workflows (workflow::calibrateHexapod, calibrateExechon, planPoses) do the work.
#pragma once

#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "common.hpp"
#include "pkm/workflow/calibrate_exechon.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"

namespace pkm::python {

/// pkm.calibration.CalibrationResult: a workflow's result, its attributes (arrays and the
/// document's members) and the summary document (to_dict).
struct CalibrationResult {
  std::string kind;  ///< "hexapod" or "exechon"
  std::shared_ptr<
      std::variant<workflow::HexapodCalibrationResult, workflow::ExechonCalibrationResult>>
      result;
  py::dict attributes;
  /// Hexapod: the request the result came from, without its data files (the text summary,
  /// workflow::hexapodCalibrationText, needs its settings); null for an Exechon.
  std::shared_ptr<const workflow::HexapodCalibrationRequest> hexapod_request;
  /// The summary JSON text (CAL.summary.json; --json), current after save().
  [[nodiscard]] const std::string& summaryJson() const;
  /// The text summary `pkm calibrate KIND` prints (workflow::hexapodCalibrationText,
  /// exechonCalibrationText), its "wrote" line once save() wrote the files.
  [[nodiscard]] std::string text() const;
};

/// The result object of a hexapod calibration (attributes filled from the report); `request` is
/// the one it came from.
[[nodiscard]] CalibrationResult hexapodResult(workflow::HexapodCalibrationResult result,
                                              const workflow::HexapodCalibrationRequest& request);
/// The result object of an Exechon calibration.
[[nodiscard]] CalibrationResult exechonResult(workflow::ExechonCalibrationResult result);

/// What both calibrations share in their requests.
struct CommonOptions {
  std::string frame;
  py::object target_offset;
  std::vector<std::string> fix;
  std::string loss;
  double loss_scale;
  int monte_carlo;
  double sigma_position, sigma_orientation;
  int threads;
  bool allow_large_changes;
  py::object out;
  bool force;
  py::object db;
};

/// The options only a hexapod calibration has.
struct HexapodOptions {
  bool backlash;
  double prior_sigma, measurement_sigma, prior_uncertainty, sigma_gauge;
  py::object uncertainty;  ///< the sources file of the uncertainty budgets, or None
  int uncertainty_trials;
  py::object registration;  ///< the tracker's readings of the table's nests (a path), or None
};

/// `pkm calibrate hexapod` on the tables of the arguments (calibration.cpp; pkm.calibration.hexapod
/// documents them): arrays, dicts of columns or paths, written as the command's files.
[[nodiscard]] CalibrationResult runHexapodCalibration(const py::object& machine,
                                                      const py::object& poses,
                                                      const py::object& points,
                                                      const py::object& gauges,
                                                      const py::object& gauge_points,
                                                      const py::object& table_normal,
                                                      const py::object& distances,
                                                      const py::object& pivot,
                                                      const py::object& files,
                                                      const py::object& holdout,
                                                      const HexapodOptions& options,
                                                      bool raise_on_failure,
                                                      const CommonOptions& common);

/// `pkm calibrate exechon` on the tables of the arguments (pkm.calibration.exechon documents them).
[[nodiscard]] CalibrationResult runExechonCalibration(const py::object& machine,
                                                      const py::object& points,
                                                      const py::object& hybrid,
                                                      const py::object& files,
                                                      const py::object& holdout,
                                                      const py::object& hybrid_holdout,
                                                      const py::object& errors,
                                                      const py::object& hybrid_target_offset,
                                                      const py::object& uncertainty,
                                                      bool raise_on_failure,
                                                      const CommonOptions& common);

/// Registers CalibrationResult in `m` (calibration_result.cpp).
void exposeCalibrationResult(py::module_& m);
/// Registers plan_poses in `m` (calibration_plan.cpp).
void exposePosePlanning(py::module_& m);

}  // namespace pkm::python
