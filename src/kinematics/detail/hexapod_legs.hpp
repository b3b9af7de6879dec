/// @file
/// @brief Internal: leg vectors, distances and readings for a pose given as (p, R), without the
/// roll-pitch-yaw extraction that the public inverseKinematics does (the FK inner loop uses this).
#pragma once

#include <Eigen/Core>

#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::kinematics::detail {

/// Fills data.world_R_platform, world_p_tcp, world_r_joint, world_p_platform_joint, leg, unit_leg,
/// joint_distance, inverse_joint_distance and readings. data.pose is left unchanged.
void computeLegs(const HexapodModel& model,
                 HexapodData& data,
                 const Eigen::Vector3d& world_p_tcp,
                 const Eigen::Matrix3d& world_R_platform);

/// computeLegs, and the strut residuals r = data.readings − target (each computed with its reading,
/// so that no caller reads back the readings just stored). Returns max_i |r_i| (NaN when a
/// residual is NaN).
double computeLegsResidual(const HexapodModel& model,
                           HexapodData& data,
                           const Eigen::Vector3d& world_p_tcp,
                           const Eigen::Matrix3d& world_R_platform,
                           const StrutVector& target,
                           StrutVector& residual);

}  // namespace pkm::kinematics::detail
