/// @file
/// @brief `pkm gcode run` as a workflow (docs/gcode.md "gcode run"): a G-code program
/// interpolated within a chordal tolerance, converted to the joints of a hexapod or an Exechon,
/// timed under joint velocity and acceleration limits and checked against every limit of the
/// machine (strokes, joint angles, interference, conditioning, joint rates).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "pkm/cnc/path_interpolation.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/gcode_run_report.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/workflow/gcode_interpreter.hpp"
#include "pkm/workflow/gcode_machining.hpp"
#include "pkm/workflow/pose_checks.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// A `gcode run` request. A rate limit left unset is the machine file's `joint_rates` value
/// when it has one, else the default named.
struct GcodeRunRequest {
  io::NamedText program;  ///< the program; its name prefixes every message (NAME:LINE:)
  /// Hexapod or Exechon: machine file, LinuxCNC `.hal` (hexapod) or built-in name.
  std::string machine = "default";
  std::string ini;  ///< the LinuxCNC INI of a .hal machine ("" : found from it)
  /// A machine the front end has already loaded (e.g. a Python pkm.Hexapod, possibly with a
  /// changed geometry), used instead of `machine` and `ini`; at most one of the two is set.
  std::shared_ptr<const io::HexapodMachine> hexapod;
  std::shared_ptr<const io::ExechonMachine> exechon;
  /// Hexapod: the strut diameter for the interference check, machine unit (default: the machine
  /// file's; a LinuxCNC configuration has none, so the check is off without it). > 0.
  std::optional<double> strut_diameter;
  /// Chordal tolerance in the machine's length unit (> 0); default kDefaultTolerance mm.
  std::optional<double> tolerance;
  std::string out;     ///< joint CSV file ("" : none; docs/gcode.md)
  std::string report;  ///< the report's JSON file ("" : none; io::gcodeRunJson)
  bool force = false;  ///< replace existing `out` and `report` files
  std::optional<double> max_joint_velocity;      ///< strut/leg speed, machine unit/s (200)
  std::optional<double> max_joint_acceleration;  ///< machine unit/s² (2000)
  std::optional<double> max_wrist_velocity;      ///< Exechon wrist C/A speed, deg/s (180)
  std::optional<double> max_wrist_acceleration;  ///< Exechon wrist, deg/s² (1800)
  /// G0 path speed, mm/min. Unset: a LinuxCNC INI's [TRAJ] MAX_LINEAR_VELOCITY (hexapod read
  /// from a .hal with its INI), else 10000. An INI's [AXIS_L] MAX_VELOCITY and [TRAJ]
  /// MAX_ANGULAR_VELOCITY lower rapids along each move either way.
  std::optional<double> rapid_rate;
  /// Exechon: A/C words are the tool vector's angles in the world frame ("vector") or the wrist
  /// axes' readings ("axes").
  std::string orientation = "vector";
  GcodeInterpreterSettings interpreter;  ///< tool table, block delete, loop guard
  /// The most interpolated points the program may need (cnc::InterpolationOptions::max_points):
  /// more is refused at the motion that crosses it, before the points are made. > 0.
  std::size_t max_points = cnc::kDefaultMaxPathPoints;
  /// Most points of the returned path (GcodeRunResult::path; 0: no path). A longer path is
  /// decimated evenly, keeping the first and last points and every point where a check's worst
  /// value occurs; the checks themselves always see every point.
  std::size_t path_points = 0;
  /// Most violations returned per check (GcodeRunResult::violations; 0: none).
  std::size_t max_violations = 0;
  /// Drawings of the machine along the path for an animation (GcodeRunResult::frames), evenly
  /// spaced in time (0: none).
  std::size_t frames = 0;
  /// The machining preview (docs/machining.md): material removed along the whole path, with
  /// its collisions (unset: none).
  std::optional<MachiningRequest> machining;
  /// Whether the run is on an Exechon: `exechon` is set, or (without a loaded machine) `machine`
  /// names one (io::machineTypeOf).
  [[nodiscard]] bool onExechon() const;
  /// Throws pkm::InvalidArgument for a limit or tolerance that is not > 0 or an orientation for a
  /// hexapod, for both loaded machines set, pkm::IoError "PATH exists; pass --force to overwrite
  /// it" for an existing `out` or `report` without `force`, and as
  /// GcodeInterpreterSettings::validate.
  void validate() const;
};

/// The interpolated path of a run, for drawing and animating it (possibly decimated).
struct GcodeRunPath {
  std::vector<std::string> joints;          ///< joint names: "strut 0".. or "leg A".., "wrist C"..
  std::vector<std::string> joint_units;     ///< each joint's unit: the machine's length unit, "deg"
  std::size_t total_points = 0;             ///< points of the full path
  std::vector<std::size_t> index;           ///< each kept point's index in the full path
  std::vector<double> t;                    ///< arrival time at each kept point, s
  std::vector<std::size_t> line;            ///< its program line
  std::vector<std::array<double, 6>> pose;  ///< X Y Z A B C, mm and degrees (as the report)
  std::vector<std::vector<double>> q;       ///< its joint values, in joint_units
};

/// One violated point of one check.
struct GcodeRunViolation {
  std::string check;          ///< the check's word (docs/gcode.md), e.g. "stroke"
  io::GcodeCheckEvent event;  ///< line, position, item, value, limit, margin (< 0), unit
};

/// What a `gcode run` found.
struct GcodeRunResult {
  io::GcodeRunReport report;  ///< every figure (io::gcodeRunText, io::gcodeRunJson)
  GcodeRunPath path;          ///< request.path_points > 0: the path
  /// request.max_violations > 0: the first max_violations violations of each check, by check
  /// then path order (report.checks[k].violations counts them all).
  std::vector<GcodeRunViolation> violations;
  /// request.frames > 0: the machine drawn (joint centres, tool, margins) at evenly spaced times
  /// of the path: frame k at time frame_t[k], path point frame_index[k].
  std::vector<double> frame_t;
  std::vector<std::size_t> frame_index;
  std::vector<PoseCheckRow> frames;
  /// request.machining set: what the preview found (its collisions do not change ok()).
  std::optional<MachiningReport> machining;
  /// False when a check is violated (the CLI then exits with code 1).
  [[nodiscard]] bool ok() const { return report.ok; }
};

/// Interprets, interpolates, converts, times and checks the program, then writes `out` and
/// `report` (io::AtomicFile). Notices: the machine reader's notes. Progress: every
/// kGcodeProgressInterval motions or points of each stage (interpreting, interpolating,
/// converting), with cancellation checked (workflow::Cancelled; nothing is written). Throws
/// pkm::IoError "NAME:LINE: message" for a program the interpreter rejects or unreadable files,
/// pkm::InvalidArgument for a program without motion, a B word on an Exechon, and as validate().
[[nodiscard]] GcodeRunResult runGcode(const GcodeRunRequest& request,
                                      const RunControl& control = {});

}  // namespace pkm::workflow
