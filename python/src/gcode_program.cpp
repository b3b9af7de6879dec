// G-code programs and interpreter settings from Python arguments (gcode_program.hpp).
#include "gcode_program.hpp"

#include <array>
#include <filesystem>
#include <string_view>

#include "paths.hpp"
#include "pkm/cnc/program.hpp"

namespace pkm::python {

namespace {

/// Whether `s` ends in a G-code file extension.
bool hasProgramExtension(std::string_view s) {
  for (const std::string_view ext :
       std::array<std::string_view, 4>{".ngc", ".nc", ".tap", ".gcode"})
    if (s.size() > ext.size() && s.substr(s.size() - ext.size()) == ext) return true;
  return false;
}

}  // namespace

io::NamedText programOf(py::handle obj, const std::optional<std::string>& name) {
  bool file = !py::isinstance<py::str>(obj);
  const std::string s = pathOf(obj, "program (a file or the program's text)");
  if (!file && s.find('\n') == std::string::npos) {
    std::error_code ec;
    file = hasProgramExtension(s) || std::filesystem::is_regular_file(s, ec);
  }
  if (file) return {name.value_or(s), cnc::Program::readFile(s)};
  return {name.value_or("program"), s};
}

workflow::GcodeInterpreterSettings interpreterOf(const py::object& tool_table,
                                                 const std::string& tool_units,
                                                 bool block_delete,
                                                 std::uint64_t max_iterations) {
  workflow::GcodeInterpreterSettings s;
  if (!tool_table.is_none()) s.tool_table = pathOf(tool_table, "tool_table");
  s.tool_units = tool_units;
  s.block_delete = block_delete;
  s.max_iterations = max_iterations;
  return s;
}

}  // namespace pkm::python
