/// @file
/// @brief `pkm calibrate hexapod --live` (calibrate_live.cpp): its options and run.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "pkm/live/live_calibration.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"

namespace pkm::cli {

/// The --live options as the command line gives them.
struct LiveCalibrateArgs {
  bool live = false;
  live::LiveCalibrationRequest request;
  std::vector<std::string> gauges;
  std::vector<double> gauge_points, reference;
};

/// Adds --live and its options to `pkm calibrate hexapod`.
void addCalibrateLiveOptions(CLI::App& hex, LiveCalibrateArgs& args);

/// Runs the live calibration with the shared options of `fit` (--ini, --out, --force, the prior).
/// Throws pkm::InvalidArgument for a bad option, pkm::IoError for LinuxCNC's refusals.
void runCalibrateLive(LiveCalibrateArgs& args, const workflow::HexapodCalibrationRequest& fit);

}  // namespace pkm::cli
