/// @file
/// @brief What the calibration binding files share (calibration.cpp: the requests from arrays;
/// calibration_result.cpp: the result object; calibration_plan.cpp: pose planning). No domain
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
  /// The summary JSON text (CAL.summary.json; --json), current after save().
  [[nodiscard]] const std::string& summaryJson() const;
};

/// The result object of a hexapod calibration (attributes filled from the report).
[[nodiscard]] CalibrationResult hexapodResult(workflow::HexapodCalibrationResult result);
/// The result object of an Exechon calibration.
[[nodiscard]] CalibrationResult exechonResult(workflow::ExechonCalibrationResult result);

/// Registers CalibrationResult in `m` (calibration_result.cpp).
void exposeCalibrationResult(py::module_& m);
/// Registers plan_poses in `m` (calibration_plan.cpp).
void exposePosePlanning(py::module_& m);

}  // namespace pkm::python
