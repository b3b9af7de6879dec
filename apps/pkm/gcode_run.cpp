// `pkm gcode run --machine M PROGRAM`: interpret a G-code program, convert it to the joints of a
// hexapod or an Exechon, time it and check every limit (docs/gcode.md "gcode run";
// workflow::runGcode, io::gcodeRunText).
#include "pkm/workflow/gcode_run.hpp"

#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "gcode_options.hpp"
#include "pkm/io/gcode_run_report.hpp"

namespace pkm::cli {
namespace {

/// Exit code when a check is violated.

/// A rate option and whether the user gave it (else the machine file's value applies).
struct RateOption {
  double value;
  CLI::Option* option = nullptr;
  [[nodiscard]] std::optional<double> given() const {
    return option->count() > 0 ? std::optional<double>(value) : std::nullopt;
  }
};

struct RunArgs {
  std::string program;
  workflow::GcodeRunRequest request;
  RateOption velocity{200.0}, acceleration{2000.0};              ///< machine length unit/s, /s²
  RateOption wrist_velocity{180.0}, wrist_acceleration{1800.0};  ///< deg/s, deg/s² (Exechon)
  std::string stock;  ///< --stock SPEC ("" : no machining preview)
  double stock_cell = 0.0;
};

void runGcode(RunArgs& a) {
  workflow::GcodeRunRequest& q = a.request;
  q.max_joint_velocity = a.velocity.given();
  q.max_joint_acceleration = a.acceleration.given();
  q.max_wrist_velocity = a.wrist_velocity.given();
  q.max_wrist_acceleration = a.wrist_acceleration.given();
  if (!a.stock.empty()) {
    q.machining.emplace();
    workflow::setStock(*q.machining, a.stock);
    q.machining->cell = a.stock_cell;
  } else if (a.stock_cell != 0.0) {
    throw InvalidArgument("--stock-cell needs --stock");
  }
  q.validate();  // option errors before the program is read
  q.program = readProgram(a.program);
  CliRunControl control;
  const workflow::GcodeRunResult r = workflow::runGcode(q, control.control());
  control.finish();
  Output out;
  out.text() = io::gcodeRunText(r.report);
  if (r.machining) out.text() += workflow::machiningText(*r.machining);
  out.flush();
  if (!r.ok()) throw ExitCode{kExitCheckFailed};
}

void addRateOptions(CLI::App& r, RunArgs& a) {
  a.velocity.option = r.add_option("--max-joint-velocity",
                                   a.velocity.value,
                                   "strut speed limit, machine length unit/s (default: the machine "
                                   "file's joint_rates, else 200)");
  a.acceleration.option = r.add_option(
      "--max-joint-acceleration",
      a.acceleration.value,
      "strut acceleration limit, machine length unit/s^2 (default: the machine file's, else 2000)");
  a.wrist_velocity.option =
      r.add_option("--max-wrist-velocity",
                   a.wrist_velocity.value,
                   "Exechon wrist C/A speed limit, deg/s (default: the machine file's, else 180)");
  a.wrist_acceleration.option = r.add_option(
      "--max-wrist-acceleration",
      a.wrist_acceleration.value,
      "Exechon wrist C/A acceleration limit, deg/s^2 (default: the machine file's, else 1800)");
  r.add_option("--rapid-rate",
               a.request.rapid_rate,
               "G0 path speed, mm/min (default: a LinuxCNC INI's [TRAJ] MAX_LINEAR_VELOCITY, else "
               "10000)");
}

}  // namespace

void addGcodeRunCommand(CLI::App& gcode) {
  auto a = std::make_shared<RunArgs>();
  workflow::GcodeRunRequest& q = a->request;
  CLI::App* r = gcode.add_subcommand(
      "run",
      "interpolate PROGRAM, convert it to the joints of a hexapod or an Exechon, estimate the "
      "cycle time and check every limit (exit 1 on a violation)");
  r->add_option("program", a->program, "G-code file (.ngc)")->required();
  addMachineOptions(*r, q.machine, q.ini);
  r->add_option("--strut-diameter",
                q.strut_diameter,
                "hexapod: strut diameter for the interference check, machine unit (default: the "
                "machine file's; a LinuxCNC configuration has none)")
      ->check(CLI::PositiveNumber);
  r->add_option("--orientation",
                q.orientation,
                "Exechon: A/C words are the tool vector's angles in the world frame (vector, "
                "default) or the wrist axes' readings (axes)");
  r->add_option("--max-points",
                q.max_points,
                "most interpolated points the program may need (default 10000000); more is "
                "refused at the line that crosses it");
  r->add_option("--tolerance",
                q.tolerance,
                "chordal tolerance in the machine's length unit (default 0.01 mm)");
  addInterpreterOptions(*r, q.interpreter);
  r->add_option("--out", q.out, "write the joint CSV to FILE (docs/gcode.md)");
  r->add_option("--report", q.report, "write the check report as JSON to FILE");
  r->add_flag("--force", q.force, "overwrite existing --out/--report files");
  addRateOptions(*r, *a);
  r->add_option("--stock",
                a->stock,
                "machining preview (docs/machining.md): remove material from auto (the feed "
                "moves' box), box:X0,Y0,Z0,X1,Y1,Z1 or cylinder:CX,CY,R,Z0,Z1 (mm) with the tool "
                "table's tools, and report collisions (rapids, holder, platform, table)");
  r->add_option("--stock-cell", a->stock_cell, "the preview's cell size, mm (default: automatic)")
      ->check(CLI::NonNegativeNumber);
  r->callback([a] { runGcode(*a); });
}

}  // namespace pkm::cli
