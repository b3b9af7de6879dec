/// @file
/// @brief Helpers shared by the `pkm calibrate` kinds (calibrate_command.cpp,
/// calibrate_exechon.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

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

/// Adds `pkm calibrate exechon` to the `calibrate` command (calibrate_exechon.cpp).
void addCalibrateExechon(CLI::App& calibrate);

}  // namespace pkm::cli
