/// @file
/// @brief The 26 kinematic parameters of an Exechon machine as a vector for identification: 14
/// tripod dimensions (Zoppi DETC2010-28668 Table 1: dA, dB, dC, the base U-joint axis offsets l12A,
/// l12C, pA, pB, pC, hA, hC, hx, hz; and leg B's base-joint axis offsets l12B, l23B after
/// Lopez-Custodio et al. 2020), the three leg length offsets, the wrist zeros c0, a0 and the tool
/// length, and the placement of the tripod's base frame (docs/calibration.md, "Exechon").
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/exechon_model.hpp"

namespace pkm::calibration {

/// Number of Exechon kinematic parameters.
inline constexpr int kExechonParameters = 26;

/// The parameter vector. Layout (index: name, unit):
///  0–13: tripod.dA, tripod.dB, tripod.dC, tripod.l12A, tripod.l12C, tripod.l12B, tripod.l23B,
///        tripod.pA, tripod.pB, tripod.pC, tripod.hA, tripod.hC, tripod.hx, tripod.hz (model
///        length unit);
/// 14–16: offsetA, offsetB, offsetC (leg length offsets, model length unit);
/// 17–19: wrist.c0, wrist.a0 (rad), wrist.tool_length (model length unit);
/// 20–25: base.x, base.y, base.z (model length unit), base.rx, base.ry, base.rz (rad): the
///        correction δ = (δt, δω) of world_T_zoppi relative to a reference placement (R₀, t₀),
///        world_T_zoppi = (exp([δω]×)·R₀, t₀ + δt) — the left perturbation of docs/conventions.md.
using ExechonParameterVector = Eigen::Matrix<double, kExechonParameters, 1>;

/// Index of the first leg length offset (offsetA).
inline constexpr int kExechonOffsetParameter = 14;

/// Index of the first wrist parameter (wrist.c0).
inline constexpr int kExechonWristParameter = 17;

/// Index of the first base-placement parameter (base.x).
inline constexpr int kExechonBaseParameter = 20;

/// The name of parameter `index` (layout above). Throws pkm::InvalidArgument outside [0, 26).
[[nodiscard]] std::string exechonParameterName(int index);

/// The index of a parameter name; throws pkm::InvalidArgument "unknown Exechon parameter 'name'".
[[nodiscard]] int exechonParameterIndex(const std::string& name);

/// True for the parameters measured in the model length unit (false: radians).
[[nodiscard]] bool exechonParameterIsLength(int index);

/// The parameters of `model`, the base placement relative to `reference_world_T_zoppi` (a rigid
/// transform; usually the initial model's world_T_zoppi, giving zeros).
[[nodiscard]] ExechonParameterVector exechonParameters(
    const kinematics::ExechonModel& model, const geometry::RigidTransform& reference_world_T_zoppi);

/// `model` with its 26 parameters replaced (base placement relative to the reference; branch
/// signs, limits, wrist axes and signs, home kept). Throws pkm::InvalidArgument when a parameter is
/// not finite. The result is not validated (a calibration may pass through odd geometry).
[[nodiscard]] kinematics::ExechonModel withExechonParameters(
    kinematics::ExechonModel model,
    const ExechonParameterVector& parameters,
    const geometry::RigidTransform& reference_world_T_zoppi);

/// Which parameters an identification may change (true = free).
using ExechonParameterMask = std::array<bool, kExechonParameters>;

/// All 26 free.
[[nodiscard]] ExechonParameterMask allExechonParametersFree();

}  // namespace pkm::calibration
