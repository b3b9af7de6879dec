// Campaign step "hexapod-calibration" on measured files (no virtual machine): calibration from the
// "fit" files, the held-out files predicted by the nominal and by the calibrated model, and the
// calibrated kinematics written for the controller. Measuring again is the user's next campaign
// (docs/campaign.md, "Measured data").
#include <fmt/format.h>

#include <cmath>

#include "campaign_hexapod_detail.hpp"
#include "campaign_steps.hpp"
#include "pkm/calibration/acceptance.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/hexapod_parameters.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/calibration_files.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/machine_loader.hpp"
#include "workflow/calibration_uncertainty.hpp"

namespace pkm::workflow::campaign {

namespace cal = pkm::calibration;

namespace {

std::vector<std::string> files(const StepContext& ctx, const Json& data, const char* key) {
  std::vector<std::string> out;
  if (!data.contains(key)) return out;
  if (!data[key].is_array())
    throw IoError(
        fmt::format("{}: \"data\".\"{}\" must be an array of file names", ctx.source, key));
  for (const Json& f : data[key]) {
    if (!f.is_string())
      throw IoError(fmt::format("{}: \"data\".\"{}\" must hold file names", ctx.source, key));
    std::filesystem::path p(f.get<std::string>());
    if (p.is_relative()) p = ctx.base_dir / p;
    if (!std::filesystem::is_regular_file(p))
      throw IoError(fmt::format("{}: {}: no such file", ctx.source, p.string()));
    out.push_back(p.string());
  }
  return out;
}

/// The 42-parameter calibration of `input` from `machine` (the tool offset moved to the target,
/// the measurement frame estimated when the readings are in the tracker's frame); throws
/// pkm::InvalidArgument when the residual does not explain the data.
cal::HexapodCalibrationSummary calibrate(const StepContext& ctx,
                                         const io::HexapodMachine& machine,
                                         io::CalibrationInput& input) {
  kinematics::HexapodModel model = machine.model;
  model.tool_offset += input.target_offset.value_or(Eigen::Vector3d::Zero());
  if (input.tracker_frame)
    input.data.measurement_frame = cal::initialMeasurementFrame(model, input.data);
  cal::HexapodCalibrationSummary s = cal::calibrateHexapod(model, input.data, {});
  if (!cal::explainsData(s.after.rms, model.characteristicLength()))
    throw InvalidArgument(
        fmt::format("{}: the calibration does not explain the data (residual RMS {:.4g})",
                    ctx.source,
                    s.after.rms));
  return s;
}

/// Writes the calibrated kinematics as a LinuxCNC genhexkins setp block.
void writeCalibrated(const StepContext& ctx,
                     StepOutcome& out,
                     const io::HexapodMachine& machine,
                     const cal::HexapodCalibrationSummary& s) {
  io::HexapodMachine result = machine;
  result.model = cal::withHexapodParameters(machine.model, s.parameters);
  result.model.name = machine.model.name + "-calibrated";
  result.notices.clear();
  const std::string hal = io::writeLinuxcncSetp(result);
  ctx.writeCompensation(out, "linuxcnc-hal", "compensation/kinematics.hal", hal);
}

/// The held-out rows: the residuals of `held` predicted by the nominal and by the calibrated
/// model (none when `held` has no observation).
void addHeldOutRows(StepOutcome& out,
                    const io::HexapodMachine& machine,
                    const io::CalibrationInput& input,
                    const io::CalibrationInput& held,
                    const cal::HexapodCalibrationSummary& s,
                    const std::string& unit) {
  if (held.data.poses.empty() && held.data.points.empty() && held.data.constrained.empty()) return;
  kinematics::HexapodModel held_model = machine.model;
  held_model.tool_offset +=
      held.target_offset.value_or(input.target_offset.value_or(Eigen::Vector3d::Zero()));
  const auto frame0 = input.tracker_frame
                          ? std::optional(cal::initialMeasurementFrame(held_model, held.data))
                          : std::nullopt;
  const cal::ResidualStatistics b = cal::residualStatistics(held_model, held.data, frame0);
  kinematics::HexapodModel held_fitted = cal::withHexapodParameters(held_model, s.parameters);
  const cal::ResidualStatistics a =
      cal::residualStatistics(held_fitted, held.data, s.measurement_frame);
  out.rows.push_back({"held-out residual RMS (predicted by the model)",
                      unit,
                      b.rms,
                      a.rms,
                      std::nullopt,
                      "",
                      "as measured"});
  out.rows.push_back(
      {"held-out residual max", unit, b.max, a.max, std::nullopt, "", "as measured"});
}

/// The report section: the data, the identifiability and the parameter table.
Json filesSection(const StepOutcome& out,
                  std::size_t fitted,
                  std::size_t held_out,
                  const io::HexapodMachine& machine,
                  const cal::HexapodCalibrationSummary& s) {
  Json sec =
      section(out.id,
              out.title,
              {fmt::format("Measured data: {} fitted and {} held-out files. The calibrated "
                           "kinematics are in compensation/kinematics.hal; 'after' is what the "
                           "calibrated model predicts for the held-out files, not a new "
                           "measurement: measure again after loading it (the next campaign).",
                           fitted,
                           held_out),
               fmt::format("Identifiability: {} of {} combinations (condition number {:.3g}); "
                           "{} LM iterations.",
                           s.identifiability.rank,
                           s.identifiability.parameters,
                           s.identifiability.condition_number,
                           s.iterations)});
  Json par = table("Parameters: nominal, estimated, σ", {"parameter", "nominal", "estimate", "σ"});
  const cal::HexapodParameterVector nominal = cal::hexapodParameters(machine.model);
  for (int i = 0; i < static_cast<int>(nominal.size()); ++i)
    par["rows"].push_back({cal::hexapodParameterName(i),
                           cell(nominal[i], 7),
                           cell(s.parameters[i], 7),
                           cell(s.standard_deviation[i], 3)});
  sec["tables"].push_back(par);
  return sec;
}

}  // namespace

StepOutcome runHexapodCalibrationFiles(const StepContext& ctx) {
  const Json& data = ctx.spec["data"];
  if (!data.is_object())
    throw IoError(fmt::format(
        "{}: \"data\" must be an object with \"fit\" and \"holdout\" file lists", ctx.source));
  const std::vector<std::string> fit = files(ctx, data, "fit");
  const std::vector<std::string> holdout = files(ctx, data, "holdout");
  if (fit.empty()) throw IoError(fmt::format("{}: \"data\".\"fit\" names no file", ctx.source));
  const io::HexapodMachine machine =
      io::loadHexapodMachine(ctx.spec.value("machine", std::string("default")));
  StepOutcome out;
  out.id = ctx.spec.value("id", std::string("hexapod"));
  out.title = fmt::format("Hexapod calibration of {} from measured files", machine.model.name);
  out.record.machine = machine.model.name;
  out.record.machine_type = "hexapod";
  out.record.source = fmt::format("{} files", fit.size() + holdout.size());

  ctx.progress(fmt::format("calibrate: 42 parameters from {} files", fit.size()));
  io::CalibrationInput input, held;
  for (const std::string& f : fit) io::addCalibrationFile(f, input);
  for (const std::string& f : holdout) io::addCalibrationFile(f, held);
  for (const std::string& f : fit)
    out.record.measurements.push_back({std::filesystem::path(f).stem().string(), "fit", f, 0});
  for (const std::string& f : holdout)
    out.record.measurements.push_back({std::filesystem::path(f).stem().string(), "holdout", f, 0});
  const cal::HexapodCalibrationSummary s = calibrate(ctx, machine, input);
  writeCalibrated(ctx, out, machine, s);

  const std::string unit(toString(machine.model.unit));
  out.rows.push_back({"residual RMS of the fitted files",
                      unit,
                      s.before.rms,
                      s.after.rms,
                      std::nullopt,
                      "",
                      "as measured"});
  addHeldOutRows(out, machine, input, held, s, unit);
  out.section = filesSection(out, fit.size(), holdout.size(), machine, s);
  // The budgets (the campaign's instruments) and the predicted TCP U at the held-out
  // configurations.
  workflow::detail::CalibrationUncertaintyRequest request;
  request.sources = ctx.sources;
  kinematics::HexapodModel model = machine.model;
  model.tool_offset += input.target_offset.value_or(Eigen::Vector3d::Zero());
  const bool has_held = !held.data.poses.empty() || !held.data.points.empty();
  const io::HexapodCalibrationReport::Uncertainty u =
      workflow::detail::hexapodCalibrationUncertainty(
          model,
          input.data,
          s,
          {},
          request,
          has_held
              ? workflow::detail::checkPoses(
                    cal::withHexapodParameters(model, s.parameters), held.data, s.measurement_frame)
              : std::vector<kinematics::PoseRpy>{},
          "held-out");
  out.section["tables"].push_back(detail::budgetTable(u));
  return out;
}

}  // namespace pkm::workflow::campaign
