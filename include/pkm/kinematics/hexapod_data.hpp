/// @file
/// @brief HexapodData: the preallocated workspace and results of the hexapod algorithms.
#pragma once

#include <Eigen/Core>
#include <array>

#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::kinematics {

/// 6×6 matrix type used for the strut Jacobian.
using Matrix6d = Eigen::Matrix<double, kStruts, kStruts>;

/// Workspace for one HexapodModel. Algorithms write their results here and return a reference to
/// the main one. Not thread-safe: use one HexapodData per thread.
struct HexapodData {
  /// Sizes the workspace for `model` (all hexapods have the same sizes; kept for the Model/Data
  /// API).
  explicit HexapodData(const HexapodModel& model);

  Eigen::Matrix3d world_R_platform = Eigen::Matrix3d::Identity();  ///< last pose's orientation
  Eigen::Vector3d world_p_tcp = Eigen::Vector3d::Zero();           ///< last pose's TCP position
  /// Platform joint centres in world (kinematic points, spindle offset included).
  std::array<Eigen::Vector3d, kStruts> world_p_platform_joint{};
  /// world_R_platform · effectivePlatform(i): platform joint relative to the TCP, world axes.
  std::array<Eigen::Vector3d, kStruts> world_r_joint{};
  std::array<Eigen::Vector3d, kStruts> leg{};        ///< platform joint − base joint, world
  std::array<Eigen::Vector3d, kStruts> unit_leg{};   ///< leg / |leg|
  StrutVector joint_distance = StrutVector::Zero();  ///< |leg|: distance between joint centres
  /// 1 / joint_distance (0 for coincident joints).
  StrutVector inverse_joint_distance = StrutVector::Zero();
  StrutVector readings = StrutVector::Zero();  ///< joint_distance − length_offset
  /// J_q_x: d(readings)/d(δp, δθ) with δp the TCP displacement and δθ the rotation vector of the
  /// left (world-frame) perturbation world_R_platform ← exp([δθ]×)·world_R_platform
  /// (docs/conventions.md).
  Matrix6d J_q_x = Matrix6d::Zero();
  PoseRpy pose;  ///< last pose (the input of IK, the result of FK)
};

}  // namespace pkm::kinematics
