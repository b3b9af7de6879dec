// `pkm gcode compensate --machine CAL.json` as a workflow (workflow/gcode_compensate.hpp): the
// program pre-distorted for a controller that keeps the nominal kinematics of a hexapod or an
// Exechon.
#include "pkm/workflow/gcode_compensate.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string_view>

#include "gcode_compensate_detail.hpp"
#include "pkm/cnc/exechon_path.hpp"
#include "pkm/cnc/exechon_program_compensation.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/machine_loader.hpp"

namespace pkm::workflow {

namespace {

/// Suffix `pkm calibrate hexapod` and `pkm calibrate exechon` append to the nominal machine's
/// name.
constexpr std::string_view kCalibratedSuffix = "-calibrated";

/// The nominal machine of calibrated machine `cal`: request.nominal (loaded by `load`), or the
/// built-in machine of `type` ("hexapod" or "exechon", loaded by `builtin`) whose name is cal's
/// without "-calibrated".
template <class Machine, class Load, class Builtin>
Machine nominalFor(const GcodeCompensateRequest& request,
                   const Machine& cal,
                   const char* type,
                   Load load,
                   Builtin builtin) {
  if (!request.nominal.empty()) return load(request.nominal);
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
                  request.machineName(),
                  name,
                  type));
}

/// The note after a pre-distortion: what was compensated (`what`), the line counts, the
/// interpolation settings (mm) and the largest correction.
std::string predistortionNote(const std::string& what,
                              const cnc::ProgramCompensation& r,
                              double tolerance_mm,
                              double max_step_mm,
                              LengthUnit unit) {
  const double per = 1.0 / millimetresPer(unit);  // the note speaks the machine's unit
  const std::string u(toString(unit));
  return fmt::format(
      "{}: {} motion lines rewritten, {} lines added (segments, dwells), {} G92/G10 L20 lines "
      "shifted (tolerance {:.4g} {}, max step {:.4g} {}), largest correction {:.4g} {}{}",
      what,
      r.motion_lines,
      r.added_lines,
      r.offset_lines,
      tolerance_mm * per,
      u,
      max_step_mm * per,
      u,
      r.max_correction * per,
      u,
      detail::flattenedNote(r));
}

/// The request's tolerance in mm for a machine in `unit`.
double toleranceMm(const GcodeCompensateRequest& request, LengthUnit unit) {
  return request.tolerance ? *request.tolerance * millimetresPer(unit) : kDefaultToleranceMm;
}

GcodeCompensateResult compensateExechon(const GcodeCompensateRequest& request) {
  const io::ExechonMachine cal =
      request.exechon ? *request.exechon : io::loadExechonMachine(request.machine);
  if (!request.nominal.empty() && io::machineTypeOf(request.nominal) != "exechon")
    throw InvalidArgument(fmt::format("--nominal {}: not an Exechon machine, but {} is one",
                                      request.nominal,
                                      request.machineName()));
  const io::ExechonMachine nominal =
      nominalFor(request, cal, "exechon", &io::loadExechonMachine, &io::loadExechonMachine);
  cnc::ExechonProgramCompensationOptions options;
  const std::string orientation = request.orientation.value_or("vector");
  options.orientation = cnc::parseExechonOrientation(orientation);
  const double tolerance_mm = toleranceMm(request, cal.model.unit);
  options.interpolation = cnc::exechonInterpolation(cal.model, tolerance_mm);
  options.interpolation.max_points = request.max_points;
  options.fk = nominal.fk;
  options.interpreter = request.interpreter.options();
  GcodeCompensateResult result;
  result.compensation = cnc::compensateExechonProgram(
      request.program.text, request.program.name, nominal.model, cal.model, options);
  detail::writeCompensated(request, result);
  result.note =
      predistortionNote(fmt::format("nominal {} -> calibrated {} (Exechon, --orientation {})",
                                    nominal.model.name,
                                    cal.model.name,
                                    orientation),
                        result.compensation,
                        tolerance_mm,
                        options.interpolation.max_step,
                        cal.model.unit);
  return result;
}

/// The interpreter settings of a hexapod program: the request's, with the start-up code of the
/// LinuxCNC configuration (request.ini, else a `.hal` nominal machine's INI). Throws
/// pkm::InvalidArgument when the INI's LINEAR_UNITS differ from the calibrated machine's.
GcodeInterpreterSettings hexapodSettings(const GcodeCompensateRequest& request,
                                         const io::HexapodMachine& cal,
                                         const io::HexapodMachine& nominal) {
  GcodeInterpreterSettings settings = request.interpreter;
  if (request.ini.empty()) {
    takeStartupCode(nominal, settings);
    return settings;
  }
  io::HexapodMachine under_ini = cal;  // what the INI says, applied to a copy
  io::applyLinuxcncIni(request.ini, under_ini);
  if (under_ini.model.unit != cal.model.unit)
    throw InvalidArgument(fmt::format("{}: [TRAJ] LINEAR_UNITS is {} but {} is in {}",
                                      request.ini,
                                      toString(under_ini.model.unit),
                                      request.machineName(),
                                      toString(cal.model.unit)));
  takeStartupCode(under_ini, settings);
  if (settings.ini.empty()) settings.ini = request.ini;  // its [RS274NGC] section too
  return settings;
}

GcodeCompensateResult compensateHexapod(const GcodeCompensateRequest& request) {
  const io::HexapodMachine cal =
      request.hexapod ? *request.hexapod : io::loadHexapodMachine(request.machine);
  io::requireRegisteredFrame(cal, "pkm gcode compensate");  // its output runs on the controller
  io::HalReadOptions hal;
  if (!request.ini.empty()) hal.ini_path = request.ini;
  const io::HexapodMachine nominal = nominalFor(
      request,
      cal,
      "hexapod",
      [&hal](const std::string& spec) { return io::loadHexapodMachine(spec, hal); },
      &io::builtinMachine);
  if (nominal.model.unit != cal.model.unit)
    throw InvalidArgument("the nominal and calibrated machines use different length units");
  cnc::ProgramCompensationOptions options;
  const double tolerance_mm = toleranceMm(request, cal.model.unit);
  options.interpolation = cnc::jointSpaceInterpolation(cal.model, tolerance_mm);
  options.interpolation.max_points = request.max_points;
  options.predistortion.fk = nominal.fk;
  const GcodeInterpreterSettings settings = hexapodSettings(request, cal, nominal);
  options.interpreter = settings.options();
  GcodeCompensateResult result;
  result.compensation = cnc::compensateProgram(
      request.program.text, request.program.name, nominal.model, cal.model, options);
  detail::writeCompensated(request, result);
  result.note =
      predistortionNote(fmt::format("nominal {} -> calibrated {}{}",
                                    nominal.model.name,
                                    cal.model.name,
                                    settings.startup_code.empty()
                                        ? std::string()
                                        : fmt::format(" (after RS274NGC_STARTUP_CODE \"{}\" of {})",
                                                      settings.startup_code,
                                                      settings.startup_source)),
                        result.compensation,
                        tolerance_mm,
                        options.interpolation.max_step,
                        cal.model.unit);
  return result;
}

}  // namespace

void GcodeCompensateRequest::validate() const {
  PKM_CHECK(!tolerance || (*tolerance > 0.0 && std::isfinite(*tolerance)),
            "--tolerance must be > 0");
  PKM_CHECK(max_points > 0, "--max-points must be > 0");
  if (!out.empty()) io::checkOverwrite(out, force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
  const int machines = int{!machine.empty()} + int{hexapod != nullptr} + int{exechon != nullptr};
  PKM_CHECK(machines <= 1, "give one calibrated machine: a name or file, or a loaded one");
  if (hybrid_frame.empty() == (machines == 0))
    throw InvalidArgument(
        "give either --machine CAL.json (hexapod or Exechon) or --hybrid-frame FILE --x2 POS");
  if (!hybrid_frame.empty()) {
    if (!x2) throw InvalidArgument("--hybrid-frame needs --x2 POS (the X2 position, mm)");
    if (!ini.empty()) throw InvalidArgument("--ini applies to hexapod machines only");
    return;
  }
  const bool is_exechon = onExechon();
  if (orientation && !is_exechon)
    throw InvalidArgument(
        fmt::format("--orientation is for Exechon machines; {} is a hexapod", machineName()));
  if (!ini.empty() && is_exechon)
    throw InvalidArgument(
        fmt::format("--ini applies to hexapod machines only; {} is an Exechon", machineName()));
}

std::string GcodeCompensateRequest::machineName() const {
  if (hexapod) return hexapod->model.name;
  if (exechon) return exechon->model.name;
  return machine;
}

bool GcodeCompensateRequest::onExechon() const {
  if (hexapod || exechon) return exechon != nullptr;
  return io::machineTypeOf(machine) == "exechon";
}

GcodeCompensateResult compensateGcode(const GcodeCompensateRequest& request) {
  request.validate();
  if (!request.hybrid_frame.empty()) return detail::compensateHybridGcode(request);
  if (request.onExechon()) return compensateExechon(request);
  return compensateHexapod(request);
}

}  // namespace pkm::workflow
