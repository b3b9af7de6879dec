/// @file
/// @brief Validation of a hexapod calibration on data kept out of the fit (docs/calibration.md):
/// the TCP position that forward kinematics predicts from each held-out observation's strut
/// readings, against the position the tracker measured.
#pragma once

#include <optional>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/geometry/rigid_fit.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::calibration {

/// Held-out TCP position errors, model length unit.
struct HoldoutErrors {
  int poses = 0;      ///< observations whose FK converged (counted)
  int failures = 0;   ///< observations whose FK did not converge (not counted)
  double rms = 0.0;   ///< root mean square of |error|
  double max = 0.0;   ///< largest |error|
  double mean = 0.0;  ///< mean |error|
};

/// |FK(q) − measured| over the poses and points of `held` (their positions), FK from `model.home`.
/// `world_T_measurement`, when given, maps FK's world position into the measurement frame first
/// (p_m = Rᵀ(p_w − t)); `backlash`, when given, is removed from the readings as half the
/// per-strut hysteresis in each observation's approach direction (q − ½·approach ∘ backlash).
[[nodiscard]] HoldoutErrors hexapodHoldoutErrors(
    const kinematics::HexapodModel& model,
    const std::optional<geometry::RigidTransform>& world_T_measurement,
    const HexapodCalibrationData& held,
    const std::optional<kinematics::StrutVector>& backlash = std::nullopt);

}  // namespace pkm::calibration
