/// @file
/// @brief Reading and writing the geometric errors of a hybrid machine (PDGE tables of X2 and Y2,
/// the PKM's error grid, the four squareness errors) as JSON (docs/formats.md, "Geometric errors").
#pragma once

#include <string>

#include "pkm/kinematics/hybrid_errors.hpp"

namespace pkm::io {

/// Parses a geometric-errors JSON text ("type": "hybrid_geometric_errors"). Translations are in the
/// machine's length unit, rotations and squareness in microradians (keys end in _urad). Throws
/// pkm::IoError "SOURCE:LINE: /json/pointer: message" for malformed JSON, unknown keys, columns of
/// the wrong length, non-increasing positions and non-finite values.
[[nodiscard]] kinematics::GeometricErrors parseGeometricErrorsJson(const std::string& text,
                                                                   const std::string& source);

/// Reads a geometric-errors file. Throws pkm::IoError.
[[nodiscard]] kinematics::GeometricErrors readGeometricErrorsJson(const std::string& path);

/// Writes the errors in the format parseGeometricErrorsJson reads.
[[nodiscard]] std::string writeGeometricErrorsJson(const kinematics::GeometricErrors& errors);

}  // namespace pkm::io
