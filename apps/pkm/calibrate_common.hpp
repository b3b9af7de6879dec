/// @file
/// @brief Helpers shared by the `pkm calibrate` kinds (calibrate_command.cpp,
/// calibrate_exechon.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "pkm/geometry/rigid_fit.hpp"

namespace pkm::cli {

/// A rigid transform as {"position": [x, y, z], "rpy_deg": [r, p, y]} (machine-file style).
[[nodiscard]] nlohmann::ordered_json frameJson(const geometry::RigidTransform& f);

/// The files a calibration writes: CAL.json, CAL.hal (hexapods), CAL.summary.json.
struct CalibrationOutputs {
  std::string machine, hal, summary;
};

/// The output paths for `--out CAL.json`.
[[nodiscard]] CalibrationOutputs calibrationOutputs(const std::string& out);

/// Writes `text` to `path` (truncating). Throws pkm::IoError when the file cannot be written.
void writeOutputFile(const std::string& path, const std::string& text);

/// Records a calibration in the result store at `db` (io::ResultStore): the data files as
/// measurements, the numeric leaves of the summary's `residuals`, `holdout`, `tcp_error_map`,
/// `backlash` and `hybrid.squareness` members as results (quantity = the JSON path without the
/// stage, stage = before/after/estimate), and `compensations` (target, file path, file text).
void recordCalibration(const std::string& db,
                       const std::string& machine,
                       const std::string& machine_type,
                       const std::string& campaign,
                       const std::vector<std::string>& files,
                       const nlohmann::ordered_json& summary,
                       const std::string& length_unit,
                       const std::vector<std::pair<std::string, std::string>>& compensations);

/// Adds `pkm calibrate exechon` to the `calibrate` command (calibrate_exechon.cpp).
void addCalibrateExechon(CLI::App& calibrate);

}  // namespace pkm::cli
