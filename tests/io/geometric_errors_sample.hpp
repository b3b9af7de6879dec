/// @file
/// @brief Shared by the geometric_errors tests: a valid errors file, one entry per line, edited
/// line by line, and the "SOURCE:LINE: /pointer: " error of parsing it.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/geometric_errors.hpp"
#include "support/edited_lines.hpp"

namespace pkm::test::errors_json {

/// A valid errors file, one entry per line (line n is kLines[n - 1]). The PKM grid has 2 × 1 × 2
/// nodes, x fastest.
inline const std::vector<std::string> kLines = {
    "{",                                                          // 1
    "  \"schema\": \"pkm.errors/1\",",                            // 2
    "  \"type\": \"hybrid_geometric_errors\",",                   // 3
    "  \"units\": \"mm\",",                                       // 4
    "  \"squareness_urad\": {\"szX2\": -34, \"sxP\": 10},",       // 5
    "  \"x2\": {\"out_of_range\": \"clamp\",",                    // 6
    "         \"positions\": [0, 100, 200],",                     // 7
    "         \"dx\": [0, 0.01, 0.03],",                          // 8
    "         \"ey_urad\": [0, -5, -10]},",                       // 9
    "  \"y2\": {\"positions\": [0, 50],",                         // 10
    "         \"dy\": [0, 0.002]},",                              // 11
    "  \"pkm\": {\"out_of_range\": \"clamp\",",                   // 12
    "          \"x\": [-100, 100], \"y\": [0], \"z\": [0, 10],",  // 13
    "          \"dz\": [0, 0.1, 0.2, 0.4]}",                      // 14
    "}",                                                          // 15
};

inline constexpr const char* kSource = "errors-under-test.json";

/// kLines with line n replaced by `edits[n]` (an empty replacement drops the line).
inline std::string text(const std::map<int, std::string>& edits = {}) {
  return editedLines(kLines, edits);
}

/// The message of the IoError that parsing `json_text` throws ("" when it does not throw).
inline std::string errorOf(const std::string& json_text) {
  return ioErrorOf([&] { return io::parseGeometricErrorsJson(json_text, kSource); });
}

/// "SOURCE:LINE: POINTER: " as the reader starts its messages.
inline std::string at(int line, const std::string& pointer) {
  return std::string(kSource) + ":" + std::to_string(line) + ": " + pointer + ": ";
}

}  // namespace pkm::test::errors_json
