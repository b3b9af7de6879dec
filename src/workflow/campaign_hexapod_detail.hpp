/// @file
/// @brief The parts of the "hexapod-calibration" campaign step shared between its two sources
/// (campaign_hexapod.cpp: measurement, calibration and compensation; campaign_hexapod_report.cpp:
/// the report section).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "campaign_steps.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"

namespace pkm::workflow::campaign::detail {

/// Target-position errors of tracker readings: world = frame · measured, nominal = command pose ·
/// smr offset; one |error| per reading, plus the nominal x and y of the target.
struct TcpErrors {
  std::vector<double> x, y, error;
  double rms = 0.0, max = 0.0;
};

/// What the step's report section shows.
struct HexapodSectionData {
  const io::Scenario& scenario;
  std::uint64_t seed;
  std::size_t poses;  ///< pose observations fitted
  const calibration::HexapodCalibrationSummary& summary;
  const simulation::HexapodVirtualMachine& vm;
  const TcpErrors& tcp_before;     ///< at the held-out poses, before calibration
  const TcpErrors& tcp_after;      ///< at the held-out poses, after calibration
  const LineData& lines_before;    ///< the laser lines before calibration
  const LineData& lines_after;     ///< the laser lines after calibration
  const std::string& positioning;  ///< the laser line shown as positioning error
};

/// The step's report section (id and title from `outcome`): paragraphs, the TCP error maps and the
/// positioning plot, the identifiability and parameter tables. Throws pkm::IoError naming
/// `context` when the positioning measurement is missing.
[[nodiscard]] Json hexapodSection(const StepContext& context,
                                  const StepOutcome& outcome,
                                  const HexapodSectionData& data);

}  // namespace pkm::workflow::campaign::detail
