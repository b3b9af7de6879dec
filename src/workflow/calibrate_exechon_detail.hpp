/// @file
/// @brief The parts of workflow::calibrateExechon shared between its two sources
/// (calibrate_exechon.cpp: request, files, hybrid squareness; calibrate_exechon_tripod.cpp: the
/// tripod and wrist fit).
#pragma once

#include <string>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/io/exechon_tracker_files.hpp"
#include "pkm/workflow/calibrate_exechon.hpp"

namespace pkm::workflow::detail {

/// "none", "huber" or "cauchy" as a calibration::RobustLoss (anything else: none).
[[nodiscard]] calibration::RobustLoss robustLoss(const std::string& name);

/// The tripod and wrist from the PKM tracker files: the fit, the acceptance rule, the held-out
/// check, the working-box map and the Monte Carlo. Sets `calibrated` to the calibrated machine.
/// May set input.data.measurement_frame (the frame's start). Throws pkm::InvalidArgument for an
/// implausible fit or one that does not explain the data.
[[nodiscard]] io::ExechonTripodReport fitTripod(const ExechonCalibrationRequest& request,
                                                const io::ExechonMachine& machine,
                                                io::ExechonCalibrationInput& input,
                                                const io::ExechonCalibrationInput& held,
                                                io::ExechonMachine& calibrated,
                                                const RunControl& control);

}  // namespace pkm::workflow::detail
