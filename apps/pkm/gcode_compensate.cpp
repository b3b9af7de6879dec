// `pkm gcode compensate --machine CAL.json PROGRAM`: the program pre-distorted for a controller
// that keeps the nominal kinematics (a hexapod or an Exechon); `--hybrid-frame F --x2 POS`: the
// hybrid machine's X2–Y2 squareness corrected in a PKM program (docs/gcode.md "gcode compensate";
// workflow::compensateGcode).
#include "pkm/workflow/gcode_compensate.hpp"

#include <fmt/format.h>

#include <memory>

#include "cli_common.hpp"
#include "gcode_options.hpp"
#include "pkm/io/hexapod_machine.hpp"

namespace pkm::cli {
namespace {

struct CompensateArgs {
  std::string program;
  workflow::GcodeCompensateRequest request;
};

void runCompensate(CompensateArgs& a) {
  a.request.validate();  // option errors before the program is read
  a.request.program = {a.program, io::readTextFile(a.program)};
  const workflow::GcodeCompensateResult r = workflow::compensateGcode(a.request);
  if (a.request.out.empty()) writeTextOutput("", r.compensation.text);
  fmt::print(stderr, "pkm: note: {}\n", r.note);
}

}  // namespace

void addGcodeCompensateCommand(CLI::App& gcode) {
  auto a = std::make_shared<CompensateArgs>();
  workflow::GcodeCompensateRequest& q = a->request;
  CLI::App* c = gcode.add_subcommand(
      "compensate",
      "pre-distort PROGRAM for a controller with nominal kinematics (machine: the output of "
      "`pkm calibrate hexapod --out` or `pkm calibrate exechon --out`)");
  c->add_option("program", a->program, "G-code file (.ngc)")->required();
  c->add_option("--machine", q.machine, "calibrated hexapod or Exechon machine JSON");
  c->add_option("--hybrid-frame",
                q.hybrid_frame,
                "hybrid machine: pkm-base-frame.txt of `pkm campaign run` (X2-Y2 squareness by "
                "G-code correction; X Y Z are PKM commands)");
  c->add_option("--x2", q.x2, "hybrid machine: the X2 position the program runs at, mm");
  c->add_flag("--base-frame-not-in-controller",
              q.frame_not_in_controller,
              "hybrid machine: also apply the base-frame rotation and offset in the program");
  c->add_option("--nominal",
                q.nominal,
                "the controller's nominal machine (default: the built-in one the calibrated "
                "machine's name refers to); a LinuxCNC .hal file finds its INI beside it");
  c->add_option("--ini",
                q.ini,
                "hexapod: the LinuxCNC INI the program runs under (its RS274NGC_STARTUP_CODE, "
                "e.g. G20, runs before the program; its LINEAR_UNITS must be the machine's)");
  c->add_option("--orientation",
                q.orientation,
                "Exechon: A/C as the tool vector of a virtual C/A head ('vector', the default) or "
                "as the wrist readings ('axes'), as in gcode run");
  c->add_option("--max-points",
                q.max_points,
                "most interpolated points the program may need (default 10000000)");
  c->add_option("--tolerance",
                q.tolerance,
                "chordal tolerance in the machine's length unit (default 0.01 mm)");
  addInterpreterOptions(*c, q.interpreter, false);
  c->add_option("--out", q.out, "write the program to FILE instead of standard output");
  c->add_flag("--force", q.force, "overwrite an existing --out file");
  c->callback([a] { runCompensate(*a); });
}

}  // namespace pkm::cli
