/// @file
/// @brief `pkm plan-poses` as a workflow (docs/calibration.md, "Pose planning"): calibration poses
/// chosen among random workspace candidates by an observability index (Sun & Hollerbach's O1..O5,
/// calibration/identifiability.hpp), for a hexapod (6-DOF poses or tracker points) or an Exechon
/// (tracker points), with the CSV of the chosen poses and optionally a G-code program that drives
/// the machine through them.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/pose_plan_report.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// A pose-planning request.
struct PlanPosesRequest {
  std::string machine = "default";  ///< machine file, LinuxCNC .hal, or built-in name (any type)
  std::string ini;                  ///< the LinuxCNC INI of a .hal machine ("": found from it)
  /// A machine the front end has already loaded (e.g. a Python pkm.Hexapod or pkm.Exechon,
  /// possibly with a changed geometry), used instead of `machine` and `ini` (its reader's notices
  /// are not repeated); at most one of the two is set.
  std::shared_ptr<const io::HexapodMachine> hexapod;
  std::shared_ptr<const io::ExechonMachine> exechon;
  int count = 30;            ///< poses to choose, ≥ 1
  std::string index = "O1";  ///< observability index "O1".."O5" (any case)
  std::string measurement;   ///< "pose" (6-DOF), "point" (tracker SMR) or "" (the machine's own)
  int candidates = 1000;     ///< random workspace candidates, ≥ count
  std::uint64_t seed = 1;    ///< random seed of the candidates
  /// Half-range of x, y, z about home, machine unit (0: 0.4 × the hexapod's platform radius,
  /// 0.3 × the Exechon's largest base dimension).
  double reach = 0.0;
  /// Degrees: hexapod, the half-range of a, b, c about home; Exechon, the largest tilt of the tool
  /// from its home direction (≤ 90).
  double tilt_deg = 10.0;
  /// G-code feed rate, machine unit per minute. Default: 1000, lowered (to two significant
  /// digits) until no joint of the program exceeds its velocity limit (checked as `gcode run`
  /// checks it). A feed given here is kept, with a notice when a joint would exceed its limit.
  std::optional<double> feed;
  /// Exechon only: the tracker target in the tool frame, x, y, z (empty: 0, 0, 0).
  std::vector<double> target_offset;
  std::string gcode;   ///< the G-code program to write ("": none)
  bool force = false;  ///< replace an existing G-code file
  /// Throws pkm::InvalidArgument naming the option for count < 1, candidates < count, an unknown
  /// index or measurement, a negative reach or tilt, a target offset that is not 3 numbers, or both
  /// loaded machines set.
  void validate() const;
  /// "hexapod" or "exechon": the loaded machine's type, else io::machineTypeOf(machine).
  [[nodiscard]] std::string machineType() const;
};

/// What a pose plan produced.
struct PlanPosesResult {
  io::PosePlanReport report;  ///< the plan and the chosen poses (io::posePlanJson)
  std::string csv;            ///< io::posePlanCsv of the report
  std::string summary;        ///< io::posePlanSummary of the report (also sent as a notice)
  std::string gcode;          ///< the program, as written ("" without request.gcode)
};

/// Plans the poses and writes the G-code program (atomically; refused when it exists unless
/// `force`, checked before planning). The machine's type chooses the planner (io::machineTypeOf).
/// Notices: the machine reader's notes (hexapod), then the summary line. Progress: the stages
/// "candidates", "plan" and "program", with cancellation checked between them (workflow::Cancelled;
/// nothing is written). Throws pkm::InvalidArgument for a bad request (also an Exechon asked for
/// 6-DOF poses, a target offset for a hexapod, a tilt over 90° for an Exechon), pkm::IoError for an
/// unreadable machine or an existing program.
[[nodiscard]] PlanPosesResult planPoses(const PlanPosesRequest& request,
                                        const RunControl& control = {});

}  // namespace pkm::workflow
