#include "pkm/kinematics/exechon_wrist.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "kinematics/exechon_tripod_math.hpp"

namespace pkm::kinematics {

namespace {

constexpr double kFullTurn = 2.0 * std::numbers::pi;
/// toolPointInverseKinematics: Newton iterations, step halvings per iteration, and the
/// convergence thresholds relative to the characteristic length (tolerance; rounding floor).
constexpr int kMaxToolPointIterations = 50;
constexpr int kMaxStepHalvings = 30;
constexpr double kToolPointTolerance = 1e-14;
constexpr double kToolPointFloor = 1e-12;

/// x + 2·pi·k nearest `near` (x itself, bit for bit, when k = 0).
double nearestTurn(double x, double near) {
  if (std::abs(near - x) < std::numbers::pi) return x;  // k = 0 (the common case on a path)
  const double k = std::round((near - x) / kFullTurn);
  return k == 0.0 ? x : x + k * kFullTurn;
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

/// data.wrist_frame: wristFrame(model.wrist), recomputed only when the model's axes differ from
/// those it was computed for.
const Eigen::Matrix3d& cachedWristFrame(const ExechonModel& model, ExechonData& data) {
  if (data.wrist_axes_of_frame[0] != model.wrist.c_axis ||
      data.wrist_axes_of_frame[1] != model.wrist.a_axis) {
    data.wrist_frame = wristFrame(model.wrist);
    data.wrist_axes_of_frame = {model.wrist.c_axis, model.wrist.a_axis};
  }
  return data.wrist_frame;
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
  const Eigen::Matrix3d& W = cachedWristFrame(model, data);
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

ExechonIkStatus toolPointInverseKinematics(const ExechonModel& model,
                                           ExechonData& data,
                                           const Eigen::Vector3d& world_p_tool,
                                           double c,
                                           double a,
                                           const Eigen::Vector3d& e_start) {
  if (!world_p_tool.allFinite() || !std::isfinite(c) || !std::isfinite(a) || !e_start.allFinite())
    return ExechonIkStatus::kInvalidInput;
  const ExechonTripodGeometry& g = model.tripod;
  const Eigen::Vector3d v =
      model.wrist.tool_length *
      (cachedWristFrame(model, data) * rzRxOfReadings(model.wrist, c, a)).col(2);
  const Eigen::Vector3d p = model.world_T_zoppi.inverse(Eigen::Isometry) * world_p_tool;
  const double tol = kToolPointTolerance * model.characteristicLength();
  const double floor = kToolPointFloor * model.characteristicLength();
  Eigen::Vector3d e = e_start, point;
  detail::ExechonTrig t = detail::trigOf(e);
  if (!detail::platformPointAt(g, t, v, &point, nullptr)) return ExechonIkStatus::kSingular;
  double last = INFINITY;
  for (int it = 0;; ++it) {
    const Eigen::Vector3d r = point - p;
    const double err = r.norm();
    if (err <= tol || (err <= floor && err >= last)) break;
    if (it == kMaxToolPointIterations) return ExechonIkStatus::kSingular;
    Eigen::Vector3d unused;
    Eigen::Matrix3d J;
    if (!detail::platformPointAt(g, t, v, &unused, &J)) return ExechonIkStatus::kSingular;
    // Cramer's rule for J·step = −r.
    const Eigen::Vector3d j12 = J.col(1).cross(J.col(2));
    const double det = J.col(0).dot(j12);
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return ExechonIkStatus::kSingular;
    Eigen::Vector3d step =
        -Eigen::Vector3d(
            r.dot(j12), J.col(0).dot(r.cross(J.col(2))), J.col(0).dot(J.col(1).cross(r))) /
        det;
    for (int halving = 0;; ++halving) {
      const detail::ExechonTrig trial_t = detail::trigOf(e + step);
      Eigen::Vector3d trial_point;
      if (detail::platformPointAt(g, trial_t, v, &trial_point, nullptr) &&
          ((trial_point - p).norm() < err || (trial_point - p).norm() <= floor)) {
        e += step;
        t = trial_t;
        point = trial_point;
        break;
      }
      if (halving == kMaxStepHalvings) return ExechonIkStatus::kSingular;
      step *= 0.5;
    }
    last = err;
  }
  for (int i = 0; i < 2; ++i) e[i] = std::remainder(e[i], kFullTurn);
  evaluateTripod(model, data, e, g.deltaA, g.deltaC);
  setWristReadings(model, data, c, a);
  return ExechonIkStatus::kOk;
}

void setWristReadings(const ExechonModel& model, ExechonData& data, double c, double a) {
  const Eigen::Matrix3d wrist_R_tool = rzRxOfReadings(model.wrist, c, a);
  fillTool(model,
           data,
           c,
           a,
           std::abs(wrist_R_tool(2, 1)) <= kExechonWristPoleTolerance,
           cachedWristFrame(model, data),
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
