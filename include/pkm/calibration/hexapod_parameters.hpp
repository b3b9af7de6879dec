/// @file
/// @brief The 42 kinematic parameters of a 6-UPS hexapod as a vector (per strut: base joint centre,
/// platform joint centre, length offset: the standard 7-per-leg model, e.g. Zhuang, Yan & Masory
/// 1998), with names, flags and scales for identification (docs/calibration.md).
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>

#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::calibration {

/// Parameters per strut: base joint centre (x, y, z, world frame), platform joint centre (x, y, z,
/// platform frame), length offset.
inline constexpr int kParametersPerStrut = 7;
/// Number of hexapod kinematic parameters.
inline constexpr int kHexapodParameters = kParametersPerStrut * kinematics::kStruts;

/// The parameter vector, model length unit. Layout: index 7·i + k for strut i with k = 0..2 the
/// base joint x, y, z; k = 3..5 the platform joint x, y, z; k = 6 the length offset.
using HexapodParameterVector = Eigen::Matrix<double, kHexapodParameters, 1>;

/// Index of base joint coordinate `axis` (0..2) of strut `strut` (0..5).
[[nodiscard]] constexpr int baseParameter(int strut, int axis) {
  return kParametersPerStrut * strut + axis;
}
/// Index of platform joint coordinate `axis` (0..2) of strut `strut`.
[[nodiscard]] constexpr int platformParameter(int strut, int axis) {
  return kParametersPerStrut * strut + 3 + axis;
}
/// Index of the length offset of strut `strut`.
[[nodiscard]] constexpr int offsetParameter(int strut) { return kParametersPerStrut * strut + 6; }

/// The name of parameter `index` as used in files and reports: "base0.x", "platform3.z",
/// "offset5". Throws pkm::InvalidArgument for an index outside [0, 42).
[[nodiscard]] std::string hexapodParameterName(int index);
/// The index of a parameter name (hexapodParameterName's inverse); throws pkm::InvalidArgument
/// "unknown hexapod parameter 'name'".
[[nodiscard]] int hexapodParameterIndex(const std::string& name);

/// The parameters of `model` (Strut::world_p_base, Strut::platform_p_joint, Strut::length_offset
/// as stored; the spindle and tool offsets stay part of the model and are not parameters).
[[nodiscard]] HexapodParameterVector hexapodParameters(const kinematics::HexapodModel& model);

/// `model` with its 42 parameters replaced by `parameters` (everything else kept). Throws
/// pkm::InvalidArgument when a parameter is not finite.
[[nodiscard]] kinematics::HexapodModel withHexapodParameters(
    kinematics::HexapodModel model, const HexapodParameterVector& parameters);

/// Which parameters an identification may change: true = free (estimated), false = fixed at the
/// initial value.
using HexapodParameterMask = std::array<bool, kHexapodParameters>;

/// All 42 free.
[[nodiscard]] HexapodParameterMask allHexapodParametersFree();

}  // namespace pkm::calibration
