/// @file
/// @brief SpatialAnalyzer (New River Kinematics) ASCII point exports (docs/formats.md, "Instrument
/// exports"): one point per line, its name fields (as chosen at export: `Collection Group
/// Target`, `Group Target`, `Target` or none) then X Y Z in the working frame, separated by
/// spaces or commas; `//` comment lines (SA version, frame and axis comments) at the top. The
/// layout is the one SA's user manual documents ("Exporting ASCII Formatted Points").
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "pkm/io/named_text.hpp"

namespace pkm::io {

/// One exported point.
struct SpatialAnalyzerPoint {
  std::string collection;    ///< "" when the export leaves it out
  std::string group;         ///< "" when the export leaves it out
  std::string target;        ///< the point's name; "" when the export has no names
  Eigen::Vector3d position;  ///< X, Y, Z in the export's unit and working frame
  std::size_t line = 0;      ///< 1-based line in the export
};

/// The points of a Cartesian SA ASCII export. Blank lines and lines starting with `//` are
/// skipped, as is a first line whose last three fields are X, Y, Z (a header some users add).
/// Every line has the same number of fields, 3 to 6: the names (0 to 3: target; group, target;
/// collection, group, target), then three finite numbers. Throws pkm::IoError "NAME:LINE:
/// message" for a line with another field count than the first (more than 6: the export's
/// tolerance, uncertainty, time-stamp or comment options, which pkm does not read), a coordinate
/// that is not a finite number, or no points at all.
[[nodiscard]] std::vector<SpatialAnalyzerPoint> parseSpatialAnalyzerPoints(const NamedText& input);

}  // namespace pkm::io
