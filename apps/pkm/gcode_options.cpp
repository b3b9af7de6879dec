#include "gcode_options.hpp"

#include "pkm/cnc/program.hpp"

namespace pkm::cli {

void addInterpreterOptions(CLI::App& cmd,
                           workflow::GcodeInterpreterSettings& settings,
                           bool all,
                           bool ini) {
  cmd.add_option("--tool-table", settings.tool_table, "LinuxCNC tool table (.tbl) for G43 and M6");
  if (ini)
    cmd.add_option("--ini",
                   settings.ini,
                   "LinuxCNC INI: its [RS274NGC] start-up code, arc tolerances, parameter file "
                   "and INI values set the interpreter up, as rs274 -i does");
  cmd.add_option(
      "--tool-units", settings.tool_units, "length unit of the tool table: mm (default) or inch");
  if (!all) return;
  cmd.add_flag("--block-delete", settings.block_delete, "skip lines starting with '/'");
  cmd.add_option("--max-iterations",
                 settings.max_iterations,
                 "iterations one loop may make before the program is rejected (default 1e7)");
}

io::NamedText readProgram(const std::string& path) { return {path, cnc::Program::readFile(path)}; }

}  // namespace pkm::cli
