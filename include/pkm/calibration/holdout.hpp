/// @file
/// @brief Validation of a calibration on data kept out of the fit (docs/calibration.md): the
/// target position the calibrated model predicts from each held-out observation's joint readings
/// or commands, against the position the tracker measured. Hexapod, Exechon and hybrid machine.
#pragma once

#include <optional>
#include <vector>

#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/hybrid_calibration.hpp"
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
  /// |error| of every observation in the order of the data (hexapod: poses, then points), NaN
  /// where there is no prediction (FK failed, command unreachable): for plots of the errors.
  std::vector<double> errors;
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

/// |predicted − measured| over the observations of `held`: the target that `model` predicts
/// (exechonTarget from the observation's joints, `held.target_offset`, FK from `model.home` with
/// `fk`) against the measured point mapped into world by `world_T_measurement` when given
/// (p_w = R·p_m + t). `mean` is not filled.
[[nodiscard]] HoldoutErrors exechonHoldoutErrors(
    const kinematics::ExechonModel& model,
    const std::optional<geometry::RigidTransform>& world_T_measurement,
    const ExechonCalibrationData& held,
    const kinematics::FkOptions& fk);

/// As exechonHoldoutErrors for the hybrid machine: hybridTarget(model, known, squareness,
/// command, held.target_offset, tripod) against the measured point. Commands the tripod cannot
/// reach are skipped (not counted as failures); `mean` is not filled.
[[nodiscard]] HoldoutErrors hybridHoldoutErrors(
    const kinematics::HybridMachineModel& model,
    const kinematics::GeometricErrors& known,
    const kinematics::HybridSquareness& squareness,
    const HybridCalibrationData& held,
    const std::optional<geometry::RigidTransform>& world_T_measurement,
    const TripodMotion& tripod = {});

/// A starting world_T_measurement for hybrid tracker data: the rigid fit of the measured points
/// to the targets `squareness` predicts (geometry::fitRigidTransform). Throws
/// pkm::InvalidArgument "hybrid data: fewer than 3 reachable commands".
[[nodiscard]] geometry::RigidTransform initialHybridMeasurementFrame(
    const kinematics::HybridMachineModel& model,
    const kinematics::GeometricErrors& known,
    const kinematics::HybridSquareness& squareness,
    const HybridCalibrationData& data,
    const TripodMotion& tripod = {});

}  // namespace pkm::calibration
