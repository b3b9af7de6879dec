/// @file
/// @brief Measurement models of hexapod calibration (docs/calibration.md): the residual of one
/// observation and its Jacobian with respect to the 42 kinematic parameters
/// (hexapod_parameters.hpp).
#pragma once

#include <Eigen/Core>
#include <optional>

#include "pkm/calibration/hexapod_parameters.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::calibration {

/// A full-pose observation: the strut readings the controller reported and the TCP pose measured
/// in the machine's world (base) frame (a laser tracker with a 6-DOF probe, expressed in world).
struct PoseObservation {
  kinematics::StrutVector readings = kinematics::StrutVector::Zero();  ///< model length unit
  kinematics::PoseRpy pose;                                            ///< measured TCP pose
  /// Direction each strut last moved in before this reading (+1, −1; 0 unknown): the sign of the
  /// backlash term when backlash is estimated (HexapodCalibrationOptions::estimate_backlash).
  kinematics::StrutVector approach = kinematics::StrutVector::Zero();
};

/// A point observation: the strut readings and the measured TCP position in world.
struct PointObservation {
  kinematics::StrutVector readings = kinematics::StrutVector::Zero();  ///< model length unit
  Eigen::Vector3d point = Eigen::Vector3d::Zero();                     ///< measured TCP, world
  /// As PoseObservation::approach.
  kinematics::StrutVector approach = kinematics::StrutVector::Zero();
};

/// Jacobian of 6 residuals with respect to the 42 parameters.
using PoseParameterJacobian = Eigen::Matrix<double, 6, kHexapodParameters>;
/// Jacobian of 3 residuals with respect to the 42 parameters.
using PointParameterJacobian = Eigen::Matrix<double, 3, kHexapodParameters>;

/// Inverse-kinematic residuals of a full-pose observation (Zhuang, Yan, Masory, J. Robotic Systems
/// 15(7), 1998): r_i = |p + R·a_i − b_i| − offset_i − q_i, i = 0..5, in the model length unit, with
/// (p, R) the measured pose and a_i, b_i the effective joint points. When `J` is given it receives
/// dr/dθ: dr_i/db_i = −u_iᵀ, dr_i/da_i = u_iᵀR, dr_i/doffset_i = −1 (u_i the unit leg vector). Uses
/// `data` as workspace.
[[nodiscard]] kinematics::StrutVector poseResiduals(const kinematics::HexapodModel& model,
                                                    kinematics::HexapodData& data,
                                                    const PoseObservation& observation,
                                                    PoseParameterJacobian* J = nullptr);

/// dq/dθ at the pose of the last inverseKinematics call on `data`: the derivative of the six strut
/// readings with respect to the parameters at a fixed pose (the negative of poseResiduals' J).
[[nodiscard]] PoseParameterJacobian readingParameterJacobian(const kinematics::HexapodModel& model,
                                                             const kinematics::HexapodData& data);

/// The forward-kinematic error of an observation: the pose FK gives for the observed readings
/// minus the measured pose, as (δp, δθ) with δθ = so3Log(R_fk·R_measᵀ) (world frame, left
/// perturbation; docs/conventions.md). nullopt when FK does not converge from `seed`.
/// When `J` is given it receives d(δp, δθ)/dθ by the implicit-function theorem:
/// J = −J_q_x⁻¹·dq/dθ at the FK solution.
[[nodiscard]] std::optional<Eigen::Matrix<double, 6, 1>> forwardPoseError(
    const kinematics::HexapodModel& model,
    kinematics::HexapodData& data,
    const kinematics::StrutVector& readings,
    const kinematics::PoseRpy& measured,
    const kinematics::PoseRpy& seed,
    PoseParameterJacobian* J = nullptr,
    const kinematics::FkOptions& options = {});

/// Point residual e = p_FK(q; θ) − p_measured (model length unit) with J = de/dθ (the position rows
/// of forwardPoseError's Jacobian). nullopt when FK does not converge from `seed`.
[[nodiscard]] std::optional<Eigen::Vector3d> pointResiduals(const kinematics::HexapodModel& model,
                                                            kinematics::HexapodData& data,
                                                            const PointObservation& observation,
                                                            const kinematics::PoseRpy& seed,
                                                            PointParameterJacobian* J = nullptr);

}  // namespace pkm::calibration
