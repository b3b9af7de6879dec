/// @file
/// @brief HexapodModel: the constant geometry of a 6-UPS Stewart platform (Model/Data split; the
/// workspace is HexapodData). Conventions: docs/conventions.md.
#pragma once

#include <Eigen/Core>
#include <array>
#include <limits>
#include <string>

#include "pkm/core/units.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::kinematics {

/// Number of struts (legs) of a hexapod.
inline constexpr int kStruts = 6;

/// Strut readings (joint positions) of the six struts, model length unit.
using StrutVector = Eigen::Matrix<double, kStruts, 1>;

/// A spherical/universal joint's allowed motion: a cone of half-angle `max_angle` about `axis`.
/// The axis points along the strut, from base towards platform. max_angle <= 0 disables the check.
struct JointCone {
  Eigen::Vector3d axis =
      Eigen::Vector3d::UnitZ();  ///< unit vector (base: world; platform: platform frame)
  double max_angle = 0.0;        ///< radians; <= 0 means unlimited
};

/// Geometry and limits of one strut (leg i joins base joint i to platform joint i).
struct Strut {
  Eigen::Vector3d world_p_base = Eigen::Vector3d::Zero();  ///< base joint centre, world frame
  Eigen::Vector3d platform_p_joint =
      Eigen::Vector3d::Zero();  ///< platform joint centre, platform frame
  /// Length offset: reading + offset = distance between the two joint centres (0 in LinuxCNC).
  double length_offset = 0.0;
  double min_reading = -std::numeric_limits<double>::infinity();  ///< lowest reading (stroke)
  double max_reading = std::numeric_limits<double>::infinity();   ///< highest reading (stroke)
  JointCone base_cone;      ///< base joint limit, axis in world
  JointCone platform_cone;  ///< platform joint limit, axis in platform frame
};

/// The constant description of a hexapod. All lengths are in `unit`; angles in radians.
struct HexapodModel {
  std::string name = "hexapod";
  LengthUnit unit = LengthUnit::kMillimetre;
  std::array<Strut, kStruts> struts{};
  /// TCP in the platform frame: poses given to IK/FK are the pose of a frame at this point with the
  /// platform's orientation.
  Eigen::Vector3d tool_offset = Eigen::Vector3d::Zero();
  /// genhexkins' `spindle-offset` + `tool-offset`: added to the z of every base and platform joint
  /// (moves the controlled point and the world origin together; 0 unless imported from LinuxCNC).
  double spindle_offset = 0.0;
  /// Of spindle_offset, the part that came from genhexkins' `tool-offset` (kept for HAL
  /// write-back).
  double linuxcnc_tool_offset = 0.0;
  double strut_diameter = 0.0;  ///< for leg-to-leg interference; 0 disables the check
  /// Largest allowed condition number of the scaled strut Jacobian (singularity proximity).
  double max_condition = 1e3;
  PoseRpy home;  ///< home pose (FK seed; LinuxCNC [TRAJ] HOME)

  /// Base joint centre i as used by the kinematics (includes spindle_offset), world frame.
  [[nodiscard]] Eigen::Vector3d effectiveBase(int i) const {
    Eigen::Vector3d b = struts[static_cast<std::size_t>(i)].world_p_base;
    b.z() += spindle_offset;
    return b;
  }
  /// Platform joint centre i relative to the TCP, in the platform frame (includes spindle_offset
  /// and tool_offset).
  [[nodiscard]] Eigen::Vector3d effectivePlatform(int i) const {
    Eigen::Vector3d a = struts[static_cast<std::size_t>(i)].platform_p_joint - tool_offset;
    a.z() += spindle_offset;
    return a;
  }
  /// Characteristic length used to make the Jacobian's angular columns commensurate with its
  /// linear ones: the mean distance of the platform joints from the platform origin.
  [[nodiscard]] double characteristicLength() const;

  /// Throws pkm::InvalidArgument naming the field when the geometry is unusable: non-finite values,
  /// coincident joints, min_reading > max_reading, zero-length cone axes, a singular home pose, or
  /// a home pose with a zero-length strut.
  void validate() const;
};

}  // namespace pkm::kinematics
