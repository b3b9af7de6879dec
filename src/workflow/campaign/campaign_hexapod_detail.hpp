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
#include "pkm/io/calibration_report.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/simulation/campaign.hpp"
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
  std::size_t poses;             ///< pose observations fitted
  std::size_t constrained_sets;  ///< constrained-motion (dial-gauge) sets fitted
  const calibration::HexapodCalibrationSummary& summary;
  const simulation::HexapodVirtualMachine& vm;
  const TcpErrors& tcp_before;     ///< at the held-out poses, before calibration
  const TcpErrors& tcp_after;      ///< at the held-out poses, after calibration
  const LineData& lines_before;    ///< the laser lines before calibration
  const LineData& lines_after;     ///< the laser lines after calibration
  const std::string& positioning;  ///< the laser line shown as positioning error
  /// The calibration's uncertainty budgets (the budget table); nullptr: none.
  const io::HexapodCalibrationReport::Uncertainty* uncertainty = nullptr;
};

/// The table positions (world frame, mm) of the fiducial nests that register the tracker.
[[nodiscard]] const std::vector<Eigen::Vector3d>& fiducialNests();

/// The expanded uncertainties (k = 2, mm) of the TCP error rows and what they combine.
struct TcpRowUncertainty {
  double measurement = 0.0;  ///< U of one held-out TCP error reading: tracker and registration
  double predicted = 0.0;    ///< the calibration's predicted TCP U, largest over the held-out poses
  double before_U = 0.0;     ///< = measurement
  double after_U = 0.0;      ///< √(measurement² + predicted²)
  io::HexapodCalibrationReport::Uncertainty budget;  ///< the calibration's budgets
};

/// The budgets of the campaign's calibration `fit` = calibrateHexapod(model, data, options) with
/// the instruments of `sources` (the tracker's range taken as the longest of the held-out readings)
/// and the U of the TCP error rows at the held-out readings of `holdout`
/// (docs/campaign.md, "Uncertainty"): one reading's U from the tracker's a + b·L at its range and
/// the registration on the fiducial nests (u·√(1/n + d²/Σ|r_i|²), d the target's distance from
/// the nests' centroid), and the predicted TCP U at the held-out commands.
[[nodiscard]] TcpRowUncertainty tcpRowUncertainty(
    const kinematics::HexapodModel& model,
    const calibration::HexapodCalibrationData& data,
    const calibration::HexapodCalibrationSummary& fit,
    const calibration::HexapodCalibrationOptions& options,
    const simulation::TrackerResult& holdout,
    const geometry::RigidTransform& world_T_tracker,
    const metrology::UncertaintySources& sources);

/// The report table of the calibration budget: the parameters with the largest U, each with its
/// two largest contributors and their shares of u_c².
[[nodiscard]] Json budgetTable(const io::HexapodCalibrationReport::Uncertainty& u);

/// The step's report section (id and title from `outcome`): paragraphs, the TCP error maps and the
/// positioning plot, the identifiability and parameter tables. Throws pkm::IoError naming
/// `context` when the positioning measurement is missing.
[[nodiscard]] Json hexapodSection(const StepContext& context,
                                  const StepOutcome& outcome,
                                  const HexapodSectionData& data);

}  // namespace pkm::workflow::campaign::detail
