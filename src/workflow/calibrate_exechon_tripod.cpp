// The tripod and wrist fit of workflow::calibrateExechon (calibrate_exechon_detail.hpp).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "calibrate_exechon_detail.hpp"
#include "calibration_common.hpp"
#include "pkm/calibration/acceptance.hpp"
#include "pkm/calibration/exechon_uncertainty.hpp"
#include "pkm/calibration/hexapod_budget.hpp"
#include "pkm/calibration/holdout.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"

namespace pkm::workflow::detail {
namespace {

namespace cal = pkm::calibration;

/// Count, mean, 95th percentile and max of `values` (empty: nullopt).
std::optional<io::DistanceStatistics> statistics(std::vector<double> values) {
  if (values.empty()) return std::nullopt;
  std::sort(values.begin(), values.end());
  double mean = 0.0;
  for (const double e : values) mean += e / static_cast<double>(values.size());
  const auto p95 = values[static_cast<std::size_t>(0.95 * static_cast<double>(values.size() - 1))];
  return io::DistanceStatistics{values.size(), mean, p95, values.back()};
}

/// A reachable point of the PKM working-box grid: the tool point and the nominal solution there.
struct GridPoint {
  Eigen::Vector3d position;
  kinematics::ExechonJoints joints;
  kinematics::ExechonConfiguration seed;
};

/// The PKM working box of a hybrid machine sampled 5 × 5 × 5 with the tool vertical (−z), the
/// points the nominal machine reaches within its limits; empty without a finite working box.
std::vector<GridPoint> workingBoxGrid(const io::ExechonMachine& machine) {
  std::vector<GridPoint> out;
  if (!machine.hybrid) return out;
  const Eigen::Vector3d lo = machine.hybrid->pkm_min, hi = machine.hybrid->pkm_max;
  if (!lo.allFinite() || !hi.allFinite()) return out;
  kinematics::ExechonData nom(machine.model);
  constexpr int kSteps = 5;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < kSteps; ++j)
      for (int k = 0; k < kSteps; ++k) {
        const Eigen::Vector3d f(i / (kSteps - 1.0), j / (kSteps - 1.0), k / (kSteps - 1.0));
        kinematics::ExechonToolPose target;
        target.position = lo + f.cwiseProduct(hi - lo);
        target.direction = -Eigen::Vector3d::UnitZ();
        if (kinematics::checkToolPose(machine.model, nom, target).ok())
          out.push_back(
              {target.position, kinematics::jointsOf(nom), kinematics::configurationOf(nom)});
      }
  return out;
}

/// Over the working-box grid: the tool-point error of the nominal controller on the calibrated
/// machine (nominal IK, calibrated FK: what the calibration removes), and the linearised
/// tool-point uncertainty the calibration leaves (exechonTargetUncertainty with the estimate's
/// covariance).
void workspaceMap(const io::ExechonMachine& machine,
                  const kinematics::ExechonModel& calibrated,
                  const Eigen::MatrixXd& covariance,
                  io::ExechonTripodReport& report) {
  std::vector<double> errors, uncertainty;
  kinematics::ExechonData cal_data(calibrated);
  for (const GridPoint& g : workingBoxGrid(machine)) {
    if (!kinematics::toolForwardKinematics(calibrated, cal_data, g.joints, g.seed, machine.fk).ok())
      continue;
    errors.push_back((cal_data.world_p_tool - g.position).norm());
    if (const auto u = cal::exechonTargetUncertainty(
            calibrated, covariance, g.joints, Eigen::Vector3d::Zero(), g.seed, machine.fk))
      uncertainty.push_back(*u);
  }
  report.map_before = statistics(errors);
  if (report.map_before) report.map_after = statistics(uncertainty);
}

/// The joints of the working-box grid, or, without a working box, the joints of the fitted
/// observations: where the Monte Carlo tool-point spread is evaluated.
std::vector<kinematics::ExechonJoints> monteCarloWorkspace(
    const io::ExechonMachine& machine, const cal::ExechonCalibrationData& data) {
  std::vector<kinematics::ExechonJoints> out;
  for (const GridPoint& g : workingBoxGrid(machine)) out.push_back(g.joints);
  if (out.empty())
    for (const cal::ExechonObservation& o : data.observations) out.push_back(o.joints);
  return out;
}

/// --monte-carlo: the calibration repeated on simulated tracker noise (monteCarloExechon).
io::ExechonTripodReport::MonteCarlo monteCarlo(const ExechonCalibrationRequest& r,
                                               const io::ExechonMachine& machine,
                                               const cal::ExechonCalibrationData& data,
                                               const cal::ExechonCalibrationSummary& s,
                                               const kinematics::ExechonModel& estimate,
                                               const cal::ExechonCalibrationOptions& options,
                                               const RunControl& control) {
  cal::ExechonMonteCarloOptions mc;
  mc.trials = r.monte_carlo;
  mc.threads = r.threads;
  mc.position_sigma = r.sigma_position > 0.0 ? r.sigma_position : s.sigma;
  mc.direction_sigma = r.sigma_orientation_urad * 1e-6;
  mc.progress = detail::monteCarloProgress(control);
  io::ExechonTripodReport::MonteCarlo out;
  out.summary = cal::monteCarloExechon(machine.model,
                                       data,
                                       estimate,
                                       s.measurement_frame,
                                       monteCarloWorkspace(machine, data),
                                       options,
                                       mc);
  out.sigma_position = mc.position_sigma;
  out.sigma_orientation = mc.direction_sigma;
  control.checkCancelled();
  return out;
}

/// Throws when the fit is implausible or does not explain the data.
void accept(const cal::ExechonCalibrationSummary& s,
            const kinematics::ExechonModel& model,
            const ExechonCalibrationRequest& r,
            const RunControl& control) {
  if (!s.warnings.empty())
    throw InvalidArgument(
        fmt::format("calibration result is implausible; nothing was written:\n  {}",
                    fmt::join(s.warnings, "\n  ")));
  if (cal::explainsData(s.after.rms, model.characteristicLength())) {
    detail::refuseLargeChanges(s.large_changes, r.allow_large_changes, control);
    return;
  }
  throw InvalidArgument(fmt::format(
      "calibration does not explain the data: residual RMS {:.4g} (max {:.4g}) after {} "
      "iterations ({}); check the units (legs {}, wrist angles in degrees), the --frame option "
      "and outliers (--loss cauchy --loss-scale ...); nothing was written. Largest residuals:{}",
      s.after.rms,
      s.after.max,
      s.iterations,
      s.termination,
      toString(model.unit),
      detail::worstList(s.worst)));
}

/// The budgets of the tripod fit and the predicted tool-point U at the held-out configurations
/// (or at the fitted ones without held-out data).
io::ExechonTripodReport::Uncertainty uncertainty(const ExechonCalibrationRequest& r,
                                                 const kinematics::ExechonModel& initial,
                                                 const cal::ExechonCalibrationData& data,
                                                 const cal::ExechonCalibrationData& held,
                                                 const cal::ExechonCalibrationSummary& s,
                                                 const cal::ExechonCalibrationOptions& options) {
  io::ExechonTripodReport::Uncertainty u;
  u.sources = r.uncertainty_name.empty() ? "typical datasheet values" : r.uncertainty_name;
  u.parameters = cal::exechonParameterUncertainty(initial, data, s, options, r.uncertainty);
  if (r.uncertainty_trials > 0) {
    cal::BudgetMonteCarloOptions mc;
    mc.max_trials = r.uncertainty_trials;
    mc.batch = std::max(10, std::min(50, r.uncertainty_trials / 4));
    mc.threads = r.threads;
    u.monte_carlo =
        cal::exechonBudgetMonteCarlo(initial, data, s, options, r.uncertainty, u.parameters, mc);
  }
  const cal::ExechonCalibrationData& at = held.observations.empty() ? data : held;
  u.tcp_poses = held.observations.empty() ? "fitted" : "held-out";
  std::vector<kinematics::ExechonJoints> joints;
  for (const cal::ExechonObservation& o : at.observations) joints.push_back(o.joints);
  u.tcp = cal::exechonToolUncertainty(
      cal::withExechonParameters(initial, s.parameters, initial.world_T_zoppi),
      u.parameters.covariance,
      joints,
      data.target_offset,
      options.fk,
      r.uncertainty.coverage_factor);
  return u;
}

}  // namespace

io::ExechonTripodReport fitTripod(const ExechonCalibrationRequest& r,
                                  const io::ExechonMachine& machine,
                                  io::ExechonCalibrationInput& input,
                                  const io::ExechonCalibrationInput& held,
                                  io::ExechonMachine& calibrated,
                                  const RunControl& control) {
  const bool use_frame = r.frame == "tracker" || (r.frame == "auto" && input.tracker_frame);
  cal::ExechonCalibrationOptions options;
  options.fk = machine.fk;
  if (use_frame) {
    input.data.measurement_frame =
        cal::initialExechonMeasurementFrame(machine.model, input.data, machine.fk);
    // The tracker frame and the base placement differ by one rigid motion the data cannot see:
    // the machine's world frame stays where the machine file puts the base (docs/calibration.md).
    for (int k = cal::kExechonBaseParameter; k < cal::kExechonParameters; ++k)
      options.free[static_cast<std::size_t>(k)] = false;
  }
  for (const std::string& name : r.fix)
    options.free[static_cast<std::size_t>(cal::exechonParameterIndex(name))] = false;
  options.loss = robustLoss(r.loss);
  options.loss_scale = r.loss_scale;

  io::ExechonTripodReport report;
  report.fit = cal::calibrateExechon(machine.model, input.data, options);
  const cal::ExechonCalibrationSummary& s = report.fit;
  accept(s, machine.model, r, control);
  calibrated.model =
      cal::withExechonParameters(machine.model, s.parameters, machine.model.world_T_zoppi);
  calibrated.model.name = machine.model.name + "-calibrated";
  calibrated.notices.clear();
  calibrated.description =
      fmt::format("{} calibrated by pkm calibrate exechon", machine.model.name);

  report.points = input.data.observations.size();
  report.equations = input.data.equations();
  report.target_offset = input.data.target_offset;
  for (std::size_t k = 0; k < report.free.size(); ++k) report.free[k] = options.free[k];
  if (!held.data.observations.empty()) {
    std::optional<geometry::RigidTransform> f0;
    if (use_frame) f0 = input.data.measurement_frame;
    report.holdout = io::HoldoutComparison{
        cal::exechonHoldoutErrors(machine.model, f0, held.data, machine.fk),
        cal::exechonHoldoutErrors(calibrated.model, s.measurement_frame, held.data, machine.fk)};
  }
  workspaceMap(machine, calibrated.model, s.covariance, report);
  if (r.monte_carlo > 0)
    report.monte_carlo = monteCarlo(r, machine, input.data, s, calibrated.model, options, control);
  report.uncertainty = uncertainty(r, machine.model, input.data, held.data, s, options);
  // What the model leaves at the held-out poses beyond its parameters' uncertainty.
  if (report.holdout && report.holdout->after.poses > 0)
    cal::addTcpRemainder(
        report.uncertainty->tcp, report.holdout->after.rms, r.uncertainty.coverage_factor);
  return report;
}

}  // namespace pkm::workflow::detail
