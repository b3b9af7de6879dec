// `pkm gcode flatten PROGRAM`: the blocks a program executes, in execution order, with every
// expression evaluated and no O-word statements (docs/gcode.md "gcode flatten").
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli_common.hpp"
#include "pkm/cnc/flatten.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cli {

namespace {

struct FlattenArgs {
  std::string program;
  std::string out;
  bool force = false;
  std::string tool_table;
  std::string tool_units = "mm";
  bool block_delete = false;
  std::uint64_t max_iterations = 10'000'000;
};

void runFlatten(const FlattenArgs& a) {
  if (a.tool_units != "mm" && a.tool_units != "inch")
    throw InvalidArgument(fmt::format("--tool-units must be mm or inch, not '{}'", a.tool_units));
  if (a.max_iterations == 0) throw InvalidArgument("--max-iterations must be positive");
  if (!a.out.empty() && !a.force && std::filesystem::exists(a.out))
    throw IoError(fmt::format("{} exists; pass --force to overwrite it", a.out));
  cnc::InterpreterOptions options;
  if (!a.tool_table.empty())
    options.tools =
        cnc::ToolTable::load(a.tool_table, a.tool_units == "inch" ? cnc::kMmPerInch : 1.0);
  options.block_delete = a.block_delete;
  options.max_loop_iterations = a.max_iterations;
  const std::string text = cnc::Program::readFile(a.program);
  const cnc::FlatProgram flat = cnc::flattenProgram(text, a.program, options);
  if (a.out.empty()) {
    std::fwrite(flat.text.data(), 1, flat.text.size(), stdout);
    std::fflush(stdout);
  } else {
    const std::string tmp = a.out + ".tmp";
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (f == nullptr) throw IoError(fmt::format("{}: cannot write", a.out));
    std::fwrite(flat.text.data(), 1, flat.text.size(), f);
    if (std::fclose(f) != 0) throw IoError(fmt::format("{}: write failed", a.out));
    std::filesystem::rename(tmp, a.out);
  }
  fmt::print(stderr,
             "pkm: note: {} executed blocks written, {} lines{}\n",
             flat.blocks,
             flat.source_line.size(),
             flat.had_o_words ? "" : " (the program has no O-words)");
}

}  // namespace

void addGcodeFlattenCommand(CLI::App& gcode) {
  auto a = std::make_shared<FlattenArgs>();
  CLI::App* f = gcode.add_subcommand(
      "flatten",
      "write the blocks PROGRAM executes, in execution order, with expressions evaluated and no "
      "O-words (subroutines, loops and conditions unrolled)");
  f->add_option("program", a->program, "G-code file (.ngc)")->required();
  f->add_option("--out", a->out, "write the program to FILE instead of standard output");
  f->add_flag("--force", a->force, "overwrite an existing --out file");
  f->add_option("--tool-table", a->tool_table, "LinuxCNC tool table (.tbl) for G43 and M6");
  f->add_option("--tool-units",
                a->tool_units,
                "length unit of the tool table: mm (default) or inch (the machine's unit)");
  f->add_flag("--block-delete", a->block_delete, "skip lines starting with '/'");
  f->add_option("--max-iterations",
                a->max_iterations,
                "iterations one loop may make before the program is rejected (default 1e7)");
  f->callback([a] { runFlatten(*a); });
}

}  // namespace pkm::cli
