// Shared by the `gcode run` workflow's sources (workflow/gcode_run.hpp): a program converted to
// joint space on one machine, whatever its type.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "gcode_progress.hpp"
#include "pkm/cnc/cycle_time.hpp"
#include "pkm/cnc/joint_checks.hpp"
#include "pkm/cnc/move.hpp"
#include "pkm/cnc/path_interpolation.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/workflow/gcode_run.hpp"

namespace pkm::workflow::detail {

/// Stages of a run, for the progress reports: interpreting, interpolating, converting.
inline constexpr std::size_t kRunStages = 3;

/// G0 path speed without --rapid-rate or an INI, mm/min.
inline constexpr double kDefaultRapidRate = 10000.0;

/// A program converted to joint space on one machine, timed and checked. Not copied or moved:
/// `csv_row` refers to it.
struct JointRun {
  std::string machine_name;
  std::string len;  ///< the machine's length unit
  bool exechon = false;
  cnc::InterpolationOptions interpolation;
  std::vector<cnc::PathPoint> points;
  cnc::CycleTime time;
  cnc::PathCheckReport report;
  std::string csv_header;
  std::function<void(std::string&, std::size_t)> csv_row;  ///< appends point i's row
  cnc::MotionLimits limits;  ///< in effect: request, else the machine file, else defaults
  double wrist_velocity = 0.0, wrist_acceleration = 0.0;  ///< deg/s, deg/s² (Exechon)
  std::vector<std::string> from_file;         ///< the limits taken from the machine file
  std::string rapid_limits;                   ///< io::GcodeRunReport::rapid_limits
  double tolerance_mm = kDefaultToleranceMm;  ///< the chordal tolerance in effect
  /// Why each disabled check is off, by check index ("" for the others).
  std::array<std::string, cnc::kPathChecks> off_reason;
  std::vector<std::string> joint_names;  ///< GcodeRunPath::joints
  std::vector<std::string> joint_units;  ///< GcodeRunPath::joint_units
  /// The joint values at point i (the first joint_names.size() entries are used).
  std::function<kinematics::StrutVector(std::size_t)> joints_at;
  /// The machine drawn at point i (workflow::PoseCheckRow).
  std::function<PoseCheckRow(std::size_t)> frame_at;
};

/// `count` frames of `run` evenly spaced in time into `result`.
void runFrames(const JointRun& run, std::size_t count, GcodeRunResult& result);

/// The path of `run` for a front end, at most `max_points` points (GcodeRunRequest::path_points).
[[nodiscard]] GcodeRunPath runPath(const JointRun& run, std::size_t max_points);

/// The request's tolerance in mm for a machine in `unit` (kDefaultToleranceMm without one).
[[nodiscard]] double toleranceMm(const GcodeRunRequest& request, LengthUnit unit);

/// Converts, times and checks `program` on the request's hexapod.
void runHexapod(const GcodeRunRequest& request,
                const io::HexapodMachine& machine,
                const cnc::MoveCollector& program,
                const GcodeProgress& progress,
                JointRun& run);

/// Converts, times and checks `program` on the request's Exechon. Throws pkm::InvalidArgument
/// "NAME:LINE: B... programmed" for a B word.
void runExechon(const GcodeRunRequest& request,
                const cnc::MoveCollector& program,
                const RunControl& control,
                const GcodeProgress& progress,
                JointRun& run);

/// The machining preview of `run` (workflow/gcode_machining.hpp): `moves` gives the tool
/// changes, `tools` the tool table, `path_index` the points of GcodeRunResult::path (the
/// report's path_tools). Cancellation is checked between path points. Throws
/// pkm::InvalidArgument "machining: ..." for a tool the table lacks or gives no diameter or
/// length, an auto stock without a feed move, and as HeightField.
[[nodiscard]] MachiningReport runMachining(const MachiningRequest& request,
                                           const JointRun& run,
                                           const cnc::MoveCollector& moves,
                                           const cnc::ToolTable& tools,
                                           const std::vector<std::size_t>& path_index,
                                           const RunControl& control);

/// Writes the joint CSV through io::AtomicFile, in blocks of about 1 MiB.
void writeJointCsv(const std::string& path, const JointRun& run);

/// The report of a run (angles in degrees, every value with its unit).
[[nodiscard]] io::GcodeRunReport runReport(const GcodeRunRequest& request,
                                           std::size_t lines,
                                           std::size_t motions,
                                           const JointRun& run);

}  // namespace pkm::workflow::detail
