// `pkm calibrate hexapod` as a workflow (workflow/calibrate_hexapod.hpp).
#include "pkm/workflow/calibrate_hexapod.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "calibration_common.hpp"
#include "calibration_uncertainty.hpp"
#include "frame_registration.hpp"
#include "pkm/calibration/acceptance.hpp"
#include "pkm/calibration/frame_registration.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/holdout.hpp"
#include "pkm/calibration/uncertainty.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/parallel.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/calibration_files.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/simulation/hexapod_workspace.hpp"
#include "pkm/simulation/random.hpp"
#include "pkm/workflow/calibration_record.hpp"

namespace pkm::workflow {
namespace {

namespace cal = pkm::calibration;

/// The workspace poses of the TCP error map: 200 poses about home (±0.4 × the characteristic
/// length, ±10°), every limit respected, from a fixed random stream.
std::vector<kinematics::PoseRpy> workspacePoses(const kinematics::HexapodModel& model) {
  simulation::PoseBox box;
  const double reach = 0.4 * model.characteristicLength();
  for (int i = 0; i < 3; ++i) {
    box.lo(i) = model.home.position(i) - reach;
    box.hi(i) = model.home.position(i) + reach;
    box.lo(3 + i) = model.home.rpy(i) - degToRad(10.0);
    box.hi(3 + i) = model.home.rpy(i) + degToRad(10.0);
  }
  simulation::RandomStream rng(1, "calibration-workspace");
  std::vector<kinematics::PoseRpy> out;
  for (const Eigen::VectorXd& c : simulation::sampleHexapodWorkspace(model, box, 200, rng)) {
    kinematics::PoseRpy p;
    p.position = c.head<3>();
    p.rpy = c.tail<3>();
    out.push_back(p);
  }
  return out;
}

cal::HexapodCalibrationOptions fitOptions(const HexapodCalibrationRequest& r) {
  cal::HexapodCalibrationOptions options;
  for (const std::string& name : r.fix)
    options.free[static_cast<std::size_t>(cal::hexapodParameterIndex(name))] = false;
  if (r.loss == "huber") options.loss = cal::RobustLoss::kHuber;
  if (r.loss == "cauchy") options.loss = cal::RobustLoss::kCauchy;
  options.loss_scale = r.loss_scale;
  options.estimate_backlash = r.backlash;
  options.parameter_prior_sigma = r.prior_sigma;
  options.measurement_sigma = r.measurement_sigma;
  options.prior_uncertainty = r.prior_uncertainty;
  return options;
}

/// The five observations with the largest residuals under the fitted model, by source.
std::vector<io::ObservationResidual> worstObservations(const kinematics::HexapodModel& fitted,
                                                       const io::CalibrationInput& input,
                                                       const cal::HexapodCalibrationSummary& s) {
  const std::vector<double> norms =
      cal::observationResidualNorms(fitted, input.data, s.measurement_frame);
  std::vector<std::string> sources = input.pose_origin;
  sources.insert(sources.end(), input.point_origin.begin(), input.point_origin.end());
  for (std::size_t c = 0; c < input.data.constrained.size(); ++c)
    for (std::size_t k = 0; k < input.data.constrained[c].stations.size(); ++k)
      sources.push_back(fmt::format("constrained set {} station {}", c + 1, k + 1));
  sources.insert(sources.end(), input.distance_origin.begin(), input.distance_origin.end());
  std::vector<std::size_t> order(norms.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return norms[a] > norms[b];
  });
  std::vector<io::ObservationResidual> worst;
  for (std::size_t k = 0; k < std::min<std::size_t>(5, order.size()); ++k)
    worst.push_back({order[k] < sources.size() ? sources[order[k]] : "?", norms[order[k]]});
  return worst;
}

/// --monte-carlo: the calibration repeated under simulated noise.
io::HexapodCalibrationReport::MonteCarlo monteCarlo(const HexapodCalibrationRequest& r,
                                                    const kinematics::HexapodModel& model,
                                                    const io::CalibrationInput& input,
                                                    const cal::HexapodCalibrationSummary& s,
                                                    const std::vector<kinematics::PoseRpy>& ws,
                                                    const cal::HexapodCalibrationOptions& options,
                                                    const RunControl& control) {
  cal::MonteCarloOptions mc;
  mc.trials = r.monte_carlo;
  mc.threads = r.threads;
  mc.position_sigma = r.sigma_position > 0.0 ? r.sigma_position : s.sigma;
  mc.orientation_sigma = r.sigma_orientation_urad * 1e-6;
  mc.gauge_sigma = r.sigma_gauge > 0.0 ? r.sigma_gauge : s.sigma;
  mc.progress = detail::monteCarloProgress(control);
  const kinematics::HexapodModel estimate = cal::withHexapodParameters(model, s.parameters);
  io::HexapodCalibrationReport::MonteCarlo out;
  out.summary =
      cal::monteCarloHexapod(model, input.data, estimate, s.measurement_frame, ws, options, mc);
  out.sigma_position = mc.position_sigma;
  out.sigma_orientation = mc.orientation_sigma;
  out.sigma_gauge = mc.gauge_sigma;
  control.checkCancelled();
  return out;
}

/// The held-out check: the nominal model with the frame fitted through it, against the
/// calibrated model with the estimated frame; each with the held-out files' own target.
io::HexapodCalibrationReport::Holdout holdout(const io::HexapodMachine& machine,
                                              const io::HexapodMachine& result,
                                              const kinematics::HexapodModel& model,
                                              const io::CalibrationInput& input,
                                              const io::CalibrationInput& held,
                                              const cal::HexapodCalibrationSummary& s,
                                              bool use_frame,
                                              const Eigen::Vector3d& target) {
  io::HexapodCalibrationReport::Holdout h;
  h.target_offset = held.target_offset.value_or(target);
  kinematics::HexapodModel before_model = machine.model, after_model = result.model;
  before_model.tool_offset += h.target_offset;
  after_model.tool_offset += h.target_offset;
  std::optional<geometry::RigidTransform> f0;
  if (use_frame) f0 = cal::initialMeasurementFrame(model, input.data);
  h.before = cal::hexapodHoldoutErrors(before_model, f0, held.data);
  h.after = cal::hexapodHoldoutErrors(after_model, s.measurement_frame, held.data, s.backlash);
  return h;
}

/// The report's description of the fit: machine, data, counts, target, free parameters.
void describe(io::HexapodCalibrationReport& rep,
              const io::HexapodMachine& machine,
              const kinematics::HexapodModel& model,
              const io::CalibrationInput& input,
              const Eigen::Vector3d& target,
              const cal::HexapodCalibrationOptions& options) {
  rep.machine = machine.model.name;
  rep.unit = model.unit;
  rep.data_notes = input.notes;
  rep.poses = static_cast<int>(input.data.poses.size());
  rep.points = static_cast<int>(input.data.points.size());
  rep.constrained_sets = static_cast<int>(input.data.constrained.size());
  rep.distances = static_cast<int>(input.data.distances.size());
  rep.equations = static_cast<int>(input.data.equations());
  rep.target_offset = target;
  for (std::size_t k = 0; k < rep.free.size(); ++k) rep.free[k] = options.free[k];
}

/// Refuses (pkm::IoError) when one of the output files exists and not `force`.
void checkOutputs(const CalibrationOutputs& paths, bool force) {
  const io::Overwrite overwrite = force ? io::Overwrite::kAllow : io::Overwrite::kRefuse;
  for (const std::string& p : {paths.machine, paths.hal, paths.summary, paths.pkmhexkins})
    io::checkOverwrite(p, overwrite);
}

/// Reads the calibration files of `r` into `input` and its --holdout files into `held`; refuses
/// (pkm::InvalidArgument) readings in an unstated frame; notes the input's notes on `control`.
void readHexapodInputs(const HexapodCalibrationRequest& r,
                       io::CalibrationInput& input,
                       io::CalibrationInput& held,
                       const RunControl& control) {
  for (const io::NamedText& f : r.data) io::addCalibrationFile(f, input);
  for (const io::NamedText& f : r.holdout) io::addCalibrationFile(f, held);
  std::vector<std::string> frameless = input.frameless;
  frameless.insert(frameless.end(), held.frameless.begin(), held.frameless.end());
  detail::refuseUnstatedFrame(r.frame, frameless);
  control.note(input.notes);
}

/// --registration: the tracker's placement from the table's nests into rep.registration, and every
/// reading of `input` and `held` expressed in the world frame. Precondition: r.registration.
void registerTrackerReadings(const HexapodCalibrationRequest& r,
                             const kinematics::HexapodModel& model,
                             io::CalibrationInput& input,
                             io::CalibrationInput& held,
                             io::HexapodCalibrationReport& rep) {
  // The tracker's placement from the table's nests: every reading into the world frame.
  rep.registration = {r.registration->name,
                      detail::registerTrackerFrame(
                          *r.registration, model.unit, model.characteristicLength(), r.uncertainty),
                      0.0};
  cal::expressInWorld(input.data, rep.registration->fit.world_T_measurement);
  cal::expressInWorld(held.data, rep.registration->fit.world_T_measurement);
}

/// Refuses (pkm::InvalidArgument) a fit `s` that cannot explain the data: a residual RMS
/// implausible for `model`'s size (calibration::explainsData); nothing is written then.
void requireExplainedData(const cal::HexapodCalibrationSummary& s,
                          const kinematics::HexapodModel& model) {
  if (!cal::explainsData(s.after.rms, model.characteristicLength()))
    throw InvalidArgument(fmt::format(
        "calibration does not explain the data: residual RMS {:.4g} (max {:.4g}) after {} "
        "iterations ({}); check the units of the data against the machine's ({}), the --frame "
        "option, and outliers (--loss cauchy --loss-scale ...); nothing was written",
        s.after.rms,
        s.after.max,
        s.iterations,
        s.termination,
        toString(model.unit)));
}

/// The calibrated machine: `machine` with the estimated parameters of `s`, named
/// "<name>-calibrated", without the reader's notices; its world frame marked unregistered when
/// `unregistered`.
io::HexapodMachine calibratedHexapodMachine(const io::HexapodMachine& machine,
                                            const cal::HexapodCalibrationSummary& s,
                                            bool unregistered) {
  io::HexapodMachine calibrated = machine;
  calibrated.model = cal::withHexapodParameters(machine.model, s.parameters);
  calibrated.model.name = machine.model.name + "-calibrated";
  calibrated.notices.clear();
  calibrated.world_frame_unregistered = unregistered;
  return calibrated;
}

/// The TCP error over the `workspace` poses of machine.model (workspacePoses; rep.workspace_poses,
/// the registration's tcp_U): the nominal controller on the `calibrated` machine (rep.tcp_before,
/// what calibration removes), with --monte-carlo the spread the calibration itself leaves
/// (rep.monte_carlo), and the uncertainty budgets (rep.uncertainty). Reads rep.fit.
void reportWorkspaceErrors(const HexapodCalibrationRequest& r,
                           const std::vector<kinematics::PoseRpy>& workspace,
                           const io::HexapodMachine& machine,
                           const kinematics::HexapodModel& calibrated,
                           const kinematics::HexapodModel& model,
                           const io::CalibrationInput& input,
                           const io::CalibrationInput& held,
                           const cal::HexapodCalibrationOptions& options,
                           io::HexapodCalibrationReport& rep,
                           const RunControl& control) {
  const cal::HexapodCalibrationSummary& s = rep.fit;
  rep.workspace_poses = static_cast<int>(workspace.size());
  if (rep.registration)
    for (const kinematics::PoseRpy& p : workspace)
      rep.registration->tcp_U =
          std::max(rep.registration->tcp_U, 2.0 * rep.registration->fit.uncertaintyAt(p.position));
  rep.tcp_before = cal::tcpErrorOverWorkspace(machine.model, calibrated, workspace);
  if (r.monte_carlo > 0)
    rep.monte_carlo = monteCarlo(r, model, input, s, workspace, options, control);
  rep.uncertainty = detail::hexapodRequestUncertainty(
      r, model, input, held, s, workspace, options, rep.holdout, control);
}

/// The run's notices: the machine reader's, the data files', and the warning on an unregistered
/// world frame.
std::vector<std::string> hexapodResultNotices(const io::HexapodMachine& machine,
                                              const io::CalibrationInput& input,
                                              const io::HexapodCalibrationReport& rep) {
  std::vector<std::string> notices = machine.notices;
  notices.insert(notices.end(), input.notes.begin(), input.notes.end());
  if (rep.world_frame == "unregistered")
    notices.push_back(
        "the readings are in the tracker's own frame and no --registration was given: the "
        "calibrated geometry is right, but its world frame is where the fit put it (tilted and "
        "shifted against the table by the base's assembly errors); the machine file is marked "
        "\"world_frame\": \"unregistered\" and no LinuxCNC block is written (measure the "
        "table's fiducial nests and pass --registration FILE)");
  return notices;
}

/// Records the written calibration in the history database r.db (when given): the inputs, the
/// summary and the output files (the LinuxCNC block when one was written).
void recordHexapodRun(const HexapodCalibrationRequest& r,
                      const io::HexapodMachine& machine,
                      const kinematics::HexapodModel& model,
                      const HexapodCalibrationResult& result) {
  const io::HexapodCalibrationReport& rep = result.report;
  const CalibrationOutputs paths = calibrationOutputs(r.out);
  if (!r.db.empty())
    recordCalibration(
        r.db,
        {machine.model.name,
         "hexapod",
         "calibrate hexapod",
         detail::inputNames(r.data),
         result.summary_json,
         std::string(toString(model.unit)),
         rep.out_hal.empty()
             ? std::vector<std::pair<std::string, std::string>>{{"machine-json", paths.machine}}
             : std::vector<std::pair<std::string, std::string>>{{"linuxcnc-hal", paths.hal},
                                                                {"machine-json", paths.machine}}});
}

}  // namespace

void HexapodCalibrationRequest::validate() const {
  detail::checkCalibrationRequest(data, "calibration file", out, db, frame, loss, monte_carlo);
  if (!(prior_uncertainty >= 0.0 && std::isfinite(prior_uncertainty)))
    throw InvalidArgument(
        fmt::format("--prior-uncertainty must be a length >= 0, got {}", prior_uncertainty));
  if (prior_uncertainty > 0.0 && !(prior_sigma > 0.0))
    throw InvalidArgument(
        "--prior-uncertainty states the uncertainty of --prior-sigma's centre; "
        "give --prior-sigma too");
}

HexapodCalibrationResult calibrateHexapod(const HexapodCalibrationRequest& r,
                                          const RunControl& control) {
  r.validate();
  io::HalReadOptions hal;
  if (!r.ini.empty()) hal.ini_path = r.ini;
  const io::HexapodMachine machine = r.loaded ? *r.loaded : io::loadHexapodMachine(r.machine, hal);
  control.note(machine.notices);
  if (!r.out.empty()) checkOutputs(calibrationOutputs(r.out), r.force);
  // The workspace poses depend on the machine alone: sampled on a spare core during the fit.
  auto workspace = alongside([&machine] { return workspacePoses(machine.model); }, r.threads != 1);
  io::CalibrationInput input, held;
  readHexapodInputs(r, input, held, control);

  // The target (SMR or 6-DOF probe) is the TCP of the fitted model: tool offset += target offset.
  const Eigen::Vector3d target =
      r.target_offset.value_or(input.target_offset.value_or(Eigen::Vector3d::Zero()));
  kinematics::HexapodModel model = machine.model;
  model.tool_offset += target;
  const bool tracker_frame = r.frame == "tracker" || (r.frame == "auto" && input.tracker_frame);
  if (tracker_frame && input.data.poses.empty() && input.data.points.empty())
    throw InvalidArgument("--frame tracker needs tracker pose or point data");
  detail::refuseRegistrationOfWorldData(r.registration, tracker_frame);
  HexapodCalibrationResult result;
  io::HexapodCalibrationReport& rep = result.report;
  rep.world_frame = detail::worldFrameKind(tracker_frame, r.registration.has_value());
  if (r.registration) registerTrackerReadings(r, model, input, held, rep);
  const bool use_frame = tracker_frame && !r.registration;
  if (use_frame) input.data.measurement_frame = cal::initialMeasurementFrame(model, input.data);
  const cal::HexapodCalibrationOptions options = fitOptions(r);

  rep.fit = cal::calibrateHexapod(model, input.data, options);
  const cal::HexapodCalibrationSummary& s = rep.fit;
  // Plausibility: a model that cannot explain the data is not written.
  requireExplainedData(s, model);
  detail::refuseLargeChanges(s.large_changes, r.allow_large_changes, control);

  result.calibrated = calibratedHexapodMachine(machine, s, rep.world_frame == "unregistered");
  describe(rep, machine, model, input, target, options);
  if (!held.data.poses.empty() || !held.data.points.empty())
    rep.holdout = holdout(machine, result.calibrated, model, input, held, s, use_frame, target);
  rep.worst = worstObservations(cal::withHexapodParameters(model, s.parameters), input, s);
  reportWorkspaceErrors(r,
                        workspace.get(),
                        machine,
                        result.calibrated.model,
                        model,
                        input,
                        held,
                        options,
                        rep,
                        control);
  result.notices = hexapodResultNotices(machine, input, rep);
  if (r.out.empty()) {
    result.summary_json = io::hexapodCalibrationJson(rep);
    return result;
  }
  writeHexapodCalibration(result, r.out, r.force);  // the summary with its output paths
  recordHexapodRun(r, machine, model, result);
  return result;
}

void writeHexapodCalibration(HexapodCalibrationResult& result, const std::string& out, bool force) {
  PKM_CHECK(!out.empty(), "give the calibrated machine file CAL.json");
  const CalibrationOutputs paths = calibrationOutputs(out);
  checkOutputs(paths, force);
  io::HexapodCalibrationReport& rep = result.report;
  rep.out_machine = paths.machine;
  rep.out_hal = paths.hal;
  rep.out_summary = paths.summary;
  const io::Overwrite overwrite = force ? io::Overwrite::kAllow : io::Overwrite::kRefuse;
  // A model whose world frame is not the machine's goes into no controller: no setp blocks.
  const bool controller_blocks = !result.calibrated.world_frame_unregistered;
  if (!controller_blocks) rep.out_hal.clear();
  result.summary_json = io::hexapodCalibrationJson(rep);  // once, with the paths written
  io::writeFileAtomic(paths.machine, io::writeHexapodJson(result.calibrated), overwrite);
  if (controller_blocks) {
    io::writeFileAtomic(paths.hal, io::writeLinuxcncSetp(result.calibrated), overwrite);
    io::writeFileAtomic(paths.pkmhexkins, io::writePkmhexkinsSetp(result.calibrated), overwrite);
  }
  io::writeFileAtomic(paths.summary, result.summary_json, overwrite);
}

}  // namespace pkm::workflow
