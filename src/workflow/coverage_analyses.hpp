// The analyses of `pkm validate coverage` (workflow/coverage.hpp): every quantity with a U that
// pkm's analyses report on one simulation's files.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pkm/io/scenario.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"
#include "pkm/workflow/simulate.hpp"

namespace pkm::workflow::detail {

/// One quantity an analysis reported, with its budget's figures.
struct CoverageReading {
  std::string group;     ///< the measurement or analysis, e.g. "linear-x", "body diagonals"
  std::string quantity;  ///< the budget's quantity, e.g. "E", "squareness_xy"
  std::string unit;
  double value = 0.0;
  double U = 0.0;
  double u_c = 0.0;
  double k = 2.0;
  /// The true value when the reading knows it itself (a calibrated parameter: the virtual
  /// machine's true geometry); unset: the perfect-instrument run's value of the same quantity.
  std::optional<double> truth = std::nullopt;
};

/// Runs the analyses a user would run on the files of `simulation` (a simulation of `scenario`),
/// with the instruments of `sources`, through the same workflow functions as `pkm analyze`: ISO
/// 230-2 of every continuous linear measurement, the straightness of every straightness
/// measurement, the body, step and shifted diagonals when the scenario has them (diag-*, step-*,
/// shift-*), the MXT700S parallelism paper's parallelism pairs (straightness-y2-h/-py-h, -v) and
/// every touch probe's circles and stylus offset. Returns every budget's value and U. Throws as the
/// analyses (naming the file).
[[nodiscard]] std::vector<CoverageReading> coverageReadings(
    const io::Scenario& scenario,
    const SimulateResult& simulation,
    const metrology::UncertaintySources& sources);

/// The calibrations a user would run on the files of `simulation`. A hexapod: the laser tracker's
/// 6-DOF poses with the registration (tracker-pose.csv and its registration file) and the dial
/// gauges (constrained-motion.csv, with the default campaign's prior), each through
/// workflow::calibrateHexapod with the instruments of `sources`; readings: every parameter with
/// its U against the machine's true parameter, and each coordinate of the TCP error at the
/// held-out poses (tracker-holdout.csv) against the predicted TCP U. A hybrid machine with tripod
/// errors and a tracker-fit.csv: the Exechon tracker calibration (held out
/// tracker-holdout.csv) through workflow::calibrateExechon, every estimated tripod parameter
/// against the true tripod's. Empty otherwise. Throws as the calibrations.
[[nodiscard]] std::vector<CoverageReading> calibrationReadings(
    const io::Scenario& scenario,
    const SimulateResult& simulation,
    const metrology::UncertaintySources& sources);

/// The injected squareness of the scenario's Cartesian machine as readings "squareness_xy",
/// "squareness_xz", "squareness_yz" (rad) of `group`; empty for another machine.
[[nodiscard]] std::vector<CoverageReading> injectedSquareness(const io::Scenario& scenario,
                                                              const std::string& group);

}  // namespace pkm::workflow::detail
