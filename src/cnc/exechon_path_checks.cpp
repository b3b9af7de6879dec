#include "pkm/cnc/exechon_path_checks.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"

namespace pkm::cnc {
namespace {
namespace kin = kinematics;

CheckStat& stat(PathCheckReport& r, PathCheck c) { return r.stats[static_cast<std::size_t>(c)]; }

/// The nearest limit of a range to `value`.
double nearerEnd(const kin::AngleRange& range, double value) {
  return value - range.min < range.max - value ? range.min : range.max;
}

void recordConfiguration(PathCheckReport& r,
                         const kin::ExechonModel& model,
                         const PathPoint& p,
                         const kin::ExechonData& data,
                         const kin::ExechonCheckResult& c) {
  int leg = 0;
  c.stroke_margin.minCoeff(&leg);
  const auto& l = model.legs[static_cast<std::size_t>(leg)];
  const double q = c.readings[leg];
  recordCheck(stat(r, PathCheck::kStroke),
              p,
              exechonJointName(leg),
              q,
              q - l.min_reading < l.max_reading - q ? l.min_reading : l.max_reading,
              c.stroke_margin[leg]);
  const std::array<const char*, 4> names{"alpha", "beta", "wrist C", "wrist A"};
  const std::array<double, 4> values{c.alpha, c.beta, c.c, c.a};
  const std::array<double, 4> margins{c.alpha_margin, c.beta_margin, c.c_margin, c.a_margin};
  const std::array<const kin::AngleRange*, 4> ranges{
      &model.limits.alpha, &model.limits.beta, &model.limits.c, &model.limits.a};
  std::size_t k = 0;
  for (std::size_t i = 1; i < 4; ++i)
    if (!(margins[k] <= margins[i])) k = i;
  recordCheck(stat(r, PathCheck::kJointAngle),
              p,
              names[k],
              values[k],
              nearerEnd(*ranges[k], values[k]),
              margins[k]);
  recordCheck(stat(r, PathCheck::kSingular),
              p,
              "jacobian",
              c.condition_number,
              model.max_condition,
              c.condition_margin);
  int d = 0;
  const double shortest = data.lengths.minCoeff(&d);
  recordCheck(stat(r, PathCheck::kDegenerate),
              p,
              exechonJointName(d),
              shortest,
              0.0,
              shortest > 0.0 ? shortest : -1.0);
}

}  // namespace

JointRateLimits exechonRateLimits(const MotionLimits& legs,
                                  double wrist_velocity,
                                  double wrist_acceleration) {
  legs.validate();
  PKM_CHECK(std::isfinite(wrist_velocity) && wrist_velocity > 0.0,
            "wrist velocity limit must be > 0 (got {})",
            wrist_velocity);
  PKM_CHECK(std::isfinite(wrist_acceleration) && wrist_acceleration > 0.0,
            "wrist acceleration limit must be > 0 (got {})",
            wrist_acceleration);
  JointRateLimits r = JointRateLimits::uniform(legs);
  r.max_velocity.tail<3>() << wrist_velocity, wrist_velocity,
      std::numeric_limits<double>::infinity();
  r.max_acceleration.tail<3>() << wrist_acceleration, wrist_acceleration,
      std::numeric_limits<double>::infinity();
  return r;
}

std::string exechonJointName(int joint) {
  static constexpr std::array<const char*, 6> kNames{
      "leg A", "leg B", "leg C", "wrist C", "wrist A", "unused"};
  PKM_CHECK(joint >= 0 && joint < 6, "joint index {} out of range", joint);
  return kNames[static_cast<std::size_t>(joint)];
}

PathCheckReport checkExechonPath(const kin::ExechonModel& model,
                                 const std::vector<PathPoint>& points,
                                 const std::vector<ExechonPathSample>& samples,
                                 const JointRateLimits& limits,
                                 std::size_t keep_violations) {
  limits.validate();
  PKM_CHECK(
      points.size() == samples.size(), "{} points but {} samples", points.size(), samples.size());
  PathCheckReport r;
  r.points = points.size();
  for (CheckStat& st : r.stats) st.keep = keep_violations;
  stat(r, PathCheck::kReach).enabled = true;
  kin::ExechonData data(model);
  std::vector<kin::StrutVector> q(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ExechonPathSample& s = samples[i];
    q[i] = s.joints;
    if (!s.ok()) {
      recordCheck(
          stat(r, PathCheck::kReach), points[i], std::string(kin::toString(s.status)), 0, 0, -1);
      continue;
    }
    kin::evaluateConfiguration(model, data, s.config);
    const kin::ExechonCheckResult c = kin::checkConfiguration(model, data);
    recordConfiguration(r, model, points[i], data, c);
  }
  checkJointRates(points, q, limits, exechonJointName, r);
  return r;
}

}  // namespace pkm::cnc
