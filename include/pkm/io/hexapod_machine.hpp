/// @file
/// @brief HexapodMachine: a hexapod model with its solver settings and provenance, as read from a
/// machine file (JSON, docs/machine-format.md) or a LinuxCNC configuration.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pkm/io/ini_velocity_limits.hpp"
#include "pkm/io/joint_rates.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::io {

/// Everything a machine file says about a hexapod.
struct HexapodMachine {
  kinematics::HexapodModel model;
  kinematics::FkOptions fk;  ///< forward-kinematics settings (convergence criterion, iteration cap)
  std::optional<JointRateSpec> joint_rates;  ///< strut rate limits, when the file gives them
  std::string description;                   ///< free text from the file
  std::string source;                        ///< file path, or "builtin:NAME"
  std::vector<std::string> notices;  ///< things the reader ignored or assumed, for the user to see
  /// G-code the controller runs before every program: a LinuxCNC INI's [RS274NGC]
  /// RS274NGC_STARTUP_CODE (e.g. "G20 G17 G40 G90"); "" when none. Not written to machine JSON.
  std::string startup_code;
  std::string startup_code_source;  ///< "INI:LINE" of the startup code, for messages
  /// True for a calibration from laser-tracker readings in the tracker's own frame without a
  /// registration (machine file `"world_frame": "unregistered"`): its geometry is right, but its
  /// world frame is where the fit put it, not the machine's table (docs/calibration.md,
  /// "Frames"). Nothing that goes into a controller is written from it (requireRegisteredFrame).
  bool world_frame_unregistered = false;
  /// A LinuxCNC INI's velocity limits ([TRAJ] and [AXIS_L] MAX_VELOCITY), which bound the rapid
  /// rate of `pkm gcode run`; unset without an INI. Not written to machine JSON.
  std::optional<IniVelocityLimits> ini_velocity;
};

/// Throws pkm::InvalidArgument, saying what to measure and pass, when `machine` is a calibration
/// whose world frame is not registered (HexapodMachine::world_frame_unregistered); `what` names
/// the refused action (e.g. "pkm linuxcnc install").
void requireRegisteredFrame(const HexapodMachine& machine, const std::string& what);

/// Parses a hexapod machine JSON text. `source` names it in messages. Cone axes left out of the
/// file default to the strut direction at the home pose. Throws pkm::IoError "SOURCE:LINE:
/// /json/pointer: message" for malformed JSON, unknown keys, wrong types, non-finite numbers and
/// unusable geometry.
[[nodiscard]] HexapodMachine parseHexapodJson(const std::string& text, const std::string& source);

/// Reads and parses a machine JSON file. Throws pkm::IoError.
[[nodiscard]] HexapodMachine readHexapodJson(const std::string& path);

/// Writes the machine as JSON in the format parseHexapodJson reads (lengths round-trip exactly;
/// angles, written in degrees, to within one unit in the last place).
[[nodiscard]] std::string writeHexapodJson(const HexapodMachine& machine);

/// Reads a whole text file (at most `max_bytes`). Throws pkm::IoError naming the file.
[[nodiscard]] std::string readTextFile(const std::string& path, std::size_t max_bytes = 64u << 20);

}  // namespace pkm::io
