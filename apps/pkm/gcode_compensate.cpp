// `pkm gcode compensate --machine CAL.json PROGRAM`: the program pre-distorted for a controller
// that keeps the nominal kinematics (a hexapod or an Exechon); `--hybrid-frame F --x2 POS`: the
// hybrid machine's X2–Y2 squareness corrected in a PKM program (docs/gcode.md "gcode compensate").
#include <fmt/format.h>

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "cli_common.hpp"
#include "gcode_options.hpp"
#include "pkm/cnc/exechon_path.hpp"
#include "pkm/cnc/exechon_program_compensation.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/cnc/program_compensation.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/machine_loader.hpp"

namespace pkm::cli {
namespace {

struct CompensateArgs {
  std::string program;
  std::string machine;
  std::string nominal;
  double tolerance = 0.01;
  std::string out;
  bool force = false;
  std::string hybrid_frame;  ///< pkm-base-frame.txt of a hybrid campaign
  std::optional<double> x2;  ///< the X2 position the PKM program runs at, mm
  bool frame_not_in_controller = false;
  std::optional<std::string> orientation;  ///< Exechon: what A/C mean (as gcode run)
  InterpreterArgs interpreter;             ///< the tool table (G43 H)
};

/// Reads `key = a b c` lines of a pkm-base-frame.txt (docs/campaign.md); `#` lines are comments.
compensation::HybridSquarenessCompensation readBaseFrame(const std::string& path) {
  const std::string text = io::readTextFile(path);
  std::map<std::string, Eigen::Vector3d> values;
  std::size_t line_no = 0, start = 0;
  while (start < text.size()) {
    std::size_t nl = text.find('\n', start);
    if (nl == std::string::npos) nl = text.size();
    const std::string line = text.substr(start, nl - start);
    start = nl + 1;
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    const std::size_t eq = line.find('=');
    std::istringstream in(eq == std::string::npos ? std::string() : line.substr(eq + 1));
    Eigen::Vector3d v;
    std::string rest;
    if (eq == std::string::npos || !(in >> v.x() >> v.y() >> v.z()) || (in >> rest) ||
        !v.allFinite())
      throw IoError(fmt::format("{}:{}: expected 'key = a b c'", path, line_no));
    std::string key = line.substr(0, eq);
    key.erase(key.find_last_not_of(' ') + 1);
    values[key] = v;
  }
  compensation::HybridSquarenessCompensation c;
  for (const char* key : {"base_rpy_rad", "base_offset_mm", "per_x2"})
    if (!values.count(key)) throw IoError(fmt::format("{}: '{}' is missing", path, key));
  c.base_rpy = values["base_rpy_rad"];
  c.base_rotation = geometry::rotationFromRpy(c.base_rpy);
  c.base_offset = values["base_offset_mm"];
  c.per_x2 = values["per_x2"];
  return c;
}

/// "; O-words: flattened ..." when the program had to be flattened first.
std::string flattenedNote(const cnc::ProgramCompensation& r) {
  if (r.flattened_blocks == 0) return "";
  return fmt::format(
      "; the program has O-words: its {} executed blocks were flattened first (pkm gcode "
      "flatten)",
      r.flattened_blocks);
}

/// The hybrid machine's squareness correction (--hybrid-frame, --x2).
void runHybrid(const CompensateArgs& a) {
  if (!a.x2) throw InvalidArgument("--hybrid-frame needs --x2 POS (the X2 position, mm)");
  const compensation::HybridSquarenessCompensation c = readBaseFrame(a.hybrid_frame);
  cnc::InterpolationOptions options;
  options.tolerance = a.tolerance;
  const std::string text = io::readTextFile(a.program);
  const cnc::ProgramCompensation r = cnc::compensateHybridProgram(
      text, a.program, c, *a.x2, !a.frame_not_in_controller, options, a.interpreter.options());
  writeTextOutput(a.out, r.text);
  fmt::print(stderr,
             "pkm: note: hybrid squareness correction at X2 = {} mm ({}): {} motion lines "
             "rewritten, {} lines added (segments, dwells), {} G92/G10 L20 lines shifted, largest "
             "correction "
             "{:.4g} mm{}\n",
             *a.x2,
             a.frame_not_in_controller ? "base frame and X2 term"
                                       : "X2 term; base frame in the controller",
             r.motion_lines,
             r.added_lines,
             r.offset_lines,
             r.max_correction,
             flattenedNote(r));
}

/// Suffix `pkm calibrate hexapod` and `pkm calibrate exechon` append to the nominal machine's
/// name.
constexpr std::string_view kCalibratedSuffix = "-calibrated";

/// The nominal machine of calibrated machine `cal`: --nominal (loaded by `load`), or the built-in
/// machine of `type` ("hexapod" or "exechon", loaded by `builtin`) whose name is cal's without
/// "-calibrated".
template <class Machine, class Load, class Builtin>
Machine nominalFor(
    const CompensateArgs& a, const Machine& cal, const char* type, Load load, Builtin builtin) {
  if (!a.nominal.empty()) return load(a.nominal);
  const std::string& name = cal.model.name;
  if (name.size() > kCalibratedSuffix.size() && name.ends_with(kCalibratedSuffix)) {
    const std::string base = name.substr(0, name.size() - kCalibratedSuffix.size());
    for (const auto& n : io::builtinMachineNames(type)) {
      Machine m = builtin(n);
      if (m.model.name == base) return m;
    }
  }
  throw InvalidArgument(
      fmt::format("{}: cannot tell the nominal machine of '{}' (no built-in {} named as it without "
                  "'-calibrated'); pass --nominal MACHINE",
                  a.machine,
                  name,
                  type));
}

/// The note on standard error after a pre-distortion: what was compensated (`what`), the line
/// counts, the interpolation settings (mm) and the largest correction.
void printNote(const std::string& what,
               const cnc::ProgramCompensation& r,
               double tolerance,
               double max_step) {
  fmt::print(
      stderr,
      "pkm: note: {}: {} motion lines rewritten, {} lines added (segments, dwells), {} G92/G10 L20 "
      "lines shifted (tolerance {} mm, max step {:.4g} mm), largest correction {:.4g} mm{}\n",
      what,
      r.motion_lines,
      r.added_lines,
      r.offset_lines,
      tolerance,
      max_step,
      r.max_correction,
      flattenedNote(r));
}

void runExechon(const CompensateArgs& a) {
  const io::ExechonMachine cal = io::loadExechonMachine(a.machine);
  if (!a.nominal.empty() && machineTypeOf(a.nominal) != "exechon")
    throw InvalidArgument(
        fmt::format("--nominal {}: not an Exechon machine, but {} is one", a.nominal, a.machine));
  const io::ExechonMachine nominal =
      nominalFor(a, cal, "exechon", &io::loadExechonMachine, &io::loadExechonMachine);
  cnc::ExechonProgramCompensationOptions options;
  const std::string orientation = a.orientation.value_or("vector");
  options.orientation = cnc::parseExechonOrientation(orientation);
  options.interpolation = cnc::exechonInterpolation(cal.model, a.tolerance);
  options.fk = nominal.fk;
  options.interpreter = a.interpreter.options();
  const std::string text = io::readTextFile(a.program);
  const cnc::ProgramCompensation r =
      cnc::compensateExechonProgram(text, a.program, nominal.model, cal.model, options);
  writeTextOutput(a.out, r.text);
  printNote(fmt::format("nominal {} -> calibrated {} (Exechon, --orientation {})",
                        nominal.model.name,
                        cal.model.name,
                        orientation),
            r,
            a.tolerance,
            options.interpolation.max_step);
}

void runCompensate(const CompensateArgs& a) {
  PKM_CHECK(a.tolerance > 0.0 && std::isfinite(a.tolerance), "--tolerance must be > 0");
  if (!a.out.empty() && !a.force && std::filesystem::exists(a.out))
    throw IoError(fmt::format("{} exists; pass --force to overwrite it", a.out));
  if (a.hybrid_frame.empty() == a.machine.empty())
    throw InvalidArgument(
        "give either --machine CAL.json (hexapod or Exechon) or --hybrid-frame FILE --x2 POS");
  if (!a.hybrid_frame.empty()) return runHybrid(a);
  if (machineTypeOf(a.machine) == "exechon") return runExechon(a);
  if (a.orientation)
    throw InvalidArgument(
        fmt::format("--orientation is for Exechon machines; {} is a hexapod", a.machine));
  const io::HexapodMachine cal = io::loadHexapodMachine(a.machine);
  const io::HexapodMachine nominal = nominalFor(
      a,
      cal,
      "hexapod",
      [](const std::string& spec) { return io::loadHexapodMachine(spec); },
      &io::builtinMachine);
  if (nominal.model.unit != cal.model.unit)
    throw InvalidArgument("the nominal and calibrated machines use different length units");
  cnc::ProgramCompensationOptions options;
  options.interpolation = cnc::jointSpaceInterpolation(cal.model, a.tolerance);
  options.predistortion.fk = nominal.fk;
  options.interpreter = a.interpreter.options();
  const std::string text = io::readTextFile(a.program);
  const cnc::ProgramCompensation r =
      cnc::compensateProgram(text, a.program, nominal.model, cal.model, options);
  writeTextOutput(a.out, r.text);
  printNote(fmt::format("nominal {} -> calibrated {}", nominal.model.name, cal.model.name),
            r,
            a.tolerance,
            options.interpolation.max_step);
}

}  // namespace

void addGcodeCompensateCommand(CLI::App& gcode) {
  auto a = std::make_shared<CompensateArgs>();
  CLI::App* c = gcode.add_subcommand(
      "compensate",
      "pre-distort PROGRAM for a controller with nominal kinematics (machine: the output of "
      "`pkm calibrate hexapod --out` or `pkm calibrate exechon --out`)");
  c->add_option("program", a->program, "G-code file (.ngc)")->required();
  c->add_option("--machine", a->machine, "calibrated hexapod or Exechon machine JSON");
  c->add_option("--hybrid-frame",
                a->hybrid_frame,
                "hybrid machine: pkm-base-frame.txt of `pkm campaign run` (X2-Y2 squareness by "
                "G-code correction; X Y Z are PKM commands)");
  c->add_option("--x2", a->x2, "hybrid machine: the X2 position the program runs at, mm");
  c->add_flag("--base-frame-not-in-controller",
              a->frame_not_in_controller,
              "hybrid machine: also apply the base-frame rotation and offset in the program");
  c->add_option("--nominal",
                a->nominal,
                "the controller's nominal machine (default: the built-in one the calibrated "
                "machine's name refers to)");
  c->add_option("--orientation",
                a->orientation,
                "Exechon: A/C as the tool vector of a virtual C/A head ('vector', the default) or "
                "as the wrist readings ('axes'), as in gcode run");
  c->add_option("--tolerance", a->tolerance, "chordal tolerance in mm (default 0.01)");
  a->interpreter.add(*c, false);
  c->add_option("--out", a->out, "write the program to FILE instead of standard output");
  c->add_flag("--force", a->force, "overwrite an existing --out file");
  c->callback([a] { runCompensate(*a); });
}

}  // namespace pkm::cli
