// `pkm gcode compensate --machine CAL.json PROGRAM`: the program pre-distorted for a controller
// that keeps the nominal kinematics (docs/gcode.md "gcode compensate").
#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "cli_common.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/cnc/program_compensation.hpp"
#include "pkm/core/error.hpp"
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
};

/// Suffix `pkm calibrate hexapod` appends to the nominal machine's name.
constexpr std::string_view kCalibratedSuffix = "-calibrated";

/// The nominal machine: --nominal, or the built-in hexapod whose name is the calibrated
/// machine's name without "-calibrated".
io::HexapodMachine nominalFor(const CompensateArgs& a, const io::HexapodMachine& cal) {
  if (!a.nominal.empty()) return io::loadHexapodMachine(a.nominal);
  const std::string& name = cal.model.name;
  if (name.size() > kCalibratedSuffix.size() && name.ends_with(kCalibratedSuffix)) {
    const std::string base = name.substr(0, name.size() - kCalibratedSuffix.size());
    for (const auto& n : io::builtinMachineNames("hexapod")) {
      io::HexapodMachine m = io::builtinMachine(n);
      if (m.model.name == base) return m;
    }
  }
  throw InvalidArgument(fmt::format(
      "{}: cannot tell the nominal machine of '{}' (no built-in hexapod named as it without "
      "'-calibrated'); pass --nominal MACHINE",
      a.machine,
      name));
}

void runCompensate(const CompensateArgs& a) {
  PKM_CHECK(a.tolerance > 0.0 && std::isfinite(a.tolerance), "--tolerance must be > 0");
  if (!a.out.empty() && !a.force && std::filesystem::exists(a.out))
    throw IoError(fmt::format("{} exists; pass --force to overwrite it", a.out));
  const io::HexapodMachine cal = io::loadHexapodMachine(a.machine);
  const io::HexapodMachine nominal = nominalFor(a, cal);
  if (nominal.model.unit != cal.model.unit)
    throw InvalidArgument("the nominal and calibrated machines use different length units");
  cnc::ProgramCompensationOptions options;
  options.interpolation = cnc::jointSpaceInterpolation(cal.model, a.tolerance);
  options.predistortion.fk = nominal.fk;
  const std::string text = io::readTextFile(a.program);
  const cnc::ProgramCompensation r =
      cnc::compensateProgram(text, a.program, nominal.model, cal.model, options);
  if (a.out.empty()) {
    std::fwrite(r.text.data(), 1, r.text.size(), stdout);
    std::fflush(stdout);
  } else {
    const std::string tmp = a.out + ".tmp";
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (f == nullptr) throw IoError(fmt::format("{}: cannot write", a.out));
    std::fwrite(r.text.data(), 1, r.text.size(), f);
    if (std::fclose(f) != 0) throw IoError(fmt::format("{}: write failed", a.out));
    std::filesystem::rename(tmp, a.out);
  }
  fmt::print(stderr,
             "pkm: note: nominal {} -> calibrated {}: {} motion lines rewritten, {} segment lines "
             "added (tolerance {} mm, max step {:.4g} mm), largest correction {:.4g} mm\n",
             nominal.model.name,
             cal.model.name,
             r.motion_lines,
             r.added_lines,
             a.tolerance,
             options.interpolation.max_step,
             r.max_correction);
}

}  // namespace

void addGcodeCompensateCommand(CLI::App& gcode) {
  auto a = std::make_shared<CompensateArgs>();
  CLI::App* c = gcode.add_subcommand(
      "compensate",
      "pre-distort PROGRAM for a controller with nominal kinematics (machine: the output of "
      "`pkm calibrate hexapod --out`)");
  c->add_option("program", a->program, "G-code file (.ngc)")->required();
  c->add_option("--machine", a->machine, "calibrated hexapod machine JSON")->required();
  c->add_option("--nominal",
                a->nominal,
                "the controller's nominal machine (default: the built-in one the calibrated "
                "machine's name refers to)");
  c->add_option("--tolerance", a->tolerance, "chordal tolerance in mm (default 0.01)");
  c->add_option("--out", a->out, "write the program to FILE instead of standard output");
  c->add_flag("--force", a->force, "overwrite an existing --out file");
  c->callback([a] { runCompensate(*a); });
}

}  // namespace pkm::cli
