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

/// Adds `pkm calibrate exechon` to the `calibrate` command (calibrate_exechon.cpp).
void addCalibrateExechon(CLI::App& calibrate);

}  // namespace pkm::cli
