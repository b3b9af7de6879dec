/// @file
/// @brief What the `pkm calibrate` kinds share (calibrate_command.cpp, calibrate_exechon.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace pkm::cli {

/// Adds `pkm calibrate exechon` to the `calibrate` command (calibrate_exechon.cpp).
void addCalibrateExechon(CLI::App& calibrate);

}  // namespace pkm::cli
