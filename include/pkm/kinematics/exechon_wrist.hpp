/// @file
/// @brief Exechon tool kinematics: the spherical C/A wrist at the wrist point S (ExechonWrist) on
/// the tripod. Tool IK: tool point and direction -> S -> tripod IK -> platform rotation -> C, A
/// (Zoppi et al. 2010 for the tripod; a serial C/A head on the platform); tool FK: leg readings, C,
/// A -> tool point and direction.
#pragma once

#include <Eigen/Core>

#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_fk.hpp"
#include "pkm/kinematics/exechon_ik.hpp"
#include "pkm/kinematics/exechon_model.hpp"

namespace pkm::kinematics {

/// A 5-axis tool pose: the tool point and the tool direction, world frame. The rotation about the
/// tool direction is not controlled (it follows from the mechanism: see exechon_drm.hpp).
struct ExechonToolPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();    ///< tool point, model length unit
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< tool direction (normalised by pkm)
};

/// The five machine axes: leg readings A, B, C (model length unit) and wrist readings C, A (rad).
struct ExechonJoints {
  ExechonLegVector readings = ExechonLegVector::Zero();  ///< legs A, B, C, model length unit
  double c = 0.0;                                        ///< wrist C reading, rad
  double a = 0.0;                                        ///< wrist A reading, rad
};

/// |sin θA| at or below this counts as the wrist pole (tool along ±c_axis), where C is undefined.
inline constexpr double kExechonWristPoleTolerance = 1e-9;

/// W = [x̂, ĉ × x̂, ĉ] with ĉ = c_axis and x̂ = a_axis, normalised: the wrist frame in the platform
/// frame.
[[nodiscard]] Eigen::Matrix3d wristFrame(const ExechonWrist& wrist);

/// platform_R_tool = W·Rz(θC)·Rx(θA) with θC = c_sign·c + c0, θA = a_sign·a + a0 (readings c, a in
/// rad).
[[nodiscard]] Eigen::Matrix3d toolRotationInPlatform(const ExechonWrist& wrist, double c, double a);

/// Wrist readings that point the tool along `platform_u_tool` (platform frame, non-zero).
struct ExechonWristAngles {
  double c = 0.0;        ///< rad
  double a = 0.0;        ///< rad
  bool at_pole = false;  ///< |sin θA| <= kExechonWristPoleTolerance: c was set to c_near
};

/// Solves W⁻¹·u = (sin θC·sin θA, −cos θC·sin θA, cos θA) for the readings. Of the two solutions
/// (θC, θA) and (θC + pi, −θA), each shifted by multiples of 2·pi, returns the one nearest (c_near,
/// a_near) (|Δc| + |Δa|), which keeps a path continuous. At the pole C is undefined and c = c_near.
[[nodiscard]] ExechonWristAngles wristAnglesFromDirection(const ExechonWrist& wrist,
                                                          const Eigen::Vector3d& platform_u_tool,
                                                          double c_near,
                                                          double a_near);

/// Tool IK in the model's tripod branch, wrist readings nearest model.home (c, a):
/// world_p_S = position − tool_length·û, tripod IK from S (Zoppi frame), û in the platform frame,
/// then wristAnglesFromDirection. Fills data's tripod and tool fields (data.world_R_tool has z =
/// û). kInvalidInput for a non-finite pose or a zero direction; otherwise the tripod IK's status.
/// On failure data is not modified. Limits are not applied (exechon_checks.hpp).
ExechonIkStatus toolInverseKinematics(const ExechonModel& model,
                                      ExechonData& data,
                                      const ExechonToolPose& target);

/// As above by continuity: the pose branch (δ1B, δ2B) whose e is nearest previous.e
/// (tripodInverseKinematicsNearest) and the wrist readings nearest (previous.c, previous.a).
/// kInvalidInput also for a non-finite `previous`.
ExechonIkStatus toolInverseKinematics(const ExechonModel& model,
                                      ExechonData& data,
                                      const ExechonToolPose& target,
                                      const ExechonConfiguration& previous);

/// Tool IK with the wrist readings given (c, a, rad), as a LinuxCNC TCP kinematics reads rotary
/// words: the tripod parameters e that put the tool point at `world_p_tool` (world frame, model
/// length unit), the tool's direction then following the platform. Newton's method on
/// F(e) = S(e) + R(e)·v − p (Zoppi frame; v the tool offset the readings give in the platform
/// frame), with the analytic dF/de, from e_start (along a path, the previous solution or an
/// extrapolation of the last ones), halving a step that increases |F|; converged when
/// |F| <= 1e-14 × characteristicLength(), or <= 1e-12 × and no longer falling (rounding). The
/// tripod stays on e_start's pose branch, in the model's leg working modes. Fills data as
/// evaluateConfiguration(e, c, a); alpha and beta are wrapped into [−pi, pi]. kInvalidInput for a
/// non-finite argument; kSingular when dF/de is singular or Newton's method does not converge in
/// 50 iterations (e.g. a point out of reach). On failure data's results are not modified (its
/// wrist-frame cache may be).
ExechonIkStatus toolPointInverseKinematics(const ExechonModel& model,
                                           ExechonData& data,
                                           const Eigen::Vector3d& world_p_tool,
                                           double c,
                                           double a,
                                           const Eigen::Vector3d& e_start);

/// Direct evaluation of a configuration (e, C, A) in the model's leg working modes: evaluateTripod,
/// then the wrist: world_R_tool = world_R_platform·toolRotationInPlatform(c, a), world_u_tool its
/// z, world_p_tool = world_p_S + tool_length·world_u_tool. Never fails.
void evaluateConfiguration(const ExechonModel& model,
                           ExechonData& data,
                           const ExechonConfiguration& config);

/// Sets the wrist readings (c, a, rad) on the tripod pose held in data and fills data's wrist and
/// tool fields as evaluateConfiguration does (the tripod fields are left as they are). Never fails.
void setWristReadings(const ExechonModel& model, ExechonData& data, double c, double a);

/// Tool FK: tripodForwardKinematics(joints.readings, seed.e, options), then the wrist at (joints.c,
/// joints.a) as in evaluateConfiguration. Returns the tripod FK summary; on failure data must not
/// be used. Throws pkm::InvalidArgument if `options` is invalid.
FkSummary toolForwardKinematics(const ExechonModel& model,
                                ExechonData& data,
                                const ExechonJoints& joints,
                                const ExechonConfiguration& seed,
                                const FkOptions& options = {});

/// The machine axes held in data (readings, c, a).
[[nodiscard]] ExechonJoints jointsOf(const ExechonData& data);

}  // namespace pkm::kinematics
