#include "pkm/kinematics/exechon_wrist.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace pkm::kinematics {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// x + 2·pi·k nearest `near` (x itself, bit for bit, when k = 0).
double nearestTurn(double x, double near) {
  const double k = std::round((near - x) / kTwoPi);
  return k == 0.0 ? x : x + k * kTwoPi;
}

/// Fills data's wrist and tool fields from data's tripod pose and readings (c, a).
void fillTool(const ExechonModel& model, ExechonData& data, double c, double a, bool at_pole) {
  data.c = c;
  data.a = a;
  data.wrist_at_pole = at_pole;
  data.world_R_tool = data.world_T_platform.linear() * toolRotationInPlatform(model.wrist, c, a);
  data.world_u_tool = data.world_R_tool.col(2);
  data.world_p_tool = data.world_p_S + model.wrist.tool_length * data.world_u_tool;
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
  const Eigen::Vector3d zoppi_p_S =
      model.world_T_zoppi.inverse() * (target.position - model.wrist.tool_length * u);
  // The tripod IK leaves data untouched on failure, and the wrist step cannot fail.
  const ExechonIkStatus status =
      previous == nullptr ? tripodInverseKinematics(model, data, zoppi_p_S)
                          : tripodInverseKinematicsNearest(model, data, zoppi_p_S, previous->e);
  if (status != ExechonIkStatus::kOk) return status;
  const Eigen::Vector3d platform_u = data.world_T_platform.linear().transpose() * u;
  const ExechonConfiguration& near = previous == nullptr ? model.home : *previous;
  const ExechonWristAngles w = wristAnglesFromDirection(model.wrist, platform_u, near.c, near.a);
  fillTool(model, data, w.c, w.a, w.at_pole);
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
  const double tc = wrist.c_sign * c + wrist.c0, ta = wrist.a_sign * a + wrist.a0;
  return wristFrame(wrist) * (Eigen::AngleAxisd(tc, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(ta, Eigen::Vector3d::UnitX()))
                                 .toRotationMatrix();
}

ExechonWristAngles wristAnglesFromDirection(const ExechonWrist& wrist,
                                            const Eigen::Vector3d& platform_u_tool,
                                            double c_near,
                                            double a_near) {
  const Eigen::Vector3d v = wristFrame(wrist).transpose() * platform_u_tool.normalized();
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
    return out;
  }
  const double theta_c = std::atan2(v.x(), -v.y());
  double best = INFINITY;
  for (int k = 0; k < 2; ++k) {
    const double c =
        nearestTurn(reading(theta_c + k * std::numbers::pi, wrist.c0, wrist.c_sign), c_near);
    const double a =
        nearestTurn(reading(k == 0 ? theta_a : -theta_a, wrist.a0, wrist.a_sign), a_near);
    const double distance = std::abs(c - c_near) + std::abs(a - a_near);
    if (distance < best) {
      best = distance;
      out.c = c;
      out.a = a;
    }
  }
  return out;
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

void evaluateConfiguration(const ExechonModel& model,
                           ExechonData& data,
                           const ExechonConfiguration& config) {
  evaluateTripod(model, data, config.e, model.tripod.deltaA, model.tripod.deltaC);
  const double sin_a = std::sin(model.wrist.a_sign * config.a + model.wrist.a0);
  fillTool(model, data, config.c, config.a, std::abs(sin_a) <= kExechonWristPoleTolerance);
}

FkSummary toolForwardKinematics(const ExechonModel& model,
                                ExechonData& data,
                                const ExechonJoints& joints,
                                const ExechonConfiguration& seed,
                                const FkOptions& options) {
  const FkSummary summary = tripodForwardKinematics(model, data, joints.readings, seed.e, options);
  const double sin_a = std::sin(model.wrist.a_sign * joints.a + model.wrist.a0);
  fillTool(model, data, joints.c, joints.a, std::abs(sin_a) <= kExechonWristPoleTolerance);
  return summary;
}

ExechonJoints jointsOf(const ExechonData& data) { return {data.readings, data.c, data.a}; }

}  // namespace pkm::kinematics
