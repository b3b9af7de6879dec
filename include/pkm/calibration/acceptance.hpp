/// @file
/// @brief The plausibility rule every calibration applies before its model is used or written
/// (docs/calibration.md, the diagnostics of `pkm calibrate`): a fit whose residuals are not small
/// against the size of the machine did not explain the data (wrong units, wrong frame, outliers, a
/// wrong model), and its parameters must not reach a controller.
#pragma once

namespace pkm::calibration {

/// The largest acceptable RMS of the fitted residuals, as a fraction of the machine's
/// characteristic length (1 mm on a 1 m machine; metrology-grade data fit to micrometres).
inline constexpr double kAcceptableResidualFraction = 1e-3;

/// True when `residual_rms` (model length unit) is below kAcceptableResidualFraction ×
/// `characteristic_length`; false for NaN.
[[nodiscard]] constexpr bool explainsData(double residual_rms, double characteristic_length) {
  return residual_rms < kAcceptableResidualFraction * characteristic_length;
}

}  // namespace pkm::calibration
