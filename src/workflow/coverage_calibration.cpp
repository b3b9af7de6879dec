// The calibrations of `pkm validate coverage` (coverage_analyses.hpp): a hexapod scenario's
// tracker and dial-gauge files calibrated as `pkm calibrate hexapod` does, every parameter and
// the predicted TCP error compared with the virtual machine's true geometry.
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <memory>

#include "coverage_analyses.hpp"
#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/calibration/exechon_parameters.hpp"
#include "pkm/calibration/hexapod_budget.hpp"
#include "pkm/calibration/hexapod_parameters.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_fit.hpp"
#include "pkm/io/calibration_files.hpp"
#include "pkm/io/exechon_tracker_files.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/simulation/compliance.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"
#include "pkm/simulation/unmodelled_geometry.hpp"
#include "pkm/workflow/calibrate_exechon.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"

namespace pkm::workflow::detail {
namespace {

namespace cal = pkm::calibration;

/// The dial-gauge calibration's prior as the default campaign's "seed004-gauges" step sets it
/// (docs/campaign.md): the geometry regularised within 5 mm of the machine file, the readings to
/// the struts' 2 µm, and the budgets' statement of the machine file's geometry at 20 mm — the
/// scenario's joint centres are off by up to 33 mm, a rectangular ±33 mm (σ 19 mm).
constexpr double kGaugePriorSigmaMm = 5.0;
constexpr double kGaugeMeasurementSigmaMm = 0.002;
constexpr double kGaugePriorUncertaintyMm = 20.0;

/// The tracker file of the held-out poses.
constexpr const char* kHoldout = "tracker-holdout.csv";
/// The virtual machine's repeatability stream of the TCP trials.
constexpr std::uint64_t kTcpNoiseSeed = 20261206u;

using FileTexts = std::map<std::string, std::string>;

/// The commanded poses of the held-out file's readings: FK of the nominal model at the commanded
/// strut readings (the nominal controller's own command), those whose FK converges.
std::vector<kinematics::PoseRpy> heldOutCommands(const FileTexts& files,
                                                 const kinematics::HexapodModel& nominal) {
  const auto it = files.find(kHoldout);
  if (it == files.end()) return {};
  io::CalibrationInput held;
  io::addCalibrationFile(io::NamedText{it->first, it->second}, held);
  kinematics::HexapodData work(nominal);
  std::vector<kinematics::PoseRpy> out;
  for (const cal::PoseObservation& o : held.data.poses)
    if (kinematics::forwardKinematics(nominal, work, o.readings, nominal.home).ok())
      out.push_back(work.pose);
  return out;
}

/// Every parameter's estimate with its U against the true parameter.
void addParameters(std::vector<CoverageReading>& out,
                   const std::string& group,
                   const io::HexapodCalibrationReport& report,
                   const cal::HexapodParameterVector& truth) {
  const std::vector<int>& index = report.uncertainty->parameters.parameter_indices;
  const auto& budgets = report.uncertainty->parameters.linear.budgets;
  for (std::size_t b = 0; b < budgets.size(); ++b) {
    if (index[b] < 0) continue;  // a frame or backlash unknown: no true value
    const metrology::UncertaintyBudget& u = budgets[b];
    CoverageReading r{group,
                      u.quantity,
                      u.unit,
                      u.value,
                      u.expandedUncertainty(),
                      u.combinedStandardUncertainty(),
                      u.coverageFactor()};
    r.truth = truth(index[b]);
    out.push_back(r);
  }
}

/// The predicted TCP error at the held-out commands: the virtual machine with the calibrated
/// kinematics in its controller goes to X (moveTo: the true geometry with everything the workshop
/// adds — unmodelled geometry, compliance, strut growth, backlash, repeatability); each
/// coordinate of its tool's error against X is a trial of the predicted U (hexapodTcpUncertainty,
/// a bound for any component),
/// combined with the model's remainder at the held-out poses (addTcpRemainder) and the
/// registration's U at the TCP when the world frame was registered.
void addTcp(std::vector<CoverageReading>& out,
            const std::string& group,
            const HexapodCalibrationResult& result,
            simulation::HexapodVirtualMachine& vm,
            const std::vector<kinematics::PoseRpy>& commands) {
  const kinematics::HexapodModel& calibrated = result.calibrated.model;
  const double k = result.report.uncertainty->parameters.linear.budgets.front().coverageFactor();
  const cal::TcpUncertainty U = cal::hexapodTcpUncertainty(
      calibrated, result.report.uncertainty->parameters.covariance, commands, k);
  const double registration = result.report.registration ? result.report.registration->tcp_U : 0.0;
  const double remainder = result.report.uncertainty->tcp.remainder;
  // The scenario's machine is shared with the next runs: its controller is put back however this
  // ends.
  struct RestoreController {
    simulation::HexapodVirtualMachine& vm;
    kinematics::HexapodModel model;
    ~RestoreController() { vm.setControllerModel(model); }
  } restore{vm, vm.controller()};
  vm.setControllerModel(calibrated);
  vm.reset(kTcpNoiseSeed);
  for (std::size_t i = 0; i < commands.size(); ++i) {
    if (!std::isfinite(U.expanded[i])) continue;
    Eigen::VectorXd command(6);
    command << commands[i].position, commands[i].rpy;
    geometry::RigidTransform reached;
    try {
      reached = vm.moveTo(command);
    } catch (const InvalidArgument&) {
      continue;  // the true machine cannot reach it: no trial
    }
    const Eigen::Vector3d e = reached.translation() - vm.nominalPose(command).translation();
    const double u = std::hypot(std::hypot(U.expanded[i], remainder), registration);
    for (int a = 0; a < 3; ++a) {
      CoverageReading r{group, "TCP error at the held-out poses", "mm", 0.0, u, u / k, k};
      r.truth = e(a);
      out.push_back(r);
    }
  }
}

/// One calibration of `data` as `pkm calibrate hexapod` runs it, and its readings.
void addCalibration(std::vector<CoverageReading>& out,
                    const std::string& group,
                    HexapodCalibrationRequest request,
                    simulation::HexapodVirtualMachine& vm,
                    const std::vector<kinematics::PoseRpy>& commands,
                    const metrology::UncertaintySources& sources) {
  request.loaded = io::HexapodMachine{};
  request.loaded->model = vm.nominal();
  request.loaded->source = "the scenario's nominal machine";
  request.allow_large_changes = true;  // the scenario's assembly errors are large by design
  request.uncertainty = sources;
  const HexapodCalibrationResult result = calibrateHexapod(request);
  if (!result.report.uncertainty) return;
  addParameters(out, group, result.report, cal::hexapodParameters(vm.truth()));
  if (!commands.empty()) addTcp(out, group, result, vm, commands);
}

/// The predicted tool-point (target) U of an Exechon calibration at the held-out readings: the
/// calibrated model's target FK_est(q) against where the true tripod puts it for the same
/// readings (its legs' lead errors and compliance included), each coordinate a trial. The fit
/// estimated the tracker's frame, so its world is fixed only up to a rigid motion (as the
/// hexapod's aligned Monte Carlo): the predicted targets are first moved onto the true ones by
/// their best rigid fit.
void addExechonTcp(std::vector<CoverageReading>& out,
                   const ExechonCalibrationResult& result,
                   const simulation::HybridTripod& tripod,
                   const FileTexts& files) {
  const auto held = files.find(kHoldout);
  if (held == files.end()) return;
  io::ExechonCalibrationInput in;
  io::addExechonCalibrationFile(io::NamedText{held->first, held->second}, in);
  const auto& u = *result.report.tripod->uncertainty;
  if (u.tcp.expanded.size() != in.data.observations.size()) return;
  const kinematics::ExechonModel& est = result.calibrated.model;
  const kinematics::ExechonModel& truth = tripod.actual();
  const Eigen::Vector3d& offset = in.data.target_offset;
  const kinematics::FkOptions& fk = tripod.fkOptions();
  const double k = u.parameters.linear.budgets.front().coverageFactor();
  std::vector<Eigen::Vector3d> predicted_points, reached_points;
  std::vector<double> expanded;
  for (std::size_t i = 0; i < u.tcp.expanded.size(); ++i) {
    const double U = u.tcp.expanded[i];
    const kinematics::ExechonJoints& q = in.data.observations[i].joints;
    const std::optional<Eigen::Vector3d> predicted =
        cal::exechonTarget(est, q, offset, est.home, fk);
    if (!std::isfinite(U) || !predicted) continue;
    const kinematics::ExechonJoints travelled =
        simulation::withLeadErrors(q, tripod.legLeadErrors());
    const kinematics::ExechonJoints actual =
        tripod.compliance() ? simulation::exechonDeflectedJoints(
                                  truth, travelled, truth.home, fk, *tripod.compliance())
                            : travelled;
    const std::optional<Eigen::Vector3d> reached =
        cal::exechonTarget(truth, actual, offset, truth.home, fk);
    if (!reached) continue;
    predicted_points.push_back(*predicted);
    reached_points.push_back(*reached);
    expanded.push_back(U);
  }
  if (predicted_points.size() < 3) return;
  // reached_T_predicted: the rigid motion that best puts the predicted targets on the reached.
  const geometry::RigidTransform align =
      geometry::fitRigidTransform(reached_points, predicted_points);
  for (std::size_t i = 0; i < predicted_points.size(); ++i) {
    const Eigen::Vector3d e = reached_points[i] - align * predicted_points[i];
    for (int a = 0; a < 3; ++a) {
      CoverageReading r{"calibration exechon tracker",
                        "tool point at the held-out poses",
                        "mm",
                        0.0,
                        expanded[i],
                        expanded[i] / k,
                        k};
      r.truth = e(a);
      out.push_back(r);
    }
  }
}

/// The hybrid machine's four squareness errors from the hybrid tracker files (the fit after the
/// tripod's, as `pkm calibrate exechon` reports them): each against the machine's injected
/// squareness, U = k·u with u the fit's σ and the calibrated tripod's uncertainty combined
/// (HybridSquarenessReport::standardUncertainty), k the sources'.
void addHybridSquareness(std::vector<CoverageReading>& out,
                         const ExechonCalibrationResult& result,
                         const simulation::HybridVirtualMachine& vm,
                         double k) {
  if (!result.report.hybrid) return;
  const cal::HybridCalibrationSummary& fit = result.report.hybrid->fit;
  const kinematics::HybridSquareness& t = vm.errors().squareness;
  const Eigen::Vector4d standard = result.report.hybrid->standardUncertainty();
  const std::array<double, 4> estimate{
      fit.squareness.sz_x2, fit.squareness.sx_p, fit.squareness.sy_p, fit.squareness.sz_p};
  const std::array<double, 4> truth{t.sz_x2, t.sx_p, t.sy_p, t.sz_p};
  for (int i = 0; i < 4; ++i) {
    const double u = standard(i);
    CoverageReading r{"calibration hybrid squareness",
                      cal::hybridSquarenessNames()[static_cast<std::size_t>(i)],
                      "rad",
                      estimate[static_cast<std::size_t>(i)],
                      k * u,
                      u,
                      k};
    r.truth = truth[static_cast<std::size_t>(i)];
    out.push_back(r);
  }
}

/// The Exechon tripod calibration of a hybrid scenario's tracker files (tracker-fit.csv with the
/// held-out tracker-holdout.csv) as `pkm calibrate exechon` runs it: each estimated parameter
/// against the true tripod's (its assembly errors added to the machine file's).
void addExechonCalibration(std::vector<CoverageReading>& out,
                           const io::Scenario& scenario,
                           const FileTexts& files,
                           const simulation::HybridVirtualMachine& vm,
                           const metrology::UncertaintySources& sources) {
  const simulation::HybridTripod& tripod = *vm.tripod();
  const auto fit = files.find("tracker-fit.csv");
  if (fit == files.end()) return;
  ExechonCalibrationRequest r;
  r.machine = scenario.machine_spec;
  r.data = {{fit->first, fit->second}};
  if (const auto held = files.find(kHoldout); held != files.end())
    r.holdout = {{held->first, held->second}};
  // The hybrid files, with the machine's known position-dependent errors under the fit.
  if (const auto hybrid = files.find("tracker-hybrid.csv");
      hybrid != files.end() && !scenario.errors_spec.empty()) {
    r.data.push_back({hybrid->first, hybrid->second});
    r.errors = scenario.errors_spec;
  }
  r.allow_large_changes = true;  // the scenario's assembly errors are large by design
  r.uncertainty = sources;
  const ExechonCalibrationResult result = calibrateExechon(r);
  if (!result.report.tripod || !result.report.tripod->uncertainty) return;
  const auto& u = result.report.tripod->uncertainty->parameters;
  const cal::ExechonParameterVector truth =
      cal::exechonParameters(tripod.actual(), tripod.nominal().world_T_zoppi);
  for (std::size_t b = 0; b < u.linear.budgets.size(); ++b) {
    if (u.parameter_indices[b] < 0) continue;  // the tracker frame: no true value
    const metrology::UncertaintyBudget& p = u.linear.budgets[b];
    CoverageReading reading{"calibration exechon tracker",
                            p.quantity,
                            p.unit,
                            p.value,
                            p.expandedUncertainty(),
                            p.combinedStandardUncertainty(),
                            p.coverageFactor()};
    reading.truth = truth(u.parameter_indices[b]);
    out.push_back(reading);
  }
  addExechonTcp(out, result, tripod, files);
  addHybridSquareness(out, result, vm, sources.coverage_factor);
}

}  // namespace

std::vector<CoverageReading> calibrationReadings(const io::Scenario& scenario,
                                                 const SimulateResult& simulation,
                                                 const metrology::UncertaintySources& sources) {
  FileTexts files;
  for (const SimulatedFile& f : simulation.files) files[f.name] = f.text;
  if (const auto* hybrid =
          dynamic_cast<const simulation::HybridVirtualMachine*>(scenario.campaign.machine.get());
      hybrid != nullptr && hybrid->tripod()) {
    std::vector<CoverageReading> out;
    addExechonCalibration(out, scenario, files, *hybrid, sources);
    return out;
  }
  auto* vm = dynamic_cast<simulation::HexapodVirtualMachine*>(scenario.campaign.machine.get());
  if (vm == nullptr) return {};
  const std::vector<kinematics::PoseRpy> commands = heldOutCommands(files, vm->nominal());
  std::vector<CoverageReading> out;
  const auto pose = files.find("tracker-pose.csv");
  const auto registration = files.find("tracker-pose-registration.csv");
  if (pose != files.end() && registration != files.end()) {
    HexapodCalibrationRequest r;
    r.data = {{pose->first, pose->second}};
    r.registration = io::NamedText{registration->first, registration->second};
    // The held-out poses, as a user checks the calibration: their remainder enters the TCP U.
    if (const auto held = files.find(kHoldout); held != files.end())
      r.holdout = {{held->first, held->second}};
    addCalibration(out, "calibration tracker-pose", r, *vm, commands, sources);
  }
  if (const auto gauges = files.find("constrained-motion.csv"); gauges != files.end()) {
    HexapodCalibrationRequest r;
    r.data = {{gauges->first, gauges->second}};
    r.prior_sigma = kGaugePriorSigmaMm;
    r.measurement_sigma = kGaugeMeasurementSigmaMm;
    r.prior_uncertainty = kGaugePriorUncertaintyMm;
    addCalibration(out, "calibration constrained-motion", r, *vm, commands, sources);
  }
  return out;
}

}  // namespace pkm::workflow::detail
