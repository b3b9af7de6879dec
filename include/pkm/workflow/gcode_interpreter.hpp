/// @file
/// @brief The interpreter settings every G-code job shares (`pkm gcode moves|run|compensate|
/// flatten`, docs/gcode.md): tool table, block delete, runaway-loop guard, and the check interval
/// of the long G-code jobs' progress reports and cancellation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/io/hexapod_machine.hpp"

namespace pkm::workflow {

/// The chordal tolerance of `gcode run` and `gcode compensate` without --tolerance, mm.
inline constexpr double kDefaultToleranceMm = 0.01;

/// Motions (or interpolated points) between two progress reports of a G-code job; each report is
/// also a cancellation check (RunControl).
inline constexpr std::size_t kGcodeProgressInterval = 10'000;

/// How a G-code program is interpreted (LinuxCNC 2.9 semantics).
struct GcodeInterpreterSettings {
  std::string tool_table;  ///< LinuxCNC tool table (.tbl) for G43 and M6 ("" : none)
  /// A tool table's text instead of a file (an upload; used when tool_table is ""), and the name
  /// its messages give it.
  std::string tool_table_text;
  std::string tool_table_name = "tools.tbl";
  std::string tool_units = "mm";  ///< the tool table's length unit: "mm" or "inch"
  bool block_delete = false;      ///< skip lines starting with '/'
  /// Iterations one loop may make before the program is rejected as runaway (> 0).
  std::uint64_t max_iterations = 10'000'000;
  /// What the controller runs before the program (a LinuxCNC INI's RS274NGC_STARTUP_CODE, e.g.
  /// "G20"; "" : none); the jobs with a LinuxCNC machine set it from the INI.
  std::string startup_code;
  std::string startup_source;  ///< where startup_code comes from ("INI:LINE"), for messages
  /// A LinuxCNC INI whose [RS274NGC] section sets the interpreter up, as `rs274 -i` does
  /// (io/rs274ngc_ini.hpp: start-up code unless startup_code is set, arc tolerances, parameter
  /// file, #<_ini[section]name> values); "" : none.
  std::string ini;
  /// Refuse a program without M2/M30 that is not enclosed in `%` lines, as LinuxCNC does.
  bool require_program_end = true;
  /// Look for called sub files (NAME.ngc) in the working folder first, as rs274 does; the
  /// server turns it off (an upload has no folder).
  bool search_working_folder = true;
  /// Throws pkm::InvalidArgument for a unit other than mm or inch (naming --tool-units) or a
  /// zero iteration cap (naming --max-iterations).
  void validate() const;
  /// The interpreter options, with the tool table and the INI read (lengths converted to mm).
  /// Throws as validate(), and pkm::IoError "FILE:LINE: message" for an unreadable or malformed
  /// table, INI or parameter file.
  [[nodiscard]] cnc::InterpreterOptions options() const;
};

/// Sets `settings`' start-up code to `machine`'s (its INI's RS274NGC_STARTUP_CODE), if it has
/// one, as LinuxCNC runs it before every program.
void takeStartupCode(const io::HexapodMachine& machine, GcodeInterpreterSettings& settings);

}  // namespace pkm::workflow
