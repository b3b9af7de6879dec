#include "pkm/cnc/joint_checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "pkm/cnc/joint_path.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_data.hpp"

namespace pkm::cnc {

void recordCheck(CheckStat& s,
                 const PathPoint& p,
                 std::string item,
                 double value,
                 double limit,
                 double margin,
                 double rank) {
  if (!std::isfinite(margin) && margin > 0.0) return;  // disabled limit
  if (std::isnan(rank)) rank = margin;
  s.enabled = true;
  const bool violated = !(margin >= 0.0);
  if (violated) ++s.violations;
  const bool worse = !(s.worst_rank <= rank);
  const bool kept = violated && s.events.size() < s.keep;
  if (!worse && !(violated && s.violations == 1) && !kept) return;
  CheckEvent e{p.line, p.pos, std::move(item), value, limit, margin};
  if (kept) s.events.push_back(e);
  if (violated && s.violations == 1) s.first = e;
  if (worse) {
    s.worst = std::move(e);
    s.worst_rank = rank;
  }
}

namespace {
constexpr std::size_t idx(PathCheck c) { return static_cast<std::size_t>(c); }

void record(
    CheckStat& s, const PathPoint& p, std::string item, double value, double limit, double margin) {
  recordCheck(s, p, std::move(item), value, limit, margin);
}

/// Index of the smallest coefficient.
int argmin(const kinematics::StrutVector& v) {
  int i = 0;
  v.minCoeff(&i);
  return i;
}

void recordPose(PathCheckReport& r,
                const kinematics::HexapodModel& model,
                const PathPoint& p,
                const kinematics::HexapodCheckResult& c) {
  auto& st = r.stats;
  const int s = argmin(c.stroke_margin);
  const auto& strut = model.struts[static_cast<std::size_t>(s)];
  const double q = c.readings(s);
  record(st[idx(PathCheck::kStroke)],
         p,
         fmt::format("strut {}", s),
         q,
         q - strut.min_reading < strut.max_reading - q ? strut.min_reading : strut.max_reading,
         c.stroke_margin(s));
  const int b = argmin(c.base_angle_margin), pl = argmin(c.platform_angle_margin);
  if (c.base_angle_margin(b) <= c.platform_angle_margin(pl))
    record(st[idx(PathCheck::kJointAngle)],
           p,
           fmt::format("base joint {}", b),
           c.base_angle(b),
           model.struts[static_cast<std::size_t>(b)].base_cone.max_angle,
           c.base_angle_margin(b));
  else
    record(st[idx(PathCheck::kJointAngle)],
           p,
           fmt::format("platform joint {}", pl),
           c.platform_angle(pl),
           model.struts[static_cast<std::size_t>(pl)].platform_cone.max_angle,
           c.platform_angle_margin(pl));
  if (c.closest_pair[0] >= 0)
    record(st[idx(PathCheck::kInterference)],
           p,
           fmt::format("struts {}-{}", c.closest_pair[0], c.closest_pair[1]),
           c.min_leg_distance,
           model.strut_diameter,
           c.interference_margin);
  record(st[idx(PathCheck::kSingular)],
         p,
         "jacobian",
         c.condition_number,
         model.max_condition,
         c.condition_margin);
  // Degenerate: the shortest distance between a strut's joint centres (limit 0).
  kinematics::StrutVector dist;
  for (int i = 0; i < kinematics::kStruts; ++i)
    dist(i) = c.readings(i) + model.struts[static_cast<std::size_t>(i)].length_offset;
  const int d = argmin(dist);
  record(st[idx(PathCheck::kDegenerate)],
         p,
         fmt::format("strut {}", d),
         dist(d),
         0.0,
         dist(d) > 0.0 ? dist(d) : -1.0);
}

}  // namespace

std::string_view toString(PathCheck check) {
  switch (check) {
    case PathCheck::kReach:
      return "reach";
    case PathCheck::kStroke:
      return "stroke";
    case PathCheck::kJointAngle:
      return "joint_angle";
    case PathCheck::kInterference:
      return "interference";
    case PathCheck::kSingular:
      return "singular";
    case PathCheck::kDegenerate:
      return "degenerate";
    case PathCheck::kJointVelocity:
      return "joint_velocity";
    case PathCheck::kJointAcceleration:
      return "joint_acceleration";
  }
  return "?";
}

bool PathCheckReport::ok() const {
  return std::all_of(
      stats.begin(), stats.end(), [](const CheckStat& s) { return s.violations == 0; });
}

PathCheckReport checkPath(const kinematics::HexapodModel& model,
                          const std::vector<PathPoint>& points,
                          const std::vector<kinematics::StrutVector>& q,
                          const MotionLimits& limits,
                          std::size_t keep_violations) {
  limits.validate();
  PKM_CHECK(points.size() == q.size(), "{} points but {} joint vectors", points.size(), q.size());
  PathCheckReport r;
  r.points = points.size();
  for (CheckStat& st : r.stats) st.keep = keep_violations;
  r.stats[static_cast<std::size_t>(PathCheck::kReach)].enabled = true;  // closed-form IK
  kinematics::HexapodData data(model);
  for (const auto& p : points) {
    const kinematics::HexapodCheckResult c =
        kinematics::checkPose(model, data, poseFromAxes(p.pos, model.unit));
    recordPose(r, model, p, c);
  }
  checkJointRates(
      points,
      q,
      JointRateLimits::uniform(limits),
      [](int j) { return fmt::format("strut {}", j); },
      r);
  return r;
}

void checkJointRates(const std::vector<PathPoint>& points,
                     const std::vector<kinematics::StrutVector>& q,
                     const JointRateLimits& limits,
                     const std::function<std::string(int)>& joint_name,
                     PathCheckReport& report) {
  limits.validate();
  PKM_CHECK(points.size() == q.size(), "{} points but {} joint vectors", points.size(), q.size());
  auto& vel = report.stats[static_cast<std::size_t>(PathCheck::kJointVelocity)];
  auto& acc = report.stats[static_cast<std::size_t>(PathCheck::kJointAcceleration)];
  MotionLimits path;
  path.rapid_rate = limits.rapid_rate;
  const kinematics::StrutVector inv_v = limits.max_velocity.cwiseInverse();
  const kinematics::StrutVector inv_a = limits.max_acceleration.cwiseInverse();
  kinematics::StrutVector prev = kinematics::StrutVector::Zero();
  double prev_ds = 0.0;
  for (std::size_t k = 1; k < points.size(); ++k) {
    const double ds = segmentLength(points[k - 1].pos, points[k].pos);
    if (ds <= 0.0 || points[k].kind == MoveKind::kRapid) {  // no programmed feed for G0
      prev_ds = 0.0;
      continue;
    }
    const double v = programmedSpeed(points[k], path);
    const kinematics::StrutVector dqds = (q[k] - q[k - 1]) / ds;
    // The joint nearest its own limit (rates relative to each joint's limit).
    int j = 0;
    const double gv = dqds.cwiseAbs().cwiseProduct(inv_v).maxCoeff(&j);
    {
      const double rate = std::abs(dqds(j)) * v, lim = limits.max_velocity(j);
      recordCheck(vel, points[k], joint_name(j), rate, lim, lim - rate, 1.0 - gv * v);
    }
    if (prev_ds > 0.0 && points[k].move == points[k - 1].move) {
      const kinematics::StrutVector jump = (dqds - prev).cwiseAbs() / (0.5 * (ds + prev_ds));
      const double ga = jump.cwiseProduct(inv_a).maxCoeff(&j);
      const double rate = jump(j) * v * v, lim = limits.max_acceleration(j);
      recordCheck(acc, points[k - 1], joint_name(j), rate, lim, lim - rate, 1.0 - ga * v * v);
    }
    prev = dqds;
    prev_ds = ds;
  }
}

}  // namespace pkm::cnc
