/// @file
/// @brief Internal: the uncertainty budgets of `pkm calibrate hexapod` (calibrate_hexapod.cpp) and
/// of the campaign's hexapod calibration step (campaign/campaign_hexapod.cpp): the linear budgets
/// of the calibrated parameters, optionally their Monte Carlo, and the predicted TCP uncertainty at
/// the check poses (docs/calibration.md, "Uncertainty budgets").
#pragma once

#include <string>
#include <vector>

#include "pkm/calibration/hexapod_budget.hpp"
#include "pkm/io/calibration_files.hpp"
#include "pkm/io/calibration_report.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow::detail {

/// What hexapodCalibrationUncertainty needs besides the fit.
struct CalibrationUncertaintyRequest {
  metrology::UncertaintySources sources;                  ///< the instruments
  std::string sources_name = "typical datasheet values";  ///< shown in the outputs
  int monte_carlo_trials = 0;  ///< GUM S1 re-fits, the adaptive procedure's limit (0: none)
  int threads = 1;             ///< Monte Carlo worker threads (0: all cores)
};

/// The check poses of the TCP prediction: the pose the calibrated model `estimated` reaches for
/// the readings of each held-out pose or point observation (FK seeded at the measurement moved by
/// `frame` into world, or at home), those whose FK converges.
[[nodiscard]] std::vector<kinematics::PoseRpy> checkPoses(
    const kinematics::HexapodModel& estimated,
    const calibration::HexapodCalibrationData& held,
    const std::optional<geometry::RigidTransform>& frame);

/// The budgets of `fit` = calibrateHexapod(initial, data, options) and the predicted TCP
/// uncertainty at `check` (labelled `check_label`). Monte Carlo progress is reported through
/// `control` as "uncertainty N/M". Throws pkm::InvalidArgument for invalid sources.
[[nodiscard]] io::HexapodCalibrationReport::Uncertainty hexapodCalibrationUncertainty(
    const kinematics::HexapodModel& initial,
    const calibration::HexapodCalibrationData& data,
    const calibration::HexapodCalibrationSummary& fit,
    const calibration::HexapodCalibrationOptions& options,
    const CalibrationUncertaintyRequest& request,
    const std::vector<kinematics::PoseRpy>& check,
    const std::string& check_label,
    const RunControl& control = {});

/// The budgets of `pkm calibrate hexapod`'s fit `s` with the request's instruments and Monte Carlo
/// trials: the predicted TCP uncertainty at the poses the calibrated model reaches for the
/// held-out readings (else at the workspace poses `ws`), with the model's remainder at the
/// held-out poses (`holdout`'s RMS after calibration, calibration::addTcpRemainder) when given.
[[nodiscard]] io::HexapodCalibrationReport::Uncertainty hexapodRequestUncertainty(
    const HexapodCalibrationRequest& r,
    const kinematics::HexapodModel& model,
    const io::CalibrationInput& input,
    const io::CalibrationInput& held,
    const calibration::HexapodCalibrationSummary& s,
    const std::vector<kinematics::PoseRpy>& ws,
    const calibration::HexapodCalibrationOptions& options,
    const std::optional<io::HexapodCalibrationReport::Holdout>& holdout,
    const RunControl& control);

}  // namespace pkm::workflow::detail
