/// @file
/// @brief A calibration in the result store (store::ResultStore, `pkm history`): the data files as
/// measurements, the summary's figures as results, the files for the controller as
/// compensations.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace pkm::workflow {

/// What recordCalibration stores.
struct CalibrationRecord {
  std::string machine;             ///< the machine's name
  std::string machine_type;        ///< "hexapod" or "exechon"
  std::string campaign;            ///< e.g. "calibrate hexapod"
  std::vector<std::string> files;  ///< the data files
  std::string summary_json;        ///< the calibration's summary document
  std::string length_unit;         ///< "mm" or "in"
  /// (target, file path) of each file written for the controller; the file's text is stored.
  std::vector<std::pair<std::string, std::string>> compensations;
};

/// Adds `record` to the result store at `db` (created when missing): the numeric leaves of the
/// summary's `residuals`, `holdout`, `tcp_error_map`, `backlash.values` and `hybrid` members as
/// results (quantity = the JSON path without the stage, stage = before/after/estimate; counts are
/// skipped). Throws pkm::IoError for an unusable store or summary.
void recordCalibration(const std::string& db, const CalibrationRecord& record);

}  // namespace pkm::workflow
