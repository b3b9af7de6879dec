/// @file
/// @brief `pkm tracker join` as a workflow (docs/linuxcnc.md step 3, docs/formats.md
/// "Laser-tracker files"): a measurement plan of `pkm plan-poses` and the laser tracker's point
/// export (SpatialAnalyzer ASCII) joined into a tracker point file that `pkm calibrate hexapod`
/// reads: per pose, the strut readings the controller commands there (the nominal inverse
/// kinematics of the planned pose) and the point the tracker measured.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "pkm/io/named_text.hpp"

namespace pkm::workflow {

/// A join request.
struct TrackerJoinRequest {
  std::string machine = "default";  ///< hexapod: machine file, LinuxCNC .hal or built-in name
  std::string ini;                  ///< the LinuxCNC INI of a .hal machine ("": found from it)
  /// The plan: `pkm plan-poses` CSV, `pose,x,y,z,a,b,c` (machine unit, degrees).
  io::NamedText plan;
  /// The tracker's points: a SpatialAnalyzer ASCII point export (io::parseSpatialAnalyzerPoints).
  /// A point belongs to the pose its target name ends with (P7, pose_007, 7); an export without
  /// names gives one point per pose, in plan order.
  io::NamedText points;
  /// The export's length unit: mm, um, m or in ("" : the machine's unit).
  std::string unit;
  /// The target's place on the tool (tool frame, machine unit), written as `smr offset mm`
  /// metadata ("": left to `pkm calibrate --target-offset` or fitted).
  std::optional<Eigen::Vector3d> smr_offset;
  /// The frame the points are in: "tracker" (the default: its placement is fitted) or "world"
  /// (the export's working frame was aligned to the machine).
  std::string frame = "tracker";
  std::string out;     ///< the tracker file to write ("" : none, the caller shows the text)
  bool force = false;  ///< replace an existing `out`
  /// Throws pkm::InvalidArgument for a frame other than tracker or world, a unit that is not a
  /// length unit, an Exechon machine; pkm::IoError when `out` exists and `force` is not set.
  void validate() const;
};

/// The joined tracker file.
struct TrackerJoinResult {
  std::string text;                ///< the tracker point file (pkm.tracker-point/1)
  std::size_t rows = 0;            ///< poses with a point
  std::vector<std::string> notes;  ///< the unit used, poses left out for want of a point
};

/// Validates, reads the machine, the plan and the export, joins them and writes `out` (atomic).
/// Throws as validate(), pkm::IoError "NAME:LINE: message" for a plan without the pose columns,
/// a point whose name has no pose number, a pose number that is not in the plan or appears
/// twice, an unnamed export whose point count differs from the plan's, or no pose with a point.
[[nodiscard]] TrackerJoinResult joinTrackerPoints(const TrackerJoinRequest& request);

}  // namespace pkm::workflow
