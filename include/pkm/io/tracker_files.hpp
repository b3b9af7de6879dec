/// @file
/// @brief Laser-tracker files (docs/formats.md, "Laser-tracker files"): the strut readings a
/// hexapod's controller commanded and the pose (6-DOF probe) or point (SMR) a laser tracker
/// measured there, one row per pose: the full-pose data of a hexapod calibration, header
/// `l0,l1,l2,l3,l4,l5,x,y,z,a,b,c` (mm and degrees, R = Rz(c)·Ry(b)·Rx(a)), or
/// `l0,l1,l2,l3,l4,l5,x,y,z` for points, after "# key: value" metadata lines.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pkm/io/measurement_files.hpp"
#include "pkm/simulation/laser_tracker.hpp"

namespace pkm::io {

/// The CSV text of a tracker measurement: `metadata` as "# key: value" lines, the header
/// (`l0..l5,x,y,z,a,b,c` for kPose, `l0..l5,x,y,z` for kPoint) and one row per reading: the
/// commanded strut readings (mm), the measured target position in the tracker frame (mm) and, for
/// kPose, its roll-pitch-yaw angles (degrees, geometry::rpyFromRotation: b in [−90°, 90°]).
/// Numbers in shortest round-trip form.
[[nodiscard]] std::string trackerCsv(const Metadata& metadata,
                                     simulation::TrackerMode mode,
                                     const std::vector<simulation::TrackerReading>& readings);

/// The metadata `pkm simulate` writes for a tracker measurement of scenario `scenario` with
/// `seed`: format, scenario, seed, measurement, instrument, mode, frame, target, smr offset mm,
/// noise, poses, columns. The frame is "tracker (...)" when the set-up places the tracker
/// (TrackerSetup::placed), else "world (...)": the readings are then in the machine's frame.
[[nodiscard]] Metadata trackerMetadata(const std::string& scenario,
                                       std::uint64_t seed,
                                       const simulation::TrackerSetup& setup,
                                       std::size_t poses);

/// A tracker file as read. Angles in radians (converted from the file's degrees).
struct TrackerFile {
  Metadata metadata;                                              ///< the "# key: value" lines
  simulation::TrackerMode mode = simulation::TrackerMode::kPose;  ///< kPose when a, b, c exist
  std::vector<kinematics::StrutVector> lengths;                   ///< l0..l5 per row, mm
  std::vector<Eigen::Vector3d> positions;                         ///< x, y, z per row, mm
  std::vector<Eigen::Vector3d> rpy;  ///< a, b, c per row, rad (kPose only)
  std::vector<std::size_t> lines;    ///< 1-based file line of each row
};

/// Parses a tracker CSV: '#' lines (metadata when of the form "key: value"), blank lines, a
/// header with l0..l5 and x, y, z, and for a pose file all of a, b, c (any order; the suffixes
/// `_mm` and `_deg` are accepted, other columns ignored), then rows of finite numbers. Throws
/// pkm::IoError "SOURCE:LINE: message" for a missing or repeated column, only some of a, b, c, a
/// field that is not a finite number, a wrong field count, or a file without rows.
[[nodiscard]] TrackerFile parseTrackerCsv(const std::string& text, const std::string& source);
/// Reads a tracker file (parseTrackerCsv). Throws pkm::IoError.
[[nodiscard]] TrackerFile readTrackerCsv(const std::string& path);

}  // namespace pkm::io
