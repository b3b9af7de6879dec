/// @file
/// @brief PoseRpy: a pose as LinuxCNC writes it (EmcPose X Y Z A B C), the boundary form for
/// hexapod commands, files and the command line, and its conversions to and from the library's one
/// rigid-transform type, geometry::RigidTransform (docs/conventions.md, "Pose").
#pragma once

#include <Eigen/Core>

#include "pkm/geometry/rigid_transform.hpp"

namespace pkm::kinematics {

/// A platform pose: position of the tool centre point (TCP) in world and roll-pitch-yaw angles
/// (a, b, c) in radians with world_R_platform = Rz(c)·Ry(b)·Rx(a) (LinuxCNC genhexkins convention).
struct PoseRpy {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< TCP in world, model length unit
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();       ///< (a, b, c), radians
};

/// The rigid transform world_T_tcp of a pose: [rotationFromRpy(pose.rpy), pose.position; 0, 1].
[[nodiscard]] geometry::RigidTransform toRigidTransform(const PoseRpy& pose);

/// The pose of a rigid transform world_T_tcp: position = T.translation(), angles
/// geometry::rpyFromRotation(T.linear()) (b in [−pi/2, pi/2], a and c in (−pi, pi]). Precondition
/// (asserted, not checked): T.linear() is a rotation matrix.
[[nodiscard]] PoseRpy poseRpyFromTransform(const geometry::RigidTransform& T);

/// As above, but of the equivalent angle triples returns the one closest to `near` (radians; see
/// geometry::rpyFromRotation), to keep angles continuous along a path.
[[nodiscard]] PoseRpy poseRpyFromTransform(const geometry::RigidTransform& T,
                                           const Eigen::Vector3d& near);

}  // namespace pkm::kinematics
