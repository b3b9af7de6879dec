/// @file
/// @brief What the `pkm gcode` commands share: the interpreter options (tool table, block delete,
/// loop guard) and the reading of the program.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "pkm/io/named_text.hpp"
#include "pkm/workflow/gcode_interpreter.hpp"

namespace pkm::cli {

/// Adds --tool-table, --tool-units, --block-delete and --max-iterations (all four, or the tool
/// table's two only) to `cmd`, stored in `settings`; and --ini when `ini` (the commands with a
/// machine's --ini of their own pass that one on to the interpreter in their workflow).
void addInterpreterOptions(CLI::App& cmd,
                           workflow::GcodeInterpreterSettings& settings,
                           bool all = true,
                           bool ini = false);

/// The G-code file `path`, named by its path. Throws pkm::IoError "PATH: cannot open G-code
/// file".
[[nodiscard]] io::NamedText readProgram(const std::string& path);

}  // namespace pkm::cli
