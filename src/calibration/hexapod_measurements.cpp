#include "pkm/calibration/hexapod_measurements.hpp"

#include <Eigen/LU>

#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::calibration {

using kinematics::kStruts;

PoseParameterJacobian readingParameterJacobian(const kinematics::HexapodModel& /*model*/,
                                               const kinematics::HexapodData& data) {
  PoseParameterJacobian J = PoseParameterJacobian::Zero();
  for (int i = 0; i < kStruts; ++i) {
    const Eigen::Vector3d& u = data.unit_leg[static_cast<std::size_t>(i)];
    // reading_i = |p + R a_i − b_i| − offset_i.
    J.block<1, 3>(i, baseParameter(i, 0)) = -u.transpose();
    J.block<1, 3>(i, platformParameter(i, 0)) = u.transpose() * data.world_R_platform;
    J(i, offsetParameter(i)) = -1.0;
  }
  return J;
}

kinematics::StrutVector poseResiduals(const kinematics::HexapodModel& model,
                                      kinematics::HexapodData& data,
                                      const PoseObservation& observation,
                                      PoseParameterJacobian* J) {
  const kinematics::StrutVector& q = kinematics::inverseKinematics(model, data, observation.pose);
  if (J != nullptr) *J = readingParameterJacobian(model, data);
  return q - observation.readings;
}

std::optional<Eigen::Matrix<double, 6, 1>> forwardPoseError(const kinematics::HexapodModel& model,
                                                            kinematics::HexapodData& data,
                                                            const kinematics::StrutVector& readings,
                                                            const kinematics::PoseRpy& measured,
                                                            const kinematics::PoseRpy& seed,
                                                            PoseParameterJacobian* J,
                                                            const kinematics::FkOptions& options) {
  const kinematics::FkSummary fk =
      kinematics::forwardKinematics(model, data, readings, seed, options);
  if (!fk.ok()) return std::nullopt;
  Eigen::Matrix<double, 6, 1> e;
  e.head<3>() = data.world_p_tcp - measured.position;
  e.tail<3>() =
      geometry::so3Log(data.world_R_platform * geometry::rotationFromRpy(measured.rpy).transpose());
  if (J != nullptr) {
    // IK(x(θ), θ) = q: J_q_x·dx + dq/dθ·dθ = 0.
    kinematics::computeStrutJacobian(model, data);
    const Eigen::PartialPivLU<kinematics::Matrix6d> lu(data.J_q_x);
    *J = -lu.solve(readingParameterJacobian(model, data));
  }
  return e;
}

std::optional<Eigen::Vector3d> pointResiduals(const kinematics::HexapodModel& model,
                                              kinematics::HexapodData& data,
                                              const PointObservation& observation,
                                              const kinematics::PoseRpy& seed,
                                              PointParameterJacobian* J) {
  kinematics::PoseRpy measured;
  measured.position = observation.point;
  PoseParameterJacobian full;
  const auto e = forwardPoseError(
      model, data, observation.readings, measured, seed, J != nullptr ? &full : nullptr);
  if (!e) return std::nullopt;
  if (J != nullptr) *J = full.topRows<3>();
  return Eigen::Vector3d(e->head<3>());
}

}  // namespace pkm::calibration
