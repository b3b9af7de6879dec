/// @file
/// @brief Exechon tracker files (docs/formats.md, "Exechon tracker files"): "# key: value"
/// metadata, the header `q1,q2,q3,c,a,x,y,z` (`q0,q1,q2` in older files; optionally `i,j,k`, a
/// measured unit tool direction), one row per measured pose: the leg readings A, B, C (mm) and
/// wrist readings C, A (degrees) the controller reported, the measured target (mm). Read into
/// calibration::ExechonCalibrationData.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/calibration/hybrid_calibration.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/simulation/exechon_tracker.hpp"
#include "pkm/simulation/hybrid_tracker.hpp"

namespace pkm::io {

/// The CSV text of a simulated Exechon tracker measurement (metadata lines, header, one row per
/// reading; lengths mm, wrist angles degrees; full precision).
[[nodiscard]] std::string exechonTrackerCsv(
    const Metadata& metadata, const std::vector<simulation::ExechonTrackerReading>& readings);

/// The metadata `pkm simulate` writes for an Exechon tracker measurement (format
/// pkm.exechon-tracker/1, frame "tracker ...", smr offset mm, noise, poses).
[[nodiscard]] Metadata exechonTrackerMetadata(const std::string& scenario,
                                              std::uint64_t seed,
                                              const simulation::ExechonTrackerSetup& setup,
                                              std::size_t poses);

/// The CSV text of a simulated hybrid tracker measurement: header `x2,y2,xp,yp,zp,x,y,z` (mm).
[[nodiscard]] std::string hybridTrackerCsv(
    const Metadata& metadata, const std::vector<simulation::HybridTrackerReading>& readings);

/// The metadata `pkm simulate` writes for a hybrid tracker measurement (format
/// pkm.hybrid-tracker/1, frame "tracker ...", smr offset mm, noise, poses).
[[nodiscard]] Metadata hybridTrackerMetadata(const std::string& scenario,
                                             std::uint64_t seed,
                                             const simulation::HybridTrackerSetup& setup,
                                             std::size_t poses);

/// What Exechon calibration files gave: PKM tracker files (q0..a columns) and hybrid tracker files
/// (x2, y2, xp, yp, zp columns, for the four squareness errors).
struct ExechonCalibrationInput {
  calibration::ExechonCalibrationData data;  ///< observations with source "FILE:LINE"
  /// Hybrid observations with source "FILE:LINE"; measurement_frame is set (to the identity, a
  /// placeholder for the caller's start) when the files' `frame` says tracker.
  calibration::HybridCalibrationData hybrid;
  /// The hybrid files' `smr offset mm` metadata, when one gave it (hybrid.target_offset holds it
  /// too, and zero otherwise).
  std::optional<Eigen::Vector3d> hybrid_target_offset;
  std::optional<Eigen::Vector3d> target_offset;  ///< `smr offset mm` metadata (first seen)
  bool tracker_frame = false;  ///< a file's `frame` metadata starts with "tracker"
  /// The files without `frame` metadata (their readings' frame is not stated).
  std::vector<std::string> frameless;
  std::vector<std::string> notes;
};

/// Adds the Exechon or hybrid tracker file `file` (read whole or an upload; messages and sources
/// use its name) to `input` (a header with x2 makes it a hybrid file). Throws pkm::IoError
/// "NAME:LINE: message" for a missing column, a bad number, a direction that is not a unit
/// vector, or two files whose `smr offset mm` or `frame` metadata disagree.
void addExechonCalibrationFile(const NamedText& file, ExechonCalibrationInput& input);
/// addExechonCalibrationFile of the file at `path` (io::readNamedText). Throws pkm::IoError.
void addExechonCalibrationFile(const std::string& path, ExechonCalibrationInput& input);

}  // namespace pkm::io
