/// @file
/// @brief Closed-form hexapod inverse kinematics and the analytic strut Jacobian.
#pragma once

#include <Eigen/Core>

#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::kinematics {

/// Strut readings for a TCP pose: reading_i = |p + R·a_i − b_i| − offset_i, with a_i, b_i the
/// effective joint points (HexapodModel::effectivePlatform/effectiveBase). Also fills data's pose,
/// leg vectors, unit vectors and distances. Readings may lie outside the stroke: use checkPose for
/// limits. A zero-length strut gives a zero unit vector. Returns data.readings.
const StrutVector& inverseKinematics(const HexapodModel& model,
                                     HexapodData& data,
                                     const PoseRpy& pose);

/// As above with the orientation given as a rotation matrix; data.pose.rpy is set from it.
const StrutVector& inverseKinematics(const HexapodModel& model,
                                     HexapodData& data,
                                     const Eigen::Vector3d& world_p_tcp,
                                     const Eigen::Matrix3d& world_R_platform);

/// The strut Jacobian J_q_x at the pose of the last inverseKinematics call: row i is
/// [u_iᵀ, (R·a_i × u_i)ᵀ] with u_i the unit leg vector (Lee et al., "Development of a
/// Parallel-Typed CNC Machine", eq. for dL; genhexkins' inverse Jacobian). Columns: TCP
/// displacement (world), then world-frame rotation vector. Returns data.J_q_x.
const Matrix6d& computeStrutJacobian(const HexapodModel& model, HexapodData& data);

/// Condition number (largest / smallest singular value) of J_q_x with its angular columns divided
/// by model.characteristicLength(), so that it does not depend on the length unit. Infinity when
/// singular. Uses data.J_q_x: call computeStrutJacobian first.
[[nodiscard]] double scaledConditionNumber(const HexapodModel& model, const HexapodData& data);

}  // namespace pkm::kinematics
