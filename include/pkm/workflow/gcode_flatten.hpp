/// @file
/// @brief `pkm gcode flatten` as a workflow (docs/gcode.md "gcode flatten"): the blocks a program
/// executes, in execution order, with every expression evaluated and no O-word statements
/// (cnc::flattenProgram).
#pragma once

#include <string>

#include "pkm/cnc/flatten.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/workflow/gcode_interpreter.hpp"

namespace pkm::workflow {

/// A `gcode flatten` request.
struct GcodeFlattenRequest {
  io::NamedText program;  ///< the program; its name prefixes every message (NAME:LINE: ...)
  std::string out;        ///< the file to write ("" : none, the caller shows the text)
  bool force = false;     ///< replace an existing `out`
  GcodeInterpreterSettings interpreter;
  /// Throws as GcodeInterpreterSettings::validate, and pkm::IoError "OUT exists; pass --force to
  /// overwrite it" when `out` exists and `force` is not set.
  void validate() const;
};

/// A flattened program.
struct GcodeFlattenResult {
  cnc::FlatProgram flat;  ///< the text and where each line comes from
  /// One line summing up the run ("N executed blocks written, L lines ..."), no newline.
  std::string note;
};

/// Flattens the program and, when `out` is set, writes it through io::AtomicFile. Throws
/// pkm::IoError "NAME:LINE: message" as cnc::flattenProgram does, and as validate().
[[nodiscard]] GcodeFlattenResult flattenGcode(const GcodeFlattenRequest& request);

}  // namespace pkm::workflow
