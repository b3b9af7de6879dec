/// @file
/// @brief Compensation of the four squareness errors of a hybrid machine (MXT700S parallelism
/// paper, §3.3): the PKM's three by rotating its basic coordinate system against the kinematic
/// reference frame in the PKM controller, and the X2–Y2 squareness by a correction of the PKM
/// command proportional to the X2 travel (a G-code / post-processor correction, or a cross-axis
/// table of the PKM axes over X2) (docs/compensation.md, "Hybrid machine: squareness").
///
/// Derivation (frames and signs of pkm/kinematics/hybrid_chain.hpp; PDGE left out): with
/// R_X2 = exp([ω_X2]×), R_P = exp([ω_P]×), the actual tool position for the command (x2, y2, p) is
///   R_X2·(x2·x̂ + X2_p_P + R_P·(P_p_tcp0 + p)) − y2·ŷ − Y2_p_work
/// and the nominal one the same with R_X2 = R_P = I. The PKM command p_c that makes the actual
/// position equal the nominal position of p is exactly
///   p_c = A·p + b₀ + x2·b₁,   A = R_Pᵀ·R_X2ᵀ,
///   b₀ = A·P_p_tcp0 − P_p_tcp0 + R_Pᵀ·(R_X2ᵀ − I)·X2_p_P,   b₁ = R_Pᵀ·(R_X2ᵀ − I)·x̂.
/// A is the base-frame rotation (controller parameter), b₀ a base-frame offset (zero in the MXT700S
/// parallelism paper, whose offsets are zero), b₁ ≈ (0, szX2, 0) the X2–Y2 squareness correction
/// per mm of X2.
#pragma once

#include <Eigen/Core>

#include "pkm/kinematics/hybrid_errors.hpp"
#include "pkm/kinematics/hybrid_model.hpp"

namespace pkm::compensation {

/// What goes into the controller to compensate the squareness errors.
struct HybridSquarenessCompensation {
  /// A: the rotation applied to PKM commands (p_kinematic = A·p + …), i.e. the orientation of the
  /// PKM's basic coordinate system in its kinematic reference frame.
  Eigen::Matrix3d base_rotation = Eigen::Matrix3d::Identity();
  /// A as LinuxCNC roll-pitch-yaw (a, b, c) = (rx, ry, rz), rad, R = Rz(c)·Ry(b)·Rx(a).
  Eigen::Vector3d base_rpy = Eigen::Vector3d::Zero();
  /// b₀: base-frame offset added to PKM commands, P frame, model length unit.
  Eigen::Vector3d base_offset = Eigen::Vector3d::Zero();
  /// b₁: PKM command correction per unit of X2 travel, P frame (unit-free).
  Eigen::Vector3d per_x2 = Eigen::Vector3d::Zero();
};

/// The compensation of `squareness` on `model` (file comment). Throws pkm::InvalidArgument when a
/// squareness is not finite or the model does not validate.
[[nodiscard]] HybridSquarenessCompensation hybridSquarenessCompensation(
    const kinematics::HybridMachineModel& model, const kinematics::HybridSquareness& squareness);

/// The command a controller with the compensation sends for the nominal `command`: x2, y2 kept,
/// PKM command p_c = A·p + b₀ + x2·b₁.
[[nodiscard]] kinematics::HybridCommand compensatedCommand(
    const HybridSquarenessCompensation& compensation, const kinematics::HybridCommand& command);

}  // namespace pkm::compensation
