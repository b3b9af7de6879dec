// Campaign step "hexapod-calibration" (seed 004): laser-tracker calibration of a hexapod, the
// calibrated kinematics loaded into the controller (LinuxCNC genhexkins setp block), and the
// TCP and positioning errors measured again (docs/campaign.md).
#include <fmt/format.h>

#include <cmath>

#include "campaign_steps.hpp"
#include "pkm/calibration/acceptance.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/hexapod_parameters.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_fit.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/calibration_files.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/tracker_files.hpp"
#include "pkm/kinematics/pose_rpy.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "pkm/simulation/random.hpp"

namespace pkm::workflow::campaign {

namespace sim = pkm::simulation;
namespace cal = pkm::calibration;

namespace {

std::vector<std::string> names(const Json& spec, const char* key, const std::string& fallback) {
  std::vector<std::string> out;
  if (!spec.contains(key)) return {fallback};
  for (const auto& v : spec[key]) out.push_back(v.get<std::string>());
  return out;
}

/// Target-position errors of tracker readings: world = frame · measured, nominal = command pose ·
/// smr offset; one |error| per reading, plus the nominal x and y of the target.
struct TcpErrors {
  std::vector<double> x, y, error;
  double rms = 0.0, max = 0.0;
};

TcpErrors tcpErrors(const sim::TrackerResult& r,
                    const sim::VirtualMachine& vm,
                    const geometry::RigidTransform& world_T_tracker) {
  TcpErrors e;
  double sum = 0.0;
  for (const sim::TrackerReading& reading : r.readings) {
    const Eigen::Vector3d nominal = vm.nominalPose(reading.command) * r.setup->smr_offset;
    const Eigen::Vector3d measured =
        world_T_tracker.linear() * Eigen::Vector3d(reading.measured.translation()) +
        world_T_tracker.translation();
    const double d = (measured - nominal).norm();
    e.x.push_back(nominal.x());
    e.y.push_back(nominal.y());
    e.error.push_back(d);
    sum += d * d;
    e.max = std::max(e.max, d);
  }
  e.rms = e.error.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(e.error.size()));
  return e;
}

const sim::TrackerResult& tracker(const std::vector<sim::TrackerResult>& all,
                                  const std::string& name,
                                  const std::string& source) {
  for (const sim::TrackerResult& r : all)
    if (r.setup->name == name) return r;
  throw IoError(fmt::format("{}: the scenario has no tracker measurement '{}'", source, name));
}

std::string noiseText(const sim::TrackerNoise& n) {
  return fmt::format("tracker {:g} µm + {:g} ppm, {:g} µrad",
                     n.range_sigma * 1e3,
                     n.range_ppm,
                     n.angle_sigma * 1e6);
}

/// Fiducial nests on the table (world frame, mm) read by the tracker with its noise, and the
/// rigid fit world_T_tracker of the readings; the readings go into
/// measured-before/tracker-registration.csv.
geometry::RigidTransform registerTracker(const StepContext& ctx,
                                         StepOutcome& out,
                                         const io::Scenario& scenario,
                                         std::uint64_t seed,
                                         const std::vector<sim::TrackerResult>& trackers) {
  if (trackers.empty())
    throw IoError(fmt::format("{}: the scenario has no tracker measurement", ctx.source));
  const sim::TrackerSetup& setup = *trackers.front().setup;
  const std::vector<Eigen::Vector3d> nests = {
      {-500, -500, 0}, {500, -500, 0}, {500, 500, 0}, {-500, 500, 0}, {0, 0, 0}, {0, -700, 0}};
  sim::RandomStream rng(seed, "tracker-registration");
  std::vector<Eigen::Vector3d> measured;
  std::string csv = fmt::format(
      "# format: pkm.tracker-registration/1\n# scenario: {}\n# seed: {}\n# instrument: laser "
      "tracker (simulated), {}\nnest,x_table,y_table,z_table,x,y,z\n",
      scenario.campaign.name,
      seed,
      noiseText(setup.noise));
  for (std::size_t k = 0; k < nests.size(); ++k) {
    const Eigen::Vector3d truth = setup.world_T_tracker.inverse() * nests[k];
    measured.push_back(setup.noise.point(truth, rng));
    csv += fmt::format("{},{},{},{},{:.6f},{:.6f},{:.6f}\n",
                       k + 1,
                       nests[k].x(),
                       nests[k].y(),
                       nests[k].z(),
                       measured.back().x(),
                       measured.back().y(),
                       measured.back().z());
  }
  ctx.write(out, "measured-before/tracker-registration.csv", csv);
  return geometry::fitRigidTransform(nests, measured);
}

}  // namespace

StepOutcome runHexapodCalibrationStep(const StepContext& ctx) {
  if (ctx.spec.contains("data")) return runHexapodCalibrationFiles(ctx);
  std::uint64_t seed = 0;
  io::Scenario scenario = stepScenario(ctx, seed);
  const auto vm = scenarioMachine<sim::HexapodVirtualMachine>(ctx, scenario, "hexapod");
  const std::vector<std::string> fit = names(ctx.spec, "fit", "tracker-pose");
  const std::vector<std::string> holdout = names(ctx.spec, "holdout", "tracker-holdout");
  const std::string linear = ctx.spec.value("positioning", std::string("linear-x"));
  scenario.campaign.constrained.clear();  // the dial-gauge calibration is `pkm calibrate hexapod`

  StepOutcome out;
  out.id = ctx.spec.value("id", std::string("seed004"));
  out.title = "Hexapod calibration by laser tracker (seed 004)";
  out.record.machine = vm->nominal().name;
  out.record.machine_type = "hexapod";
  out.record.name = fmt::format("campaign {}", out.id);
  out.record.source = scenario.source;

  // 1. Measure on the uncompensated machine and keep the files.
  ctx.progress("measure: tracker and laser on the uncompensated machine");
  const LineData lines_before{sim::runCampaign(scenario.campaign, seed)};
  const std::vector<sim::TrackerResult> before = sim::runLaserTrackers(scenario.campaign, seed);
  writeLineFiles(ctx, out, "measured-before", scenario, seed, lines_before);
  for (const sim::TrackerResult& r : before)
    ctx.write(out,
              fmt::format("measured-before/{}.csv", r.setup->name),
              io::trackerCsv(
                  io::trackerMetadata(scenario.campaign.name, seed, *r.setup, r.readings.size()),
                  r.setup->mode,
                  r.readings));

  // 2. Calibrate from the files, as `pkm calibrate hexapod` does.
  ctx.progress(fmt::format("calibrate: 42 parameters from {}", fmt::join(fit, ", ")));
  io::CalibrationInput input;
  for (const std::string& f : fit)
    io::addCalibrationFile((ctx.dir / "measured-before" / (f + ".csv")).string(), input);
  kinematics::HexapodModel model = vm->nominal();
  model.tool_offset += input.target_offset.value_or(Eigen::Vector3d::Zero());
  // The tracker is registered to the table by fiducial nests at known table positions, so the
  // readings are in the machine frame and the base's rigid placement is identifiable too (without
  // it the six rigid-motion directions are not, and the machine moves accurately but in a frame
  // rotated against the table: docs/calibration.md "Frames").
  const geometry::RigidTransform world_T_tracker =
      registerTracker(ctx, out, scenario, seed, before);
  for (cal::PoseObservation& o : input.data.poses) {
    o.pose =
        kinematics::poseRpyFromTransform(world_T_tracker * kinematics::toRigidTransform(o.pose));
  }
  for (cal::PointObservation& o : input.data.points)
    o.point = world_T_tracker.linear() * o.point + world_T_tracker.translation();
  const cal::HexapodCalibrationSummary s = cal::calibrateHexapod(model, input.data, {});
  if (!cal::explainsData(s.after.rms, model.characteristicLength()))
    throw InvalidArgument(
        fmt::format("{}: the calibration does not explain the data (residual RMS {:.4g} mm)",
                    ctx.source,
                    s.after.rms));
  kinematics::HexapodModel calibrated = cal::withHexapodParameters(vm->nominal(), s.parameters);
  calibrated.name = vm->nominal().name + "-calibrated";

  // 3. Compensation: the calibrated kinematics in the controller.
  io::HexapodMachine machine;
  machine.model = calibrated;
  ctx.writeCompensation(
      out, "linuxcnc-hal", "compensation/kinematics.hal", io::writeLinuxcncSetp(machine));
  vm->setControllerModel(calibrated);

  // 4. Measure again.
  ctx.progress("re-measure: the same poses with the calibrated kinematics in the controller");
  const LineData lines_after{sim::runCampaign(scenario.campaign, remeasureSeed(seed))};
  const std::vector<sim::TrackerResult> after =
      sim::runLaserTrackers(scenario.campaign, remeasureSeed(seed));
  writeLineFiles(ctx, out, "measured-after", scenario, remeasureSeed(seed), lines_after);
  for (const sim::TrackerResult& r : after)
    ctx.write(out,
              fmt::format("measured-after/{}.csv", r.setup->name),
              io::trackerCsv(
                  io::trackerMetadata(
                      scenario.campaign.name, remeasureSeed(seed), *r.setup, r.readings.size()),
                  r.setup->mode,
                  r.readings));

  // 5. Figures.
  const sim::TrackerResult& hb = tracker(before, holdout.front(), ctx.source);
  const sim::TrackerResult& ha = tracker(after, holdout.front(), ctx.source);
  const TcpErrors eb = tcpErrors(hb, *vm, world_T_tracker);
  const TcpErrors ea = tcpErrors(ha, *vm, world_T_tracker);
  const std::string noise = noiseText(hb.setup->noise);
  out.rows.push_back({fmt::format("TCP error, {} held-out poses, max", hb.readings.size()),
                      "mm",
                      eb.max,
                      ea.max,
                      0.05,
                      "12 -> < 0.5 mm",
                      noise});
  out.rows.push_back(
      {"TCP error, held-out poses, RMS", "mm", eb.rms, ea.rms, std::nullopt, "", noise});
  const metrology::Iso230_2Result pb = iso230_2(lines_before.runs(linear, ctx.source));
  const metrology::Iso230_2Result pa = iso230_2(lines_after.runs(linear, ctx.source));
  const sim::LineSetup& ls = lines_before.setup(linear, ctx.source);
  const double travel = ls.cycle.last - ls.cycle.first;
  out.rows.push_back(
      {fmt::format("{} positioning (ISO 230-2 M over {:g} mm)", linear, travel),
       "mm",
       pb.M,
       pa.M,
       std::nullopt,
       "12 -> < 0.5 mm (540 mm along x)",
       fmt::format("laser {:g} µm + {:g} ppm", ls.noise.sigma * 1e3, ls.noise.sigma_ppm)});
  out.record.results.push_back({"calibration.residual_rms", "after", s.after.rms, "mm"});

  // 6. Report section.
  Json sec =
      section(out.id,
              out.title,
              {fmt::format("Scenario {} (seed {}): {}",
                           scenario.campaign.name,
                           seed,
                           scenario.campaign.description),
               fmt::format("Calibration: {} pose observations, {} of {} parameter combinations "
                           "identifiable (condition number {:.3g}), {} LM iterations; residual "
                           "RMS {:.4g} -> {:.4g} mm. The calibrated kinematics are written as a "
                           "LinuxCNC genhexkins setp block (compensation/kinematics.hal) and "
                           "loaded into the virtual machine's controller; the held-out poses "
                           "and the laser line are then measured again.",
                           input.data.poses.size(),
                           s.identifiability.rank,
                           s.identifiability.parameters,
                           s.identifiability.condition_number,
                           s.iterations,
                           s.before.rms,
                           s.after.rms),
               "The tracker is registered to the table by six fiducial nests "
               "(measured-before/tracker-registration.csv), so its readings are in the "
               "machine frame and all 42 parameters, the base placement included, are "
               "identifiable. TCP error: a held-out tracker reading in the machine frame "
               "minus the commanded target position."});
  // TCP error maps: target positions in the xy plane, coloured by |error| (mm).
  auto map = [&](const std::string& id,
                 const std::string& title,
                 const std::string& label,
                 const TcpErrors& e) {
    Json p = plot(out.id + id, title, "scatter", "x (mm)", "y (mm)");
    addSeries(p, label, e.x, e.y);
    Json v = Json::array();
    for (double d : e.error) v.push_back(cell(d, 5));
    p["series"][0]["value"] = std::move(v);
    return p;
  };
  const Json p1 = map("-tcp-before",
                      "TCP error map before calibration: |error| (mm) at the held-out poses",
                      "|error| before (mm)",
                      eb);
  const Json p2 = map("-tcp-after",
                      "TCP error map after calibration: |error| (mm) at the held-out poses",
                      "|error| after (mm)",
                      ea);
  std::vector<double> tb, mb, ta, ma;
  meanReadings(lines_before.runs(linear, ctx.source), tb, mb);
  meanReadings(lines_after.runs(linear, ctx.source), ta, ma);
  for (std::size_t i = 0; i < tb.size(); ++i) mb[i] -= tb[i];
  for (std::size_t i = 0; i < ta.size(); ++i) ma[i] -= ta[i];
  Json p3 = plot(out.id + "-positioning",
                 fmt::format("Positioning error along {} (mean of runs)", linear),
                 "line",
                 "target (mm)",
                 "deviation (mm)");
  addSeries(p3, "before", tb, mb);
  addSeries(p3, "after", ta, ma);
  sec["plots"] = Json::array({p1, p2, p3});

  Json id = table("Identifiability and uncertainty", {"quantity", "value"});
  id["rows"].push_back({"free parameters", s.identifiability.parameters});
  id["rows"].push_back({"identifiable combinations (rank)", s.identifiability.rank});
  id["rows"].push_back(
      {"condition number (scaled Jacobian)", cell(s.identifiability.condition_number)});
  id["rows"].push_back({"residual σ (mm)", cell(s.sigma)});
  id["rows"].push_back({"largest parameter σ (mm)", cell(s.standard_deviation.maxCoeff())});
  id["rows"].push_back(
      {"median parameter σ (mm)", [&] {
         std::vector<double> v(s.standard_deviation.data(),
                               s.standard_deviation.data() + s.standard_deviation.size());
         std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
         return cell(v[v.size() / 2]);
       }()});
  const cal::HexapodParameterVector truth = cal::hexapodParameters(vm->truth());
  const cal::HexapodParameterVector nominal = cal::hexapodParameters(vm->nominal());
  Json par = table("Parameters: nominal, estimated, true (simulation), σ (mm)",
                   {"parameter", "nominal", "estimate", "truth", "σ"});
  for (int i = 0; i < static_cast<int>(nominal.size()); ++i)
    par["rows"].push_back({cal::hexapodParameterName(i),
                           cell(nominal[i], 7),
                           cell(s.parameters[i], 7),
                           cell(truth[i], 7),
                           cell(s.standard_deviation[i], 3)});
  sec["tables"] = Json::array({id, par});
  out.section = std::move(sec);
  return out;
}

}  // namespace pkm::workflow::campaign
