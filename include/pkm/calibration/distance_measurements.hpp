/// @file
/// @brief Distance observations of a hexapod for calibration (the ball-bar constraint of PKM
/// calibration, generalised): a length measured between the TCP and a fixed point (a ball bar on a
/// pivot at a known position) or between the TCPs of two configurations (a laser interferometer
/// along a diagonal, zeroed at its first target). Distances see no rigid motion of the whole
/// machine, so they identify shape, not placement (docs/calibration.md, "Distances").
#pragma once

#include <Eigen/Core>
#include <optional>

#include "pkm/calibration/hexapod_measurements.hpp"

namespace pkm::calibration {

/// One distance: |p_TCP(readings) − p_from| = distance, p_from being the TCP at `readings_from`
/// when given, else the fixed point `from_point` (world frame). Model length unit.
struct DistanceObservation {
  kinematics::StrutVector readings = kinematics::StrutVector::Zero();
  std::optional<kinematics::StrutVector> readings_from;  ///< the other end on the machine
  Eigen::Vector3d from_point = Eigen::Vector3d::Zero();  ///< the other end fixed (world)
  double distance = 0.0;                                 ///< measured, ≥ 0
};

/// Jacobian of one distance residual with respect to the 42 parameters.
using DistanceParameterJacobian = Eigen::Matrix<double, 1, kHexapodParameters>;

/// The residual r = |p_a − p_b| − distance (model length unit) with p_a = FK(readings) and p_b
/// the other end, FK seeded with `seed` for both; J = uᵀ·(dp_a/dθ − dp_b/dθ), u the unit vector
/// from p_b to p_a (the FK point Jacobians of pointResiduals). nullopt when an FK does not
/// converge or the two ends coincide (direction undefined). Uses `data` as workspace.
[[nodiscard]] std::optional<double> distanceResidual(const kinematics::HexapodModel& model,
                                                     kinematics::HexapodData& data,
                                                     const DistanceObservation& observation,
                                                     const kinematics::PoseRpy& seed,
                                                     DistanceParameterJacobian* J = nullptr);

}  // namespace pkm::calibration
