/// @file
/// @brief A whole G-code program held in memory: its parsed blocks and the resolved O-word
/// structure (sub/endsub, if/elseif/else/endif, while/endwhile, do/while, repeat/endrepeat,
/// break/continue), so that the interpreter jumps without searching.
#pragma once

#include <istream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "pkm/cnc/block.hpp"

namespace pkm::cnc {

/// A parsed program.
class Program {
 public:
  /// Parses `text` (the whole file); `file` names it in error messages. A program enclosed in
  /// `%` lines ends at the second `%`. Throws pkm::IoError "FILE:LINE: message" for a malformed
  /// line or O-word structure (unterminated or mismatched sub/if/while/do/repeat, nested sub,
  /// return outside a sub, break/continue outside its loop).
  static Program parse(std::string_view text, const std::string& file = "<gcode>");
  /// Reads and parses a file; throws pkm::IoError when it cannot be read.
  static Program load(const std::string& path);
  /// The whole text of a G-code file (also a pipe). Throws pkm::IoError "PATH: cannot open
  /// G-code file".
  static std::string readFile(const std::string& path);

  /// The non-empty blocks in source order.
  [[nodiscard]] const std::vector<Block>& blocks() const { return blocks_; }
  /// Index of the `sub` block of subroutine `name`, or kNoBlock.
  [[nodiscard]] std::size_t findSub(const std::string& name) const;
  /// Index of the first label block `O<name>` alone (OKind::kProgram) whose name is `name`, or
  /// kNoBlock: the target of `M98 P<name>`. Numbers compare as numbers ("0002" is 2).
  [[nodiscard]] std::size_t findProgram(const std::string& name) const;
  /// `name` as findProgram compares it: a number without its leading zeros, else as written.
  [[nodiscard]] static std::string programKey(const std::string& name);
  /// The file name given to parse/load.
  [[nodiscard]] const std::string& file() const { return file_; }
  /// Number of source lines read.
  [[nodiscard]] std::size_t lineCount() const { return lines_; }
  /// True when the program is enclosed in `%` lines (it may then end without M2/M30).
  [[nodiscard]] bool closedByPercent() const { return closed_by_percent_; }

 private:
  void resolve();
  std::vector<Block> blocks_;
  std::unordered_map<std::string, std::size_t> subs_;
  std::unordered_map<std::string, std::size_t> programs_;  // M98 targets, by programKey
  std::string file_;
  std::size_t lines_ = 0;
  bool closed_by_percent_ = false;
};

}  // namespace pkm::cnc
