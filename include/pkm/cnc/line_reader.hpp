/// @file
/// @brief Reads the lines of a G-code text one block at a time (LinuxCNC 2.9 "Format of a line"):
/// line numbers, `%` program delimiters (a program that starts with `%` ends at the second `%`;
/// the rest of the file is ignored), empty lines and comment-only lines skipped. Program::parse
/// collects its blocks; Interpreter::runStream executes them as they are read.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "pkm/cnc/block.hpp"

namespace pkm::cnc {

/// A cursor over the lines of a G-code text (the text must outlive the reader).
class LineReader {
 public:
  /// `file` names the text in error messages.
  LineReader(std::string_view text, std::string file);

  /// Parses the next non-empty block into `block` (its `line` set). Returns false at the end of
  /// the text or after a `%` line that does not open the program (the rest is not read). Throws
  /// pkm::IoError "FILE:LINE: message" for a malformed line.
  bool next(Block& block);

  /// After the program's end: a malformed line becomes a block with Block::deferred_error
  /// instead of an error (LinuxCNC stops reading at M2/M30, so text after it is never read).
  void setLenient(bool lenient) { lenient_ = lenient; }

  /// Source lines read so far.
  [[nodiscard]] std::size_t lines() const { return line_; }
  /// The file name given to the constructor.
  [[nodiscard]] const std::string& file() const { return file_; }
  /// True once the closing `%` of a program that started with `%` was read.
  [[nodiscard]] bool closedByPercent() const { return done_ && percent_open_; }

  /// True when the text may contain an O-word statement: a letter `o` or `O` outside comments.
  /// Conservative (an `o` in an expression's function name counts too); false means none.
  [[nodiscard]] static bool mayHaveOWords(std::string_view text);

 private:
  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
  bool seen_content_ = false;
  bool percent_open_ = false;
  bool done_ = false;
  bool lenient_ = false;
};

}  // namespace pkm::cnc
