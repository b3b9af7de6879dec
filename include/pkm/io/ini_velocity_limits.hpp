/// @file
/// @brief The Cartesian velocity limits of a LinuxCNC INI (LinuxCNC 2.9 "INI Configuration":
/// [TRAJ] MAX_LINEAR_VELOCITY, formerly MAX_VELOCITY, and MAX_ANGULAR_VELOCITY; [AXIS_<letter>]
/// MAX_VELOCITY), which bound a G0: LinuxCNC runs a rapid at the trajectory's maximum, lowered so
/// that no axis exceeds its own maximum along the move.
#pragma once

#include <array>
#include <limits>
#include <string>

#include "pkm/io/named_text.hpp"

namespace pkm::io {

/// An INI's velocity limits, in the INI's units a second ([TRAJ] LINEAR_UNITS for lengths,
/// degrees for angles). NaN: not given.
struct IniVelocityLimits {
  static constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();
  double linear = kUnset;   ///< [TRAJ] MAX_LINEAR_VELOCITY (or MAX_VELOCITY), length unit/s
  double angular = kUnset;  ///< [TRAJ] MAX_ANGULAR_VELOCITY, deg/s
  /// [AXIS_X] .. [AXIS_C] MAX_VELOCITY: X, Y, Z in length unit/s, A, B, C in deg/s.
  std::array<double, 6> axis{kUnset, kUnset, kUnset, kUnset, kUnset, kUnset};
  std::string source;  ///< the INI's name
  /// Whether the INI gives any of them.
  [[nodiscard]] bool any() const;
};

/// Reads the velocity limits of an INI held in memory. [TRAJ] MAX_LINEAR_VELOCITY wins over the
/// older MAX_VELOCITY wherever they stand. Throws pkm::IoError "NAME:LINE: [SECTION] KEY: expected
/// one number > 0" for a value that is not one finite number > 0.
[[nodiscard]] IniVelocityLimits readIniVelocityLimits(const NamedText& ini);

}  // namespace pkm::io
