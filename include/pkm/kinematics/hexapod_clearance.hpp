/// @file
/// @brief The height of a hexapod's platform joints above its base plane: the distance to the
/// mirror configuration. With the platform joints in the base joints' plane the struts' z
/// components vanish and the pose is singular; beyond it lies the mirror assembly, which has the
/// same strut lengths (Merlet, "Parallel Robots", 2nd ed., 2006, §4.2, the reflection of a
/// Gough-Stewart platform's assembly about its base plane). Joint limits cannot tell the two
/// apart: only the world workspace can keep a controller away from that plane.
#pragma once

#include <Eigen/Core>

#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_model.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::kinematics {

/// The base plane: the least-squares plane of the six base joint centres (with the spindle
/// offset), world frame, its unit normal pointing to the side of the platform at the home pose.
struct BasePlane {
  Eigen::Vector3d world_p_centre = Eigen::Vector3d::Zero();  ///< centroid of the base joints
  Eigen::Vector3d world_n = Eigen::Vector3d::UnitZ();        ///< unit normal, towards the platform
};

/// The smallest clearance above the base plane a controller's workspace keeps, in characteristic
/// lengths (HexapodModel::characteristicLength): far enough from the singular plane for the
/// conditioning to stay usable, small against any practical platform height.
inline constexpr double kMirrorClearanceFraction = 0.1;

/// The base plane of `model` (see BasePlane).
[[nodiscard]] BasePlane basePlane(const HexapodModel& model);

/// The smallest signed distance (model length unit) of a platform joint centre from `plane` at
/// `pose`, positive on the home side: ≤ 0 when a platform joint has reached or crossed the base
/// plane (singular, then mirror configurations).
[[nodiscard]] double platformClearance(const HexapodModel& model,
                                       const BasePlane& plane,
                                       const PoseRpy& pose);

/// The assembly branch at `pose`: the sign of the determinant of the strut Jacobian J_q_x (+1 or
/// −1), 0 when it is singular (smallest to largest pivot of its LU factorisation, angular columns
/// divided by the characteristic length, at most 1e-12). Two poses of one branch can be joined
/// without crossing a singular configuration only if their signs agree (Gosselin and Angeles,
/// "Singularity analysis of closed-loop kinematic chains", IEEE TRA 6(3), 1990: the type II
/// singularities are det J = 0); pkmhexkins refuses a pose whose sign is not home's. Computes the
/// inverse kinematics and Jacobian into `data`.
[[nodiscard]] int assemblyBranch(const HexapodModel& model, HexapodData& data, const PoseRpy& pose);

}  // namespace pkm::kinematics
