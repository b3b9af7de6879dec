/// @file
/// @brief Internal: the stacked residuals and identification Jacobian of hexapod calibration data
/// and the check of its values (hexapod_residuals.cpp), shared by the public evaluations there and
/// the solver (calibrateHexapod, hexapod_calibration.cpp).
#pragma once

#include <Eigen/Core>

#include "observations.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"

namespace pkm::calibration::detail {

/// The stacked Jacobian (all observations of `data`, in the order of observations(); 42 columns,
/// + 6 for `frame`, + 6 for `backlash`) and residuals (model length unit) at (model, frame,
/// backlash); frame nullptr: the measurements are in world. Each output is filled when non-null;
/// rows whose FK fails stay zero and count in stats->fk_failures.
void stackHexapodObservations(const kinematics::HexapodModel& model,
                              const HexapodCalibrationData& data,
                              const FrameEstimate* frame,
                              Eigen::MatrixXd* J,
                              Eigen::VectorXd* r,
                              ResidualStatistics* stats,
                              const kinematics::StrutVector* backlash = nullptr);

/// Throws pkm::InvalidArgument naming the first observation of `data` with a non-finite (or, for
/// a distance, negative) value, or a constrained set whose table normal is not a unit vector.
void requireFiniteHexapodData(const HexapodCalibrationData& data);

}  // namespace pkm::calibration::detail
