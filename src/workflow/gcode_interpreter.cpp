// The interpreter settings of the G-code workflows (workflow/gcode_interpreter.hpp) and their
// progress reports (gcode_progress.hpp).
#include "pkm/workflow/gcode_interpreter.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "gcode_progress.hpp"
#include "pkm/cnc/interpreter_ini.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::workflow {

void GcodeInterpreterSettings::validate() const {
  if (tool_units != "mm" && tool_units != "inch")
    throw InvalidArgument(fmt::format("--tool-units must be mm or inch, not '{}'", tool_units));
  if (max_iterations == 0) throw InvalidArgument("--max-iterations must be positive");
}

cnc::InterpreterOptions GcodeInterpreterSettings::options() const {
  validate();
  cnc::InterpreterOptions o;
  const double scale = tool_units == "inch" ? cnc::kMmPerInch : 1.0;
  if (!tool_table.empty())
    o.tools = cnc::ToolTable::load(tool_table, scale);
  else if (!tool_table_text.empty())
    o.tools = cnc::ToolTable::parse(tool_table_text, scale, tool_table_name);
  o.block_delete = block_delete;
  o.max_loop_iterations = max_iterations;
  o.startup_code = startup_code;
  o.startup_source = startup_source;
  o.require_program_end = require_program_end;
  o.search_working_folder = search_working_folder;
  if (!ini.empty()) {
    const io::NamedText text = io::readNamedText(ini);
    const cnc::Rs274ngcIni r = cnc::readRs274ngcIni(text.text, text.name);
    if (o.startup_code.empty()) {
      o.startup_code = r.startup_code;
      o.startup_source = r.startup_source;
    }
    o.arc = r.arc;
    o.subroutine_path = r.subroutine_path;
    o.remapped_codes = r.remapped;
    o.ini_values = r.values;
    // LinuxCNC starts with zeros and creates the file when it is missing; so does pkm.
    if (!r.parameter_file.empty() && std::filesystem::exists(r.parameter_file)) {
      const io::NamedText var = io::readNamedText(r.parameter_file);
      cnc::readParameterFile(var.text, var.name, r.inch_machine, o);
    }
  }
  return o;
}

void takeStartupCode(const io::HexapodMachine& machine, GcodeInterpreterSettings& settings) {
  if (machine.startup_code.empty()) return;
  settings.startup_code = machine.startup_code;
  settings.startup_source = machine.startup_code_source;
}

namespace detail {

void GcodeProgress::report(const char* stage,
                           const char* what,
                           std::size_t index,
                           std::size_t count,
                           std::size_t done,
                           std::size_t total) const {
  if (control_.progress) {
    ProgressEvent e;
    e.stage = stage;
    e.index = index;
    e.count = count;
    e.elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    e.message = total > 0 ? fmt::format("{}: {}/{} {}", stage, done, total, what)
                          : fmt::format("{}: {} {}", stage, done, what);
    control_.report(e);
  }
  control_.checkCancelled();
}

}  // namespace detail
}  // namespace pkm::workflow
