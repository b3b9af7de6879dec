// `pkm gcode moves PROGRAM`: interpret an RS274NGC program with LinuxCNC semantics and write one
// CSV row per motion in machine coordinates (docs/gcode.md; workflow::runGcodeMoves).
#include <fmt/format.h>

#include <cstdio>
#include <memory>

#include "cli_common.hpp"
#include "gcode_options.hpp"
#include "pkm/cnc/program_file.hpp"
#include "pkm/workflow/gcode_moves.hpp"

namespace pkm::cli {

void addGcodeRunCommand(CLI::App& gcode);         // gcode_run.cpp
void addGcodeCompensateCommand(CLI::App& gcode);  // gcode_compensate.cpp
void addGcodeFlattenCommand(CLI::App& gcode);     // gcode_flatten.cpp
void addGcodeMakeCommand(CLI::App& gcode);        // gcode_make.cpp

namespace {

struct MovesArgs {
  std::string program;
  workflow::GcodeMovesRequest request;
};

void runMoves(MovesArgs& a) {
  a.request.validate();                    // option errors before the program is read
  const cnc::ProgramFile file(a.program);  // mapped, not copied
  a.request.program.name = a.program;
  a.request.program_text = file.text();
  CliRunControl control;
  const workflow::GcodeMovesResult r =
      workflow::runGcodeMoves(a.request, control.control(), [](std::string_view text) {
        std::fwrite(text.data(), 1, text.size(), stdout);
      });
  control.finish();
  fmt::print(stderr, "pkm: note: {}\n", r.note);
  std::fflush(stdout);
}

void addGcodeCommand(CLI::App& app) {
  CLI::App* g = app.add_subcommand("gcode", "RS274NGC (LinuxCNC) G-code programs");
  g->require_subcommand(1);
  auto a = std::make_shared<MovesArgs>();
  CLI::App* m = g->add_subcommand(
      "moves",
      "interpret PROGRAM and write one CSV row per motion in machine coordinates (mm, deg)");
  m->add_option("program", a->program, "G-code file (.ngc)")->required();
  m->add_option("--out", a->request.out, "write the CSV to FILE instead of standard output");
  m->add_flag("--force", a->request.force, "overwrite an existing --out file");
  addInterpreterOptions(*m, a->request.interpreter, true, true);
  m->callback([a] { runMoves(*a); });
  addGcodeRunCommand(*g);
  addGcodeCompensateCommand(*g);
  addGcodeFlattenCommand(*g);
  addGcodeMakeCommand(*g);
}

const CommandRegistration kRegisterGcode{60, "gcode", &addGcodeCommand};

}  // namespace
}  // namespace pkm::cli
