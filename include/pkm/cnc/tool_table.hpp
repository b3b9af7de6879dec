/// @file
/// @brief LinuxCNC tool table (`.tbl`) reader: lines such as `T1 P1 Z0.511 D0.125 ;comment`
/// (LinuxCNC 2.9 "Tool Table Format"). Offsets are kept in mm; the table's own length unit is
/// the machine's (INI LINEAR_UNITS), which the caller states.
#pragma once

#include <array>
#include <map>
#include <string>
#include <string_view>

namespace pkm::cnc {

/// One tool: its length offsets X Y Z (mm) and A B C (deg), and diameter (mm).
struct ToolEntry {
  int number = 0;
  int pocket = 0;
  std::array<double, 6> offset{};
  double diameter = 0.0;
  /// The text after ';' on its line, trimmed ("" without one): LinuxCNC keeps it as the tool's
  /// description; the machining preview reads the tool's end shape from it (cnc::toolEndOf).
  std::string comment{};
};

/// A tool table keyed by tool number.
struct ToolTable {
  std::map<int, ToolEntry> tools;
  /// The tool with number `t`, or nullptr.
  [[nodiscard]] const ToolEntry* find(int t) const;
  /// Parses table text whose lengths are in mm (`mm_per_unit` 1) or inch (25.4). `file` names it
  /// in errors. Throws pkm::IoError "FILE:LINE: message" for a malformed line or a repeated tool.
  static ToolTable parse(std::string_view text, double mm_per_unit, const std::string& file);
  /// Reads a file; throws pkm::IoError when it cannot be read.
  static ToolTable load(const std::string& path, double mm_per_unit);
};

}  // namespace pkm::cnc
