#include "pkm/kinematics/exechon_checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "pkm/kinematics/exechon_ik.hpp"

namespace pkm::kinematics {

namespace {

constexpr const char* kLegNames[kExechonLegs] = {"leg A", "leg B", "leg C"};

/// Appends a violation of `range` by `value` when its margin is negative.
void checkRange(const AngleRange& range,
                double value,
                const char* item,
                double& margin,
                std::vector<LimitViolation>& out) {
  margin = range.margin(value);
  if (margin < 0.0)
    out.push_back(
        {LimitKind::kJointAngle, item, value, value < range.min ? range.min : range.max, margin});
}

ExechonCheckResult failed(std::string_view word) {
  ExechonCheckResult out;
  out.solver_status = word;
  return out;
}

}  // namespace

std::string_view ExechonCheckResult::status() const {
  if (solver_status != "ok") return solver_status;
  return violations.empty() ? std::string_view("ok") : toString(violations.front().kind);
}

ExechonCheckResult checkConfiguration(const ExechonModel& model, ExechonData& data) {
  ExechonCheckResult out;
  out.readings = data.readings;
  for (int i = 0; i < kExechonLegs; ++i) {
    const ExechonLeg& leg = model.legs[static_cast<std::size_t>(i)];
    const double q = data.readings[i];
    out.stroke_margin[i] = std::min(q - leg.min_reading, leg.max_reading - q);
    if (out.stroke_margin[i] < 0.0)
      out.violations.push_back({LimitKind::kStroke,
                                kLegNames[i],
                                q,
                                q < leg.min_reading ? leg.min_reading : leg.max_reading,
                                out.stroke_margin[i]});
  }
  for (int i = 0; i < kExechonLegs; ++i)
    if (!(data.lengths[i] > 0.0))
      out.violations.push_back({LimitKind::kDegenerate, kLegNames[i], 0.0, 0.0, 0.0});
  out.alpha = data.e[0];
  out.beta = data.e[1];
  out.c = data.c;
  out.a = data.a;
  out.wrist_at_pole = data.wrist_at_pole;
  checkRange(model.limits.alpha, out.alpha, "alpha", out.alpha_margin, out.violations);
  checkRange(model.limits.beta, out.beta, "beta", out.beta_margin, out.violations);
  checkRange(model.limits.c, out.c, "wrist C", out.c_margin, out.violations);
  checkRange(model.limits.a, out.a, "wrist A", out.a_margin, out.violations);
  computeTripodJacobian(model, data);
  out.condition_number = tripodConditionNumber(data);
  out.condition_margin = model.max_condition - out.condition_number;
  if (!(out.condition_margin >= 0.0))
    out.violations.push_back({LimitKind::kSingular,
                              "jacobian",
                              out.condition_number,
                              model.max_condition,
                              out.condition_margin});
  return out;
}

ExechonCheckResult checkToolPose(const ExechonModel& model,
                                 ExechonData& data,
                                 const ExechonToolPose& target) {
  const ExechonIkStatus status = toolInverseKinematics(model, data, target);
  return status == ExechonIkStatus::kOk ? checkConfiguration(model, data)
                                        : failed(toString(status));
}

ExechonCheckResult checkToolPose(const ExechonModel& model,
                                 ExechonData& data,
                                 const ExechonToolPose& target,
                                 const ExechonConfiguration& previous) {
  const ExechonIkStatus status = toolInverseKinematics(model, data, target, previous);
  return status == ExechonIkStatus::kOk ? checkConfiguration(model, data)
                                        : failed(toString(status));
}

ExechonCheckResult checkJoints(const ExechonModel& model,
                               ExechonData& data,
                               const ExechonJoints& joints,
                               const ExechonConfiguration& seed,
                               const FkOptions& options) {
  const FkSummary summary = toolForwardKinematics(model, data, joints, seed, options);
  return summary.ok() ? checkConfiguration(model, data) : failed(toString(summary.status));
}

}  // namespace pkm::kinematics
