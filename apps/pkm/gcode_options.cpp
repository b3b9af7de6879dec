#include "gcode_options.hpp"

#include <fmt/format.h>

#include "pkm/core/error.hpp"

namespace pkm::cli {

void InterpreterArgs::add(CLI::App& cmd, bool all) {
  cmd.add_option("--tool-table", tool_table, "LinuxCNC tool table (.tbl) for G43 and M6");
  cmd.add_option("--tool-units", tool_units, "length unit of the tool table: mm (default) or inch");
  if (!all) return;
  cmd.add_flag("--block-delete", block_delete, "skip lines starting with '/'");
  cmd.add_option("--max-iterations",
                 max_iterations,
                 "iterations one loop may make before the program is rejected (default 1e7)");
}

cnc::InterpreterOptions InterpreterArgs::options() const {
  if (tool_units != "mm" && tool_units != "inch")
    throw InvalidArgument(fmt::format("--tool-units must be mm or inch, not '{}'", tool_units));
  if (max_iterations == 0) throw InvalidArgument("--max-iterations must be positive");
  cnc::InterpreterOptions o;
  if (!tool_table.empty())
    o.tools = cnc::ToolTable::load(tool_table, tool_units == "inch" ? cnc::kMmPerInch : 1.0);
  o.block_delete = block_delete;
  o.max_loop_iterations = max_iterations;
  return o;
}

}  // namespace pkm::cli
