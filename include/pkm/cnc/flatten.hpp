/// @file
/// @brief Flattening of a G-code program: the blocks an interpreter run executes, in execution
/// order, with every expression replaced by its value (docs/gcode.md "gcode flatten"). The
/// result has no O-word statements, parameters or expressions, so line-by-line tools (gcode
/// compensate, controllers without O-words) can take programs written with subroutines and loops.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/cnc/interpreter.hpp"

namespace pkm::cnc {

/// A flattened program.
struct FlatProgram {
  std::string text;  ///< the program, '\n' line ends
  /// For each line of `text` (0-based), the 1-based source line it comes from.
  std::vector<std::size_t> source_line;
  std::size_t blocks = 0;    ///< executed blocks written (an ordinary block may appear many times)
  bool had_o_words = false;  ///< the source held O-word statements
};

/// Runs `text` (`file` names it in messages) through a fresh Interpreter with `options` and
/// writes each ordinary block it executes as one line: the block-delete slash if the source had
/// one, then its words in source order (letters upper case, values as evaluated, in the shortest
/// decimal form that reads back to the same double, never an exponent), then the comments of the
/// source line. The N number, parameter settings and O-word statements are left out; comment
/// and blank lines are copied where the run passes straight through them (between two blocks
/// executed one after the other, at the start of a sub body, a branch or a loop pass, before the
/// first block and after the last). A program enclosed
/// in `%` lines stays enclosed. A line is at most 256 characters (LinuxCNC's limit): when the
/// comments would make it longer they go on a line of their own before the block, and when the
/// words alone would, their values are rounded to 9 decimals. Throws pkm::IoError
/// "FILE:LINE: message" as Interpreter::run does, and when a block is still too long.
[[nodiscard]] FlatProgram flattenProgram(std::string_view text,
                                         const std::string& file,
                                         const InterpreterOptions& options = {});

/// `value` as a G-code number: the shortest decimal that reads back to the same double, without
/// an exponent ("0.00001", not "1e-05"), "-" for negatives, no "-0". Precondition: finite.
[[nodiscard]] std::string formatGcodeNumber(double value);

}  // namespace pkm::cnc
