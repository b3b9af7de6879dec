#include "pkm/kinematics/exechon_wrist.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace pkm::kinematics {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// x + 2·pi·k nearest `near` (x itself, bit for bit, when k = 0).
double nearestTurn(double x, double near) {
  if (std::abs(near - x) < std::numbers::pi) return x;  // k = 0 (the common case on a path)
  const double k = std::round((near - x) / kTwoPi);
  return k == 0.0 ? x : x + k * kTwoPi;
}

/// Rz(θC)·Rx(θA) from the sines and cosines of θC and θA.
Eigen::Matrix3d rzRx(double sc, double cc, double sa, double ca) {
  Eigen::Matrix3d m;
  m << cc, -sc * ca, sc * sa, sc, cc * ca, -cc * sa, 0.0, sa, ca;
  return m;
}

/// Rz(θC)·Rx(θA) for readings (c, a).
Eigen::Matrix3d rzRxOfReadings(const ExechonWrist& wrist, double c, double a) {
  const double tc = wrist.c_sign * c + wrist.c0, ta = wrist.a_sign * a + wrist.a0;
  return rzRx(std::sin(tc), std::cos(tc), std::sin(ta), std::cos(ta));
}

/// Fills data's wrist and tool fields from data's tripod pose, the readings (c, a) and
/// wrist_R_tool = Rz(θC)·Rx(θA) of those readings.
void fillTool(const ExechonModel& model,
              ExechonData& data,
              double c,
              double a,
              bool at_pole,
              const Eigen::Matrix3d& platform_R_wrist,
              const Eigen::Matrix3d& wrist_R_tool) {
  data.c = c;
  data.a = a;
  data.wrist_at_pole = at_pole;
  data.world_R_tool = data.world_T_platform.linear() * (platform_R_wrist * wrist_R_tool);
  data.world_u_tool = data.world_R_tool.col(2);
  data.world_p_tool = data.world_p_S + model.wrist.tool_length * data.world_u_tool;
}

/// wristAnglesFromDirection for v = W⁻¹·u (unit), also giving Rz(θC)·Rx(θA) of the result
/// (from v's components, without evaluating trigonometric functions away from the pole).
ExechonWristAngles anglesInWristFrame(const ExechonWrist& wrist,
                                      const Eigen::Vector3d& v,
                                      double c_near,
                                      double a_near,
                                      Eigen::Matrix3d* wrist_R_tool) {
  const double rho = std::sqrt(v.x() * v.x() + v.y() * v.y());
  const double theta_a = std::atan2(rho, v.z());  // in [0, pi]
  ExechonWristAngles out;
  const auto reading = [](double theta, double zero, int sign) { return sign * (theta - zero); };
  if (rho <= kExechonWristPoleTolerance) {
    out.at_pole = true;
    out.c = c_near;
    out.a = nearestTurn(reading(theta_a, wrist.a0, wrist.a_sign), a_near);
    if (v.z() < 0.0) {  // θA = ±pi: take the nearer of the two
      const double other = nearestTurn(reading(-theta_a, wrist.a0, wrist.a_sign), a_near);
      if (std::abs(other - a_near) < std::abs(out.a - a_near)) out.a = other;
    }
    if (wrist_R_tool != nullptr) *wrist_R_tool = rzRxOfReadings(wrist, out.c, out.a);
    return out;
  }
  const double theta_c = std::atan2(v.x(), -v.y());
  double best = INFINITY;
  int best_k = 0;
  for (int k = 0; k < 2; ++k) {
    const double c =
        nearestTurn(reading(theta_c + k * std::numbers::pi, wrist.c0, wrist.c_sign), c_near);
    const double a =
        nearestTurn(reading(k == 0 ? theta_a : -theta_a, wrist.a0, wrist.a_sign), a_near);
    const double distance = std::abs(c - c_near) + std::abs(a - a_near);
    if (distance < best) {
      best = distance;
      best_k = k;
      out.c = c;
      out.a = a;
    }
  }
  if (wrist_R_tool != nullptr) {
    // sin θA = rho, cos θA = v.z, sin θC = v.x/rho, cos θC = −v.y/rho; the second solution
    // (θC + pi, −θA) flips the signs of sin θC, cos θC and sin θA.
    const double f = best_k == 0 ? 1.0 : -1.0;
    *wrist_R_tool = rzRx(f * v.x() / rho, -f * v.y() / rho, f * rho, v.z());
  }
  return out;
}

ExechonIkStatus solveTool(const ExechonModel& model,
                          ExechonData& data,
                          const ExechonToolPose& target,
                          const ExechonConfiguration* previous) {
  const double norm = target.direction.norm();
  if (!target.position.allFinite() || !target.direction.allFinite() || !(norm > 0.0))
    return ExechonIkStatus::kInvalidInput;
  if (previous != nullptr && !(std::isfinite(previous->c) && std::isfinite(previous->a)))
    return ExechonIkStatus::kInvalidInput;
  const Eigen::Vector3d u = target.direction / norm;
  const Eigen::Vector3d zoppi_p_S = model.world_T_zoppi.inverse(Eigen::Isometry) *
                                    (target.position - model.wrist.tool_length * u);
  // The tripod IK leaves data untouched on failure, and the wrist step cannot fail.
  const ExechonIkStatus status =
      previous == nullptr ? tripodInverseKinematics(model, data, zoppi_p_S)
                          : tripodInverseKinematicsNearest(model, data, zoppi_p_S, previous->e);
  if (status != ExechonIkStatus::kOk) return status;
  if (data.wrist_axes_of_frame[0] != model.wrist.c_axis ||
      data.wrist_axes_of_frame[1] != model.wrist.a_axis) {
    data.wrist_frame = wristFrame(model.wrist);
    data.wrist_axes_of_frame = {model.wrist.c_axis, model.wrist.a_axis};
  }
  const Eigen::Matrix3d& W = data.wrist_frame;
  const Eigen::Vector3d v =
      (W.transpose() * (data.world_T_platform.linear().transpose() * u)).normalized();
  const ExechonConfiguration& near = previous == nullptr ? model.home : *previous;
  Eigen::Matrix3d wrist_R_tool;
  const ExechonWristAngles w = anglesInWristFrame(model.wrist, v, near.c, near.a, &wrist_R_tool);
  fillTool(model, data, w.c, w.a, w.at_pole, W, wrist_R_tool);
  return status;
}

}  // namespace

Eigen::Matrix3d wristFrame(const ExechonWrist& wrist) {
  const Eigen::Vector3d c = wrist.c_axis.normalized();
  const Eigen::Vector3d x = (wrist.a_axis - wrist.a_axis.dot(c) * c).normalized();
  Eigen::Matrix3d W;
  W << x, c.cross(x), c;
  return W;
}

Eigen::Matrix3d toolRotationInPlatform(const ExechonWrist& wrist, double c, double a) {
  return wristFrame(wrist) * rzRxOfReadings(wrist, c, a);
}

ExechonWristAngles wristAnglesFromDirection(const ExechonWrist& wrist,
                                            const Eigen::Vector3d& platform_u_tool,
                                            double c_near,
                                            double a_near) {
  const Eigen::Vector3d v = wristFrame(wrist).transpose() * platform_u_tool.normalized();
  return anglesInWristFrame(wrist, v, c_near, a_near, nullptr);
}

ExechonIkStatus toolInverseKinematics(const ExechonModel& model,
                                      ExechonData& data,
                                      const ExechonToolPose& target) {
  return solveTool(model, data, target, nullptr);
}

ExechonIkStatus toolInverseKinematics(const ExechonModel& model,
                                      ExechonData& data,
                                      const ExechonToolPose& target,
                                      const ExechonConfiguration& previous) {
  return solveTool(model, data, target, &previous);
}

void setWristReadings(const ExechonModel& model, ExechonData& data, double c, double a) {
  const Eigen::Matrix3d wrist_R_tool = rzRxOfReadings(model.wrist, c, a);
  fillTool(model,
           data,
           c,
           a,
           std::abs(wrist_R_tool(2, 1)) <= kExechonWristPoleTolerance,
           wristFrame(model.wrist),
           wrist_R_tool);
}

void evaluateConfiguration(const ExechonModel& model,
                           ExechonData& data,
                           const ExechonConfiguration& config) {
  evaluateTripod(model, data, config.e, model.tripod.deltaA, model.tripod.deltaC);
  setWristReadings(model, data, config.c, config.a);
}

FkSummary toolForwardKinematics(const ExechonModel& model,
                                ExechonData& data,
                                const ExechonJoints& joints,
                                const ExechonConfiguration& seed,
                                const FkOptions& options) {
  const FkSummary summary = tripodForwardKinematics(model, data, joints.readings, seed.e, options);
  setWristReadings(model, data, joints.c, joints.a);
  return summary;
}

ExechonJoints jointsOf(const ExechonData& data) { return {data.readings, data.c, data.a}; }

}  // namespace pkm::kinematics
