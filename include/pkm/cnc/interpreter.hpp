/// @file
/// @brief RS274NGC interpreter with LinuxCNC 2.9 semantics: executes a Program and reports every
/// motion, in machine coordinates (mm, degrees), to a MoveSink (docs/gcode.md lists the supported
/// codes; anything else is an error naming the line).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "pkm/cnc/arc.hpp"
#include "pkm/cnc/line_reader.hpp"
#include "pkm/cnc/modal_state.hpp"
#include "pkm/cnc/move.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/cnc/tool_table.hpp"

namespace pkm::cnc {

/// Interpreter settings.
struct InterpreterOptions {
  ToolTable tools;            ///< tool table for G43 / M6 (lengths in mm)
  bool block_delete = false;  ///< skip lines starting with '/' (LinuxCNC's block delete switch)
  /// Iterations one activation of a while/do/repeat loop may make before the program is
  /// rejected as runaway (no hang on `while [1]`); also the most motions one canned-cycle block
  /// may expand to (L repeats times pecks).
  std::uint64_t max_loop_iterations = 10'000'000;
  /// Motions one run may send to its sink; more is refused at the line that crosses it (a runaway
  /// program's memory is bounded before it is spent: 20 million moves took 3.4 GB). 0: no limit.
  std::size_t max_moves = 0;
  /// Refuse a program that ends without M2/M30 and is not enclosed in `%` lines, as LinuxCNC's
  /// rs274 does ("file ended with no percent sign or program end"); off for snippets.
  bool require_program_end = false;
  /// Deepest subroutine nesting.
  std::size_t max_call_depth = 64;
  /// Blocks the controller runs before every program, e.g. "G20 G17 G40" (LinuxCNC's INI
  /// [RS274NGC] RS274NGC_STARTUP_CODE): the program's modes start where they leave them. ""
  /// : none. Run by the Interpreter's constructor; a motion in them is an error.
  std::string startup_code;
  /// Where startup_code comes from, prefixed to its messages ("hexapod.ini:12"; "" : nothing).
  std::string startup_source;
  /// Folders searched for NAME.ngc when a program calls a sub it does not define (INI
  /// [RS274NGC] SUBROUTINE_PATH, in order), after the working folder when
  /// search_working_folder (where LinuxCNC's rs274 looks first; off for uploads).
  std::vector<std::string> subroutine_path;
  bool search_working_folder = true;
  /// Centre-format arc tolerances (INI [RS274NGC] CENTER_ARC_RADIUS_TOLERANCE_MM/_INCH).
  ArcTolerances arc;
  /// The INI's numeric entries for #<_ini[section]name>, keyed "section]name" in lower case
  /// (LinuxCNC upper-cases the name before it looks it up, so only upper-case entries count).
  std::map<std::string, double> ini_values;
  /// Codes an INI remaps ("m6" -> "machine.ini:22"): a program that uses one is refused, since
  /// pkm does not run the remap's procedure.
  std::map<std::string, std::string> remapped_codes;
  /// Numbered parameters at start-up (a LinuxCNC parameter file, lengths in mm): offsets of the
  /// coordinate systems and G92 (#5210-#5390), the active system (#5220), G28/G30 positions and
  /// the user's values. Applied before startup_code.
  std::map<int, double> initial_parameters;
};

/// What a run did.
struct RunSummary {
  std::size_t blocks = 0;  ///< blocks executed (loops counted per pass)
  std::size_t moves = 0;   ///< motions sent to the sink
  /// Of which made under G20: their program said inches, the moves are in mm all the same.
  std::size_t inch_moves = 0;
  bool ended_by_m2 = false;  ///< the program ended with M2 or M30
};

/// Executes programs. One interpreter keeps its state (offsets, modes) from run to run, as a
/// controller does; construct a new one for a fresh start (G54, G17, G21, G90, G94, G99, no
/// offsets, machine at 0, then the options' startup_code).
class Interpreter {
 public:
  /// Throws pkm::IoError "SOURCE: RS274NGC_STARTUP_CODE...: message" for start-up code the
  /// interpreter rejects or that moves the machine.
  explicit Interpreter(InterpreterOptions options = {});
  ~Interpreter();
  Interpreter(const Interpreter&) = delete;
  Interpreter& operator=(const Interpreter&) = delete;

  /// Runs `program`, sending each motion to `sink`. Throws pkm::IoError "FILE:LINE: message" for
  /// an unsupported code, a modal-group conflict, a missing or misplaced word, an expression
  /// error, a runaway loop, an undefined subroutine.
  RunSummary run(const Program& program, MoveSink& sink);

  /// Runs a program without O-word statements while it is read (constant memory, for long
  /// programs): each block is executed as `reader` delivers it. After M2/M30 the rest is still
  /// read, so a malformed line anywhere is reported as by Program::parse; errors come in reading
  /// order (as LinuxCNC reports them). Throws pkm::IoError "FILE:LINE: message" as run() does,
  /// and for an O-word statement ("needs the whole program"): check
  /// LineReader::mayHaveOWords first and use Program::parse and run() when it is true.
  RunSummary runStream(LineReader& reader, MoveSink& sink);

  /// The modal state and offsets now.
  [[nodiscard]] const MachineState& state() const;
  /// Whether the last run stopped at a tool its tool table lacks (G43 H, G10 L1/L10/L11, or T
  /// with a table that does not hold it): a caller may look for the right table and run again.
  [[nodiscard]] bool missingTool() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pkm::cnc
