/// @file
/// @brief `pkm gcode moves` as a workflow (docs/gcode.md): a G-code program interpreted with
/// LinuxCNC semantics, one CSV row per motion in machine coordinates (mm, degrees), streamed in
/// constant memory to a file or to the caller.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

#include "pkm/io/named_text.hpp"
#include "pkm/workflow/gcode_interpreter.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// A `gcode moves` request.
struct GcodeMovesRequest {
  io::NamedText program;  ///< the program; its name prefixes every message (NAME:LINE: ...)
  /// The program's text when the caller holds it elsewhere for the whole call (a file mapped
  /// into memory, cnc::ProgramFile); empty: `program.text` is read. Messages still use
  /// `program.name`.
  std::string_view program_text;
  std::string out;     ///< the CSV file ("" : the rows go to the caller)
  bool force = false;  ///< replace an existing `out`
  GcodeInterpreterSettings interpreter;
  /// Throws as GcodeInterpreterSettings::validate, and pkm::IoError "OUT exists; pass --force to
  /// overwrite it" when `out` exists and `force` is not set.
  void validate() const;
};

/// Receives the CSV text in pieces of about 1 MiB, in order (e.g. to write standard output).
using TextOutput = std::function<void(std::string_view)>;

/// What a `gcode moves` run did.
struct GcodeMovesResult {
  std::size_t lines = 0;     ///< source lines read
  std::size_t blocks = 0;    ///< blocks executed (loops counted per pass)
  std::size_t moves = 0;     ///< motions, one CSV row each
  bool ended_by_m2 = false;  ///< the program ended with M2 or M30
  /// The CSV when neither `out` nor an output callback was given, else empty.
  std::string csv;
  /// One line summing up the run ("N lines, B blocks executed, M moves ..."), no newline; for a
  /// program with moves under G20 it says that the CSV is in mm all the same.
  std::string note;
};

/// Interprets the program and writes the CSV (cnc::kMoveCsvHeader, then cnc::appendMoveCsv rows)
/// to `request.out` through io::AtomicFile (nothing is left on an error), else to `output`, else
/// into the result. A program without O-words is run while it is read. Progress: every
/// kGcodeProgressInterval motions, with cancellation checked (workflow::Cancelled). Throws
/// pkm::IoError "NAME:LINE: message" for a program the interpreter rejects, and as validate().
[[nodiscard]] GcodeMovesResult runGcodeMoves(const GcodeMovesRequest& request,
                                             const RunControl& control = {},
                                             const TextOutput& output = {});

}  // namespace pkm::workflow
