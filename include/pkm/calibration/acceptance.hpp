/// @file
/// @brief The plausibility rule every calibration applies before its model is used or written
/// (docs/calibration.md, the diagnostics of `pkm calibrate`): a fit whose residuals are not small
/// against the size of the machine did not explain the data (wrong units, wrong frame, outliers, a
/// wrong model), and its parameters must not reach a controller.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace pkm::calibration {

/// The largest acceptable RMS of the fitted residuals, as a fraction of the machine's
/// characteristic length (1 mm on a 1 m machine; metrology-grade data fit to micrometres).
inline constexpr double kAcceptableResidualFraction = 1e-3;

/// True when `residual_rms` (model length unit) is below kAcceptableResidualFraction ×
/// `characteristic_length`; false for NaN.
[[nodiscard]] constexpr bool explainsData(double residual_rms, double characteristic_length) {
  return residual_rms < kAcceptableResidualFraction * characteristic_length;
}

/// The largest plausible change of a calibrated length parameter from the machine file's value,
/// as a fraction of the machine's characteristic length (a hexapod's platform radius, an
/// Exechon's largest base offset): a quarter of it. Assembly errors, even the large illustrative
/// ones of the seed004-hexapod-calibration scenario (after Lee et al., "Development of a
/// Parallel-Typed CNC Machine"; joints off by up to 33 mm on a 250 mm platform), stay inside it;
/// readings in another unit, or a tracker's placement absorbed into the geometry because readings
/// in the tracker's own frame were taken as the machine's, move joints by the machine's size or
/// more.
inline constexpr double kPlausibleChangeFraction = 0.25;
/// The largest plausible change of a calibrated angle parameter, rad (1.15°).
inline constexpr double kPlausibleAngleChange = 0.02;

/// One parameter before and after a calibration.
struct ParameterValues {
  std::string name;         ///< e.g. "base0.y", "tripod.hx"
  double nominal = 0.0;     ///< the machine file's value (model length unit, or rad)
  double calibrated = 0.0;  ///< the estimate (same unit)
  bool is_length = true;    ///< false for an angle (rad)
};

/// A parameter whose change is larger than plausible.
struct ParameterChange {
  ParameterValues values;
  double limit = 0.0;  ///< the plausible change (model length unit, or rad)
  std::string unit;    ///< "mm", "in" or "rad"
  [[nodiscard]] double change() const { return values.calibrated - values.nominal; }
};

/// The parameters whose change |calibrated − nominal| exceeds `fraction` × `characteristic_length`
/// (lengths) or `angle_limit` rad (angles), largest change relative to its limit first. NaN
/// counts as implausible. `length_unit` names the model's length unit in ParameterChange::unit.
[[nodiscard]] std::vector<ParameterChange> implausibleChanges(
    const std::vector<ParameterValues>& parameters,
    double characteristic_length,
    std::string_view length_unit,
    double fraction = kPlausibleChangeFraction,
    double angle_limit = kPlausibleAngleChange);

/// "base0.y: 13.25 → 80.18 in (moved 66.93; plausible ≤ 2.875)".
[[nodiscard]] std::string describe(const ParameterChange& change);

}  // namespace pkm::calibration
