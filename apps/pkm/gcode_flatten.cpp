// `pkm gcode flatten PROGRAM`: the blocks a program executes, in execution order, with every
// expression evaluated and no O-word statements (docs/gcode.md "gcode flatten";
// workflow::flattenGcode).
#include "pkm/workflow/gcode_flatten.hpp"

#include <fmt/format.h>

#include <memory>

#include "cli_common.hpp"
#include "gcode_options.hpp"

namespace pkm::cli {

namespace {

struct FlattenArgs {
  std::string program;
  workflow::GcodeFlattenRequest request;
};

void runFlatten(FlattenArgs& a) {
  a.request.validate();  // option errors before the program is read
  a.request.program = readProgram(a.program);
  const workflow::GcodeFlattenResult r = workflow::flattenGcode(a.request);
  if (a.request.out.empty()) writeTextOutput("", r.flat.text);
  fmt::print(stderr, "pkm: note: {}\n", r.note);
}

}  // namespace

void addGcodeFlattenCommand(CLI::App& gcode) {
  auto a = std::make_shared<FlattenArgs>();
  CLI::App* f = gcode.add_subcommand(
      "flatten",
      "write the blocks PROGRAM executes, in execution order, with expressions evaluated and no "
      "O-words (subroutines, loops and conditions unrolled)");
  f->add_option("program", a->program, "G-code file (.ngc)")->required();
  f->add_option("--out", a->request.out, "write the program to FILE instead of standard output");
  f->add_flag("--force", a->request.force, "overwrite an existing --out file");
  addInterpreterOptions(*f, a->request.interpreter, true, true);
  f->callback([a] { runFlatten(*a); });
}

}  // namespace pkm::cli
