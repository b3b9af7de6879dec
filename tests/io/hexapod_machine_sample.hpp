/// @file
/// @brief Shared by the hexapod_machine tests: a valid machine file (the LinuxCNC hexapod-sim), one
/// entry per line, edited line by line, and the "SOURCE:LINE: /pointer: " error of parsing it.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "support/edited_lines.hpp"

namespace pkm::test::hexapod_json {

/// A valid machine file, one entry per line (line n of the text is kLines[n - 1]).
inline const std::vector<std::string> kLines = {
    "{",                                                                           // 1
    "  \"name\": \"t\",",                                                          // 2
    "  \"units\": \"inch\",",                                                      // 3
    "  \"home\": {\"x\": 0, \"y\": 0, \"z\": 20, \"a\": 0, \"b\": 0, \"c\": 0},",  // 4
    "  \"struts\": [",                                                             // 5
    "    {\"base\": [-22.95, 13.25, 0], \"platform\": [-1, 11.5, 0]},",            // 6
    "    {\"base\": [22.95, 13.25, 0], \"platform\": [1, 11.5, 0]},",              // 7
    "    {\"base\": [22.95, 13.25, 0], \"platform\": [10.459, -4.884, 0]},",       // 8
    "    {\"base\": [0, -26.5, 0], \"platform\": [9.459, -6.616, 0]},",            // 9
    "    {\"base\": [0, -26.5, 0], \"platform\": [-9.459, -6.616, 0]},",           // 10
    "    {\"base\": [-22.95, 13.25, 0], \"platform\": [-10.459, -4.884, 0]}",      // 11
    "  ]",                                                                         // 12
    "}",                                                                           // 13
};

inline constexpr const char* kSource = "machine-under-test.json";

/// kLines with line n replaced by `edits[n]` (an empty replacement drops the line).
inline std::string text(const std::map<int, std::string>& edits = {}) {
  return editedLines(kLines, edits);
}

/// The message of the IoError that parsing `json_text` throws ("" when it does not throw).
inline std::string errorOf(const std::string& json_text) {
  return ioErrorOf([&] { return io::parseHexapodJson(json_text, kSource); });
}

/// "SOURCE:LINE: " as the reader starts its messages.
inline std::string at(int line) { return std::string(kSource) + ":" + std::to_string(line) + ": "; }

}  // namespace pkm::test::hexapod_json
