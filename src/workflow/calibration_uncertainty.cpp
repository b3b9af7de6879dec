// The uncertainty budgets of a hexapod calibration in the workflows
// (calibration_uncertainty.hpp).
#include "calibration_uncertainty.hpp"

#include <fmt/format.h>

#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::workflow::detail {

namespace cal = pkm::calibration;

std::vector<kinematics::PoseRpy> checkPoses(const kinematics::HexapodModel& estimated,
                                            const cal::HexapodCalibrationData& held,
                                            const std::optional<geometry::RigidTransform>& frame) {
  const geometry::RigidTransform f = frame.value_or(geometry::RigidTransform::Identity());
  kinematics::HexapodData work(estimated);
  std::vector<kinematics::PoseRpy> out;
  const auto reach = [&](const kinematics::StrutVector& q, const kinematics::PoseRpy& seed) {
    if (!kinematics::forwardKinematics(estimated, work, q, seed).ok()) return;
    kinematics::PoseRpy p;
    p.position = work.world_p_tcp;
    p.rpy = geometry::rpyFromRotation(work.world_R_platform, seed.rpy);
    out.push_back(p);
  };
  for (const cal::PoseObservation& o : held.poses)
    reach(o.readings, kinematics::poseRpyFromTransform(f * kinematics::toRigidTransform(o.pose)));
  for (const cal::PointObservation& o : held.points) {
    kinematics::PoseRpy seed = estimated.home;
    seed.position = f.linear() * o.point + f.translation();
    reach(o.readings, seed);
  }
  return out;
}

io::HexapodCalibrationReport::Uncertainty hexapodCalibrationUncertainty(
    const kinematics::HexapodModel& initial,
    const cal::HexapodCalibrationData& data,
    const cal::HexapodCalibrationSummary& fit,
    const cal::HexapodCalibrationOptions& options,
    const CalibrationUncertaintyRequest& request,
    const std::vector<kinematics::PoseRpy>& check,
    const std::string& check_label,
    const RunControl& control) {
  io::HexapodCalibrationReport::Uncertainty u;
  u.sources = request.sources_name;
  u.parameters = cal::hexapodParameterUncertainty(initial, data, fit, options, request.sources);
  if (request.monte_carlo_trials > 0) {
    cal::BudgetMonteCarloOptions mc;
    mc.max_trials = request.monte_carlo_trials;
    mc.batch = std::max(10, std::min(50, request.monte_carlo_trials / 4));
    mc.threads = request.threads;
    mc.progress = [&control](int done, int total) {
      control.report({"uncertainty",
                      static_cast<std::size_t>(done),
                      static_cast<std::size_t>(total),
                      0.0,
                      fmt::format("uncertainty Monte Carlo {}/{}", done, total)});
    };
    u.monte_carlo = cal::hexapodBudgetMonteCarlo(
        initial, data, fit, options, request.sources, u.parameters, mc);
    control.checkCancelled();
  }
  const kinematics::HexapodModel estimated = cal::withHexapodParameters(initial, fit.parameters);
  u.tcp_poses = check_label;
  u.tcp = cal::hexapodTcpUncertainty(estimated,
                                     u.parameters.covariance,
                                     check,
                                     request.sources.coverage_factor,
                                     fit.measurement_frame.has_value());
  return u;
}

io::HexapodCalibrationReport::Uncertainty hexapodRequestUncertainty(
    const HexapodCalibrationRequest& r,
    const kinematics::HexapodModel& model,
    const io::CalibrationInput& input,
    const io::CalibrationInput& held,
    const cal::HexapodCalibrationSummary& s,
    const std::vector<kinematics::PoseRpy>& ws,
    const cal::HexapodCalibrationOptions& options,
    const std::optional<io::HexapodCalibrationReport::Holdout>& holdout,
    const RunControl& control) {
  CalibrationUncertaintyRequest u;
  u.sources = r.uncertainty;
  if (!r.uncertainty_name.empty()) u.sources_name = r.uncertainty_name;
  u.monte_carlo_trials = r.uncertainty_trials;
  u.threads = r.threads;
  const bool has_held = !held.data.poses.empty() || !held.data.points.empty();
  const std::vector<kinematics::PoseRpy> check =
      has_held
          ? checkPoses(
                cal::withHexapodParameters(model, s.parameters), held.data, s.measurement_frame)
          : ws;
  io::HexapodCalibrationReport::Uncertainty out = hexapodCalibrationUncertainty(
      model, input.data, s, options, u, check, has_held ? "held-out" : "workspace", control);
  // What the model leaves at the held-out poses beyond its parameters' uncertainty.
  if (holdout && holdout->after.poses > 0)
    cal::addTcpRemainder(out.tcp, holdout->after.rms, r.uncertainty.coverage_factor);
  return out;
}

}  // namespace pkm::workflow::detail
