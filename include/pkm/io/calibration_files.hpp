/// @file
/// @brief Calibration input files (docs/calibration.md, "pkm calibrate hexapod"): laser-tracker
/// pose and point files (io/tracker_files.hpp) and constrained-motion (dial gauge) files
/// (docs/formats.md, "Constrained-motion files"), gathered into
/// calibration::HexapodCalibrationData.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/text_table.hpp"

namespace pkm::io {

/// Parses metadata text such as "(150, 0, 0), (-75, 129.9, 0)" into vectors. Throws pkm::IoError
/// "SOURCE: metadata 'key': ..." when a group is not three finite numbers in parentheses.
[[nodiscard]] std::vector<Eigen::Vector3d> parseVectorList(const std::string& text,
                                                           const std::string& source,
                                                           const std::string& key);

/// Reads a constrained-motion file: the gauge tips from metadata `gauge points mm` (three
/// vectors, tool frame) and the normal from `table normal` (default (0, 0, 1)), the station-0 row
/// as the reference and the rows with converged = 1 as stations (rows that did not converge are
/// left out and counted in *skipped). Angles in the file are degrees. Throws pkm::IoError
/// "FILE:LINE: message" for a missing column or metadata key, a bad number, no station 0 or a
/// second one (NAME is the input's name).
[[nodiscard]] calibration::ConstrainedMotionData readConstrainedMotionCsv(const NamedText& input,
                                                                          int* skipped = nullptr);
/// readConstrainedMotionCsv of the file at `path` (io::readNamedText). Throws as it.
[[nodiscard]] calibration::ConstrainedMotionData readConstrainedMotionCsv(const std::string& path,
                                                                          int* skipped = nullptr);

/// What the calibration input files gave.
struct CalibrationInput {
  calibration::HexapodCalibrationData data;
  /// From a tracker file's `smr offset mm` metadata (the first one seen), tool frame.
  std::optional<Eigen::Vector3d> target_offset;
  /// True when a tracker file's `frame` metadata says the readings are in the tracker's frame.
  bool tracker_frame = false;
  /// The tracker files without `frame` metadata (their readings' frame is not stated).
  std::vector<std::string> frameless;
  std::vector<std::string> notes;            ///< what was read, for the user
  std::vector<std::string> pose_origin;      ///< "FILE:LINE" of each pose observation
  std::vector<std::string> point_origin;     ///< "FILE:LINE" of each point observation
  std::vector<std::string> distance_origin;  ///< "FILE:LINE" of each distance observation
};

/// Adds `file` (a file read whole or an upload; messages and origins use its name) to `input`:
/// a distance file (header l0..l5, distance: with metadata
/// `# pivot mm: (x, y, z)` ball-bar lengths to that pivot, else distances from the first row's TCP,
/// whose distance must be 0), a constrained-motion file (header with g0_mm) or a tracker pose or
/// point file (header with l0..l5, x, y, z and optionally a, b, c). Throws pkm::IoError
/// "NAME:LINE: message".
void addCalibrationFile(const NamedText& file, CalibrationInput& input);
/// addCalibrationFile of the file at `path` (io::readNamedText). Throws pkm::IoError.
void addCalibrationFile(const std::string& path, CalibrationInput& input);

}  // namespace pkm::io
