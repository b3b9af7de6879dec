/// @file
/// @brief The joint rate limits a machine file may carry (`"joint_rates"`, docs/machine-format.md):
/// the largest speed and acceleration of the struts or legs and, for an Exechon, of the wrist
/// axes. `pkm gcode run` times programs and checks rates with them.
#pragma once

#include <limits>
#include <string>

namespace pkm::io {

/// Joint rate limits of a machine. NaN means "not given" (the command's default applies).
struct JointRateSpec {
  double velocity = std::numeric_limits<double>::quiet_NaN();      ///< length unit per s, > 0
  double acceleration = std::numeric_limits<double>::quiet_NaN();  ///< length unit per s², > 0
  double wrist_velocity_deg = std::numeric_limits<double>::quiet_NaN();      ///< deg/s, > 0
  double wrist_acceleration_deg = std::numeric_limits<double>::quiet_NaN();  ///< deg/s², > 0
};

/// The `"joint_rates"` member as the writers emit it (no leading separator, no newline); the
/// wrist keys only when `wrist` is true, NaN fields left out.
[[nodiscard]] std::string jointRatesJson(const JointRateSpec& rates, bool wrist);

}  // namespace pkm::io
