/// @file
/// @brief Shared by the exechon_machine tests: a valid hybrid Exechon machine file, one entry per
/// line, edited line by line, and the "SOURCE:LINE: /pointer: " error of parsing it.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "support/edited_lines.hpp"

namespace pkm::test::exechon_json {

/// A valid hybrid Exechon machine file, one entry per line (line n is kLines[n - 1]).
// clang-format off
inline const std::vector<std::string> kLines = {
    "{",                                                                                  // 1
    "  \"schema\": \"pkm.machine/1\",",                                                   // 2
    "  \"type\": \"exechon\",",                                                           // 3
    "  \"name\": \"t\",",                                                                 // 4
    "  \"units\": \"mm\",",                                                               // 5
    "  \"tripod\": {\"dA\": -443.4, \"dB\": 345.5, \"dC\": 779.8, \"l12A\": 102.3,",      // 6
    "             \"l12C\": 152.3, \"pA\": -152.3, \"pB\": 132.4, \"pC\": 252.3,",        // 7
    "             \"hA\": 40, \"hC\": 23, \"hx\": 0, \"hz\": 250,",                       // 8
    "             \"branch\": {\"delta1B\": 1, \"delta2B\": 1, "
    "\"deltaA\": 1, \"deltaC\": 1}},",                                                    // 9
    "  \"legs\": [",                                                                      // 10
    "    {\"length_offset\": 631.8455, \"stroke\": [0, 700]},",                           // 11
    "    {\"length_offset\": 672.4537, \"stroke\": [0, 700]},",                           // 12
    "    {\"length_offset\": 668.0249, \"stroke\": [0, 700]}",                            // 13
    "  ],",                                                                               // 14
    "  \"limits\": {\"alpha_deg\": [50, 130], \"beta_deg\": [-45, 45],",                  // 15
    "             \"c_deg\": [-270, 270], \"a_deg\": [-100, 100]},",                      // 16
    "  \"wrist\": {\"c_axis\": [0, 0, 1], \"a_axis\": [1, 0, 0], \"tool_length\": 200},", // 17
    "  \"world_T_zoppi\": {\"position\": [0, -427.5251, 1374.6158], "
    "\"rpy_deg\": [200, 0, 0]},",                                                         // 18
    "  \"home\": {\"alpha_deg\": 90, \"beta_deg\": 0, \"h\": 1000, "
    "\"c_deg\": 0, \"a_deg\": 0},",                                                       // 19
    "  \"hybrid\": {\"x2_stroke\": [0, 4000], \"y2_stroke\": [0, 450],",                  // 20
    "             \"pkm_min\": [-300, -300, -350], \"pkm_max\": [300, 300, 350]}",        // 21
    "}",                                                                                  // 22
};
// clang-format on

inline constexpr const char* kSource = "exechon-under-test.json";

/// kLines with line n replaced by `edits[n]` (an empty replacement drops the line).
inline std::string text(const std::map<int, std::string>& edits = {}) {
  return editedLines(kLines, edits);
}

/// The message of the IoError that parsing `json_text` throws ("" when it does not throw).
inline std::string errorOf(const std::string& json_text) {
  return ioErrorOf([&] { return io::parseExechonJson(json_text, kSource); });
}

/// "SOURCE:LINE: POINTER: " as the reader starts its messages.
inline std::string at(int line, const std::string& pointer) {
  return std::string(kSource) + ":" + std::to_string(line) + ": " + pointer + ": ";
}

}  // namespace pkm::test::exechon_json
