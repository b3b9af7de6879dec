/// @file
/// @brief Internal: the Ceres least-squares problem of calibrateHexapod — one residual block per
/// observation, the null-space and Tikhonov priors, the fixed parameters held — and its solve
/// (hexapod_least_squares.cpp; the rest of the fit is in hexapod_calibration.cpp).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "pkm/calibration/hexapod_calibration.hpp"

namespace pkm::calibration::detail {

/// The unknowns of a hexapod calibration in their column order: the free parameters, the frame
/// correction (6, when the data have a measurement frame), the backlash (6, when estimated).
struct HexapodUnknownColumns {
  Eigen::Index n_free = 0;  ///< free parameters
  bool has_frame = false;
  Eigen::Index n_frame = 0;  ///< 6 with a measurement frame, else 0
  bool has_backlash = false;
  Eigen::Index n_back = 0;  ///< kStruts with estimate_backlash, else 0
};

/// The values of the unknowns, updated in place by the solve: the 42 parameters (model length
/// unit and rad), the frame correction δ = (δt, δω) and the per-strut backlash (length unit).
struct HexapodUnknownValues {
  HexapodParameterVector theta;
  Eigen::Matrix<double, 6, 1> delta;
  kinematics::StrutVector backlash;
};

/// Minimises the observations' residuals (with the null-space priors and, when prior_weight > 0,
/// the Tikhonov prior) over the unknowns `x`, updated in place from their start; the fixed
/// parameters are held. The solver's report goes into `out`, which must hold the free indices,
/// the initial parameters and the identifiability.
void solveHexapodProblem(const kinematics::HexapodModel& initial,
                         const HexapodCalibrationData& data,
                         const HexapodCalibrationOptions& options,
                         const HexapodUnknownColumns& u,
                         const kinematics::StrutVector& backlash0,
                         double prior_weight,
                         HexapodUnknownValues& x,
                         HexapodCalibrationSummary& out);

}  // namespace pkm::calibration::detail
