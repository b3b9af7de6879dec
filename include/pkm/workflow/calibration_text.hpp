/// @file
/// @brief The text summaries `pkm calibrate hexapod` and `pkm calibrate exechon` print
/// (docs/calibration.md), built from a calibration's result so that every front end (the command
/// line, the Python module's `str(result)`) shows the same lines.
#pragma once

#include <string>

#include "pkm/workflow/calibrate_exechon.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"

namespace pkm::workflow {

/// The text summary of a hexapod calibration, one fact per line, each ending in '\n': the data
/// counts, the solver's stop (iterations and wall time, s), identifiability and the unidentifiable
/// combinations, the fitted residuals before -> after (machine unit), the largest residual, the
/// backlash, the held-out TCP error, the nominal controller's workspace TCP error, the Monte Carlo
/// spread (its trial count is request.monte_carlo), the uncertainty lines
/// (io::hexapodCalibrationUncertaintyText) and "wrote CAL.json, CAL.hal, CAL.summary.json" — that
/// last line only once the files are written (result.report.out_machine set). `request` is the one
/// the result came from: its prior_sigma decides the hint on weakly seen dial-gauge combinations.
[[nodiscard]] std::string hexapodCalibrationText(const HexapodCalibrationRequest& request,
                                                 const HexapodCalibrationResult& result);

/// The text summary of an Exechon calibration: the tripod fit's lines (as the hexapod's, with the
/// working-volume tool error and uncertainty, io::exechonCalibrationUncertaintyText), then the
/// hybrid squareness fit's (szX2, sxP, syP, szP and their standard deviations in mrad, residuals
/// before -> after), then "wrote FILES" once files are written (result.written not empty).
[[nodiscard]] std::string exechonCalibrationText(const ExechonCalibrationResult& result);

}  // namespace pkm::workflow
