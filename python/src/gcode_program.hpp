/// @file
/// @brief A G-code program and the interpreter settings from Python arguments, shared by
/// pkm.gcode.moves and pkm.gcode.run (gcode.cpp, gcode_run.cpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "common.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/workflow/gcode_interpreter.hpp"

namespace pkm::python {

/// The program `obj`: an os.PathLike is a file; a str is the program's text when it holds a
/// newline or is not the name of an existing file (a name ending in .ngc, .nc, .tap or .gcode is
/// always a file); else the file it names. A file is named by its path in messages, a text by
/// `name` (default "program"). Throws pkm::IoError "PATH: cannot open G-code file", and
/// pkm::InvalidArgument for another type.
[[nodiscard]] io::NamedText programOf(py::handle obj, const std::optional<std::string>& name);

/// The interpreter settings of the --tool-table, --tool-units, --block-delete and
/// --max-iterations options. Not validated here (the workflows do).
[[nodiscard]] workflow::GcodeInterpreterSettings interpreterOf(const py::object& tool_table,
                                                               const std::string& tool_units,
                                                               bool block_delete,
                                                               std::uint64_t max_iterations);

}  // namespace pkm::python
