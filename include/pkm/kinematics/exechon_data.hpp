/// @file
/// @brief ExechonBranch (the 16 tripod solution branches) and ExechonData, the workspace and
/// results of the Exechon algorithms. Frames and symbols: exechon_model.hpp.
#pragma once

#include <Eigen/Core>
#include <array>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/exechon_model.hpp"

namespace pkm::kinematics {

/// One of Zoppi's 16 joint solutions for a wrist point S: δ1B, δ2B select one of the four platform
/// poses (DETC2010-28668 sec. 4.1), δA, δC the working modes of legs A and C. Each is +1 or -1.
struct ExechonBranch {
  int delta1B = 1;  ///< Zoppi's δ1B (as ExechonTripodGeometry::delta1B)
  int delta2B = 1;  ///< Zoppi's δ2B
  int deltaA = 1;   ///< working mode of leg A
  int deltaC = 1;   ///< working mode of leg C

  /// True when every sign is +1 or -1.
  [[nodiscard]] bool isValid() const;
  /// 0..15: bit 0 set for δ1B = -1, bit 1 for δ2B = -1, bit 2 for δA = -1, bit 3 for δC = -1.
  [[nodiscard]] int index() const;
  /// The inverse of index(). Throws pkm::InvalidArgument unless 0 <= index < 16.
  [[nodiscard]] static ExechonBranch fromIndex(int index);
  /// Equal when all four signs are.
  friend bool operator==(const ExechonBranch&, const ExechonBranch&) = default;
};

/// The branch a machine is built and assembled in (the signs of ExechonTripodGeometry).
[[nodiscard]] ExechonBranch branchOf(const ExechonTripodGeometry& tripod);

/// Workspace for one ExechonModel. Algorithms write their results here. Fixed size, no heap
/// allocation. Not thread-safe: use one ExechonData per thread.
struct ExechonData {
  /// Sets the constant base joint centres of `model` (zoppi_p_base).
  explicit ExechonData(const ExechonModel& model);

  // ---- tripod (filled by tripod IK/FK and by evaluateTripod) ----
  ExechonBranch branch;                         ///< branch of the last tripod solution
  Eigen::Vector3d e = Eigen::Vector3d::Zero();  ///< (alpha, beta in (-pi, pi], h), rad/rad/length
  Eigen::Vector3d zoppi_p_S = Eigen::Vector3d::Zero();  ///< wrist point, Zoppi frame
  Eigen::Vector3d world_p_S = Eigen::Vector3d::Zero();  ///< wrist point, world frame
  /// Platform frame (P, kA2, kB5, eh) in the Zoppi frame: the inverse of Zoppi's eq. (6) He.
  geometry::RigidTransform zoppi_T_platform = geometry::RigidTransform::Identity();
  geometry::RigidTransform world_T_platform =
      geometry::RigidTransform::Identity();  ///< world_T_zoppi · zoppi_T_platform
  /// Base joint centres P1A, P1B, P1C, Zoppi frame (constant).
  std::array<Eigen::Vector3d, kExechonLegs> zoppi_p_base{};
  /// Where each strut length is measured from: P2A, P1B, P2C (P2L = P1L shifted by δL·l12L), Zoppi
  /// frame.
  std::array<Eigen::Vector3d, kExechonLegs> zoppi_p_leg_start{};
  /// Platform joint centres P4A, P5B, P4C, Zoppi frame.
  std::array<Eigen::Vector3d, kExechonLegs> zoppi_p_platform_joint{};
  ExechonLegVector lengths = ExechonLegVector::Zero();  ///< Zoppi's q: |platform joint − leg start|
  ExechonLegVector readings = ExechonLegVector::Zero();  ///< lengths − length_offset
  /// sin α, cos α, sin β, cos β of `e_of_sin_cos`: set with e by the tripod algorithms, so that a
  /// solve near the previous solution need not recompute them (a cache; not part of the result).
  std::array<double, 4> e_sin_cos{0.0, 1.0, 0.0, 1.0};
  Eigen::Vector3d e_of_sin_cos = Eigen::Vector3d::Zero();  ///< the e that e_sin_cos belong to
  /// wristFrame(wrist) of the wrist axes `wrist_axes_of_frame` (c_axis, a_axis): a cache of the
  /// tool IK and setWristReadings, recomputed when the model's axes differ.
  Eigen::Matrix3d wrist_frame = Eigen::Matrix3d::Zero();
  std::array<Eigen::Vector3d, 2> wrist_axes_of_frame{Eigen::Vector3d::Zero(),
                                                     Eigen::Vector3d::Zero()};

  // ---- Jacobians (filled by computeTripodJacobian) ----
  Eigen::Matrix3d J_q_e = Eigen::Matrix3d::Zero();  ///< d(lengths)/d(alpha, beta, h)
  Eigen::Matrix3d J_S_e = Eigen::Matrix3d::Zero();  ///< d(zoppi_p_S)/d(alpha, beta, h)
  Eigen::Matrix3d J_q_S =
      Eigen::Matrix3d::Zero();  ///< d(lengths)/d(zoppi_p_S) = J_q_e·J_S_e⁻¹ (unit-free)

  // ---- wrist and tool (filled by the tool IK/FK of exechon_wrist.hpp) ----
  double c = 0.0;              ///< wrist C reading, rad
  double a = 0.0;              ///< wrist A reading, rad
  bool wrist_at_pole = false;  ///< |sin θA| at or below the pole tolerance (θA = 0 or ±180°): C is
                               ///< undefined and was kept
  Eigen::Matrix3d world_R_tool =
      Eigen::Matrix3d::Identity();  ///< tool frame; its z is the tool direction
  Eigen::Vector3d world_p_tool = Eigen::Vector3d::Zero();   ///< tool point, world frame
  Eigen::Vector3d world_u_tool = Eigen::Vector3d::UnitZ();  ///< unit tool direction, world frame
};

/// The configuration (e, C, A) held in `data` (e.g. the previous solution for continuity).
[[nodiscard]] ExechonConfiguration configurationOf(const ExechonData& data);

}  // namespace pkm::kinematics
