/// @file
/// @brief Internal: the pieces the hexapod and Exechon LinuxCNC configurations share
/// (io/linuxcnc_config.hpp): the INI from a list of joints and axes, the simulator HAL file, the
/// tool table, and the reach of a machine along one world coordinate.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "pkm/core/units.hpp"
#include "pkm/io/linuxcnc_config.hpp"

namespace pkm::io::detail {

/// Largest translation the axis-limit search of a configuration reaches, in the machine's
/// characteristic lengths.
inline constexpr double kTranslationCap = 2.0;

/// One [AXIS_L] section: world limits and rates (machine unit or degrees).
struct IniAxis {
  char letter = 'X';
  double min = 0.0, max = 0.0;
  double velocity = 0.0, acceleration = 0.0;
};

/// One [JOINT_n] section.
struct IniJoint {
  bool angular = false;
  double home = 0.0;  ///< HOME = HOME_OFFSET
  double min = 0.0, max = 0.0;
  double velocity = 0.0, acceleration = 0.0;
};

/// Everything the INI says.
struct IniSpec {
  std::string comment;  ///< leading "# " lines (with newlines)
  std::string machine;  ///< [EMC] MACHINE
  LengthUnit unit = LengthUnit::kMillimetre;
  std::string kinematics;            ///< [KINS] KINEMATICS
  std::array<double, 6> home{};      ///< [TRAJ] HOME, X Y Z A B C (degrees)
  std::vector<IniAxis> axes;         ///< in COORDINATES order
  std::vector<IniJoint> joints;      ///< joint 0, 1, ...
  double linear_velocity = 0.0;      ///< [TRAJ] MAX_LINEAR_VELOCITY, unit/s
  double linear_acceleration = 0.0;  ///< [TRAJ] MAX_LINEAR_ACCELERATION, unit/s²
  double angular_velocity = 0.0;     ///< [TRAJ] MAX_ANGULAR_VELOCITY, deg/s
};

/// The INI text of `spec` with the file names `names` and the options' display and COMP_FILEs.
[[nodiscard]] std::string linuxcncIni(const IniSpec& spec,
                                      const LinuxcncConfigNames& names,
                                      const LinuxcncConfigOptions& options);

/// The simulator HAL file: motion, the servo thread, each joint's command looped back as its
/// feedback, E-stop and tool changes answered, and motion.tooloffset.z netted to `tool_pin`.
[[nodiscard]] std::string simulatorHal(int joints, const std::string& tool_pin);

/// A tool table with tool 1 in pocket 1, length 0 (set it with G10 L1 P1 Z...).
[[nodiscard]] std::string toolTable(LengthUnit unit);

/// How far from home (0) along one coordinate `ok(t)` holds, t in [0, cap]: steps of cap/64 up to
/// the first t where it fails, then bisection between it and the last t that held; cap when it
/// never fails. `ok(0)` is assumed.
[[nodiscard]] double reach(const std::function<bool(double)>& ok, double cap);

/// [min, max] of an axis whose home is `home` and that reaches `below` / `above` from it, each end
/// rounded towards home to a multiple of `step` (home itself always inside).
[[nodiscard]] std::array<double, 2> axisLimits(double home,
                                               double below,
                                               double above,
                                               double step);

/// 10^(floor(log10(length)) − 3): the rounding step of linear axis limits for a machine of
/// characteristic length `length`.
[[nodiscard]] double limitStep(double length);

/// `pkm gcode run`'s default joint rates (workflow/gcode_run.hpp): unit/s, unit/s², deg/s, deg/s².
inline constexpr double kDefaultJointVelocity = 200.0;
inline constexpr double kDefaultJointAcceleration = 2000.0;
inline constexpr double kDefaultWristVelocityDeg = 180.0;
inline constexpr double kDefaultWristAccelerationDeg = 1800.0;

/// An open angle range's end in the INI (LinuxCNC needs a number).
inline constexpr double kOpenAngleLimit = 1e9;

}  // namespace pkm::io::detail
