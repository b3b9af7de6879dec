// `pkm gcode flatten PROGRAM`: the blocks a program executes, in execution order, with every
// expression evaluated and no O-word statements (docs/gcode.md "gcode flatten").
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli_common.hpp"
#include "gcode_options.hpp"
#include "pkm/cnc/flatten.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cli {

namespace {

struct FlattenArgs {
  std::string program;
  std::string out;
  bool force = false;
  InterpreterArgs interpreter;
};

void runFlatten(const FlattenArgs& a) {
  const cnc::InterpreterOptions options = a.interpreter.options();
  if (!a.out.empty() && !a.force && std::filesystem::exists(a.out))
    throw IoError(fmt::format("{} exists; pass --force to overwrite it", a.out));
  const std::string text = cnc::Program::readFile(a.program);
  const cnc::FlatProgram flat = cnc::flattenProgram(text, a.program, options);
  writeTextOutput(a.out, flat.text);
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
  a->interpreter.add(*f);
  f->callback([a] { runFlatten(*a); });
}

}  // namespace pkm::cli
