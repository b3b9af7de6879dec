/// @file
/// @brief The interpreter settings of a LinuxCNC 2.9 INI file, as `rs274 -i` reads them (INI
/// reference, "[RS274NGC] Section"; G-code overview, "HAL pins and INI values"): start-up code,
/// centre-arc tolerances, the parameter file, the subroutine path and the INI values
/// #<_ini[section]name> programs may read.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/core/text.hpp"

namespace pkm::cnc {

/// What an INI sets up for the interpreter.
struct Rs274ngcIni {
  std::string startup_code;    ///< [RS274NGC] RS274NGC_STARTUP_CODE ("" : none)
  std::string startup_source;  ///< "INI:LINE" of it
  ArcTolerances arc;           ///< CENTER_ARC_RADIUS_TOLERANCE_MM/_INCH (defaults otherwise)
  /// [RS274NGC] PARAMETER_FILE resolved against the INI's folder ("" : none).
  std::string parameter_file;
  /// [RS274NGC] SUBROUTINE_PATH's folders, resolved against the INI's folder, in order.
  std::vector<std::string> subroutine_path;
  /// The numeric entries with upper-case section and key, for #<_ini[section]name> (empty when
  /// [RS274NGC] INI_VARS = 0).
  std::map<std::string, double> values;
  /// A millimetre machine ([TRAJ] LINEAR_UNITS mm, the default) or an inch one.
  bool inch_machine = false;
  /// The codes `[RS274NGC] REMAP` remaps ("m6", "g81"), with "INI:LINE" of each.
  std::map<std::string, std::string> remapped;
};

/// Reads the interpreter settings of INI `text` named `name` (its path, for relative folders).
/// Throws pkm::IoError "NAME:LINE: message" for a tolerance outside LinuxCNC's range or a
/// malformed line. USER_M_PATH and ON_ABORT_COMMAND have no effect (user M codes are refused by
/// name; pkm stops at an error).
[[nodiscard]] Rs274ngcIni readRs274ngcIni(std::string_view text, const std::string& name);

/// Reads LinuxCNC parameter file `text` named `name` (`NUMBER VALUE` per line; LinuxCNC's .var)
/// into `options`' initial parameters, lengths converted to mm from inches when `inch_machine`.
/// Throws pkm::IoError "NAME:LINE: message" for a malformed line or a number outside 1..5601.
void readParameterFile(std::string_view text,
                       const std::string& name,
                       bool inch_machine,
                       InterpreterOptions& options);

}  // namespace pkm::cnc
