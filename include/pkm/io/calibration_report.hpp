/// @file
/// @brief The summary of a hexapod calibration (`pkm calibrate hexapod`, CAL.summary.json and
/// `--json`; docs/calibration.md lists its members): everything the fit, the held-out check, the
/// outlier ranking, the workspace error map and the Monte Carlo found, as one typed report and as
/// its JSON document (schema pkm.hexapod-calibration-summary/1, documented in docs/formats.md).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "pkm/calibration/frame_registration.hpp"
#include "pkm/calibration/hexapod_budget.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/holdout.hpp"
#include "pkm/calibration/uncertainty.hpp"
#include "pkm/core/units.hpp"

namespace pkm::io {

/// An observation's residual after the fit, and where it came from ("FILE:LINE" or
/// "constrained set N station M").
struct ObservationResidual {
  std::string source;
  double residual = 0.0;  ///< norm of the observation's residual, model length unit
};

/// A hexapod calibration, as reported.
struct HexapodCalibrationReport {
  std::string machine;                        ///< the machine's name (before calibration)
  LengthUnit unit = LengthUnit::kMillimetre;  ///< the machine's length unit
  std::vector<std::string> data_notes;        ///< what was read from each data file
  int poses = 0, points = 0, constrained_sets = 0, distances = 0, equations = 0;
  Eigen::Vector3d target_offset = Eigen::Vector3d::Zero();  ///< the tracker target, tool frame
  calibration::HexapodCalibrationSummary fit;
  std::array<bool, calibration::kHexapodParameters> free{};  ///< which parameters were fitted
  /// Errors on the held-out files, before (nominal model) and after (calibrated model).
  struct Holdout {
    Eigen::Vector3d target_offset = Eigen::Vector3d::Zero();
    calibration::HoldoutErrors before, after;
  };
  std::optional<Holdout> holdout;
  std::vector<ObservationResidual> worst;  ///< the largest residuals after the fit, largest first
  int workspace_poses = 0;                 ///< poses of the TCP error map
  calibration::TcpErrorStatistics tcp_before;  ///< nominal controller on the calibrated machine
  /// --monte-carlo: the spread the calibration leaves, and the noise it was simulated with.
  struct MonteCarlo {
    calibration::MonteCarloSummary summary;
    double sigma_position = 0.0, sigma_orientation = 0.0, sigma_gauge = 0.0;
  };
  std::optional<MonteCarlo> monte_carlo;
  std::string out_machine, out_hal, out_summary;  ///< the files written
  /// The uncertainty budgets of the calibrated parameters and the predicted TCP uncertainty
  /// (docs/calibration.md, "Uncertainty budgets").
  struct Uncertainty {
    std::string sources;  ///< the sources file, or "typical datasheet values"
    calibration::HexapodParameterUncertainty parameters;  ///< linear budgets
    /// --uncertainty-trials: the GUM Supplement 1 propagation of the same inputs.
    std::optional<calibration::BudgetMonteCarloResult> monte_carlo;
    std::string tcp_poses;            ///< where the TCP U is predicted: "held-out", "workspace"
    calibration::TcpUncertainty tcp;  ///< the predicted TCP U at those poses (k)
  };
  std::optional<Uncertainty> uncertainty;
  /// Where the calibrated model's world frame comes from (docs/calibration.md, "Frames"):
  /// "machine" (readings in the machine's world frame), "registered" (tracker-frame readings
  /// moved into world by a registration on fiducial nests), "unregistered" (tracker-frame
  /// readings without one: the frame is where the fit put it; nothing for a controller).
  std::string world_frame = "machine";
  /// The registration of the tracker frame (`--registration FILE`).
  struct Registration {
    std::string file;                    ///< the registration file
    calibration::FrameRegistration fit;  ///< world_T_tracker, residuals, covariance
    double tcp_U = 0.0;  ///< its expanded uncertainty (k = 2) at the TCP, worst workspace pose
  };
  std::optional<Registration> registration;
};

/// The report as JSON text (two-space indent, closing newline): the exact document
/// `pkm calibrate hexapod` writes to CAL.summary.json and prints with --json.
[[nodiscard]] std::string hexapodCalibrationJson(const HexapodCalibrationReport& report);

/// The uncertainty lines of the text summary (value ± U of every estimated unknown with its
/// largest contributor, the full budget of the least certain, the Monte Carlo check, the predicted
/// TCP uncertainty); "" without report.uncertainty.
[[nodiscard]] std::string hexapodCalibrationUncertaintyText(const HexapodCalibrationReport& report);

}  // namespace pkm::io
