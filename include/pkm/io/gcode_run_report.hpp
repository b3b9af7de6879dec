/// @file
/// @brief The result of `pkm gcode run` (docs/gcode.md "gcode run"): a G-code program converted
/// to the joints of a hexapod or an Exechon, its cycle time and every path check, as one typed
/// report, as the text table the command prints and as the JSON document of `--report`.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace pkm::io {

/// One evaluation of a path check, in the units it is reported in (angles in degrees).
struct GcodeCheckEvent {
  std::size_t line = 0;              ///< 1-based program line
  std::array<double, 6> position{};  ///< machine position X Y Z A B C, mm and degrees
  std::string item;                  ///< e.g. "strut 3", "wrist C", "struts 1-4"
  double value = 0.0;                ///< the checked quantity, in `unit`
  double limit = 0.0;                ///< its limit, in `unit`
  /// Distance to the limit, in `unit`, < 0 when violated; +infinity when nothing was evaluated.
  double margin = std::numeric_limits<double>::infinity();
  std::string unit;  ///< e.g. "mm", "deg", "mm/s", "deg/s^2"; "" for a ratio
};

/// The summary of one path check over the whole program.
struct GcodeCheckSummary {
  std::string name;            ///< the check's word (docs/gcode.md), e.g. "stroke"
  bool enabled = false;        ///< false when the machine disables the limit
  std::size_t violations = 0;  ///< points (or sub-segments) where it is violated
  std::string unit;            ///< the unit of its values, for every joint
  GcodeCheckEvent worst;       ///< the smallest margin (margin +infinity when none)
  GcodeCheckEvent first;       ///< the first violation (valid when violations > 0)
  /// Why a disabled check is off and how to turn it on ("" when enabled or unknown).
  std::string off_reason = {};
};

/// What `pkm gcode run` found.
struct GcodeRunReport {
  std::string program;                  ///< the program's name (its path, or an upload's name)
  std::string machine;                  ///< the machine's name
  std::string machine_type;             ///< "hexapod" or "exechon"
  std::string units;                    ///< the machine's length unit, "mm" or "in"
  std::string orientation;              ///< Exechon: "vector" or "axes" (what A/C mean)
  std::size_t lines = 0;                ///< source lines of the program
  std::size_t motions = 0;              ///< interpreted motions
  std::size_t points = 0;               ///< interpolated points converted to joints
  double tolerance_mm = 0.0;            ///< chordal tolerance
  double max_step_mm = 0.0;             ///< longest interpolation step
  double max_angle_step_deg = 0.0;      ///< largest rotary interpolation step
  double max_joint_velocity = 0.0;      ///< leg or strut speed limit, machine unit/s
  double max_joint_acceleration = 0.0;  ///< leg or strut acceleration limit, machine unit/s²
  double max_wrist_velocity_deg_per_s = 0.0;          ///< Exechon wrist speed limit
  double max_wrist_acceleration_deg_per_s2 = 0.0;     ///< Exechon wrist acceleration limit
  double rapid_rate_mm_per_min = 0.0;                 ///< G0 path speed
  std::vector<std::string> limits_from_machine_file;  ///< limits the machine file set
  /// The limits that lower a rapid along each move (a LinuxCNC INI's axis maxima), in words;
  /// "" when none.
  std::string rapid_limits;
  double cycle_time_s = 0.0;              ///< estimated cycle time, dwells included
  double dwell_time_s = 0.0;              ///< of which dwells
  bool ok = true;                         ///< no check violated
  std::vector<GcodeCheckSummary> checks;  ///< every check, in the order of docs/gcode.md

  [[nodiscard]] bool exechon() const { return machine_type == "exechon"; }
};

/// The report as the JSON document of `pkm gcode run --report` (two-space indent, closing
/// newline; docs/gcode.md lists its members).
[[nodiscard]] std::string gcodeRunJson(const GcodeRunReport& report);

/// The report as the text `pkm gcode run` prints: the run's settings, the cycle time, one table
/// row per check, a `PROGRAM:LINE: ...` line per violated check and the result line.
[[nodiscard]] std::string gcodeRunText(const GcodeRunReport& report);

}  // namespace pkm::io
