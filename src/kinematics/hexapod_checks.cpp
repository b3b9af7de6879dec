#include "pkm/kinematics/hexapod_checks.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "pkm/geometry/segment_distance.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::kinematics {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Angle (rad) between unit vector u and the (not necessarily unit) cone axis.
double angleTo(const Eigen::Vector3d& u, const Eigen::Vector3d& axis) {
  return std::atan2(u.cross(axis).norm(), u.dot(axis));
}

/// The stroke margin of each strut and the angles and margins of its joints (rad) into `out`
/// (out.readings set, `data` at the pose): violations of the strokes and degenerate struts first,
/// then those of the joint cones.
void checkHexapodStruts(const HexapodModel& model,
                        const HexapodData& data,
                        HexapodCheckResult& out) {
  std::vector<LimitViolation> angle_violations;

  for (int i = 0; i < kStruts; ++i) {
    const Strut& s = model.struts[static_cast<std::size_t>(i)];
    const double q = out.readings[i];
    out.stroke_margin[i] = std::min(q - s.min_reading, s.max_reading - q);
    if (out.stroke_margin[i] < 0.0) {
      const double limit = q < s.min_reading ? s.min_reading : s.max_reading;
      out.violations.push_back(
          {LimitKind::kStroke, fmt::format("strut {}", i), q, limit, out.stroke_margin[i]});
    }
    if (data.joint_distance[i] <= 0.0) {
      out.violations.push_back({LimitKind::kDegenerate, fmt::format("strut {}", i), 0.0, 0.0, 0.0});
      out.base_angle[i] = out.platform_angle[i] = 0.0;
      out.base_angle_margin[i] = out.platform_angle_margin[i] = kInf;
      continue;
    }
    const Eigen::Vector3d& u = data.unit_leg[static_cast<std::size_t>(i)];
    out.base_angle[i] = angleTo(u, s.base_cone.axis);
    out.platform_angle[i] = angleTo(u, data.world_R_platform * s.platform_cone.axis);
    const auto margin = [](const JointCone& c, double angle) {
      return c.max_angle > 0.0 ? c.max_angle - angle : kInf;
    };
    out.base_angle_margin[i] = margin(s.base_cone, out.base_angle[i]);
    out.platform_angle_margin[i] = margin(s.platform_cone, out.platform_angle[i]);
    if (out.base_angle_margin[i] < 0.0)
      angle_violations.push_back({LimitKind::kJointAngle,
                                  fmt::format("base joint {}", i),
                                  out.base_angle[i],
                                  s.base_cone.max_angle,
                                  out.base_angle_margin[i]});
    if (out.platform_angle_margin[i] < 0.0)
      angle_violations.push_back({LimitKind::kJointAngle,
                                  fmt::format("platform joint {}", i),
                                  out.platform_angle[i],
                                  s.platform_cone.max_angle,
                                  out.platform_angle_margin[i]});
  }
  out.violations.insert(out.violations.end(), angle_violations.begin(), angle_violations.end());
}

/// The smallest distance between the legs' joint-centre segments and its margin to the strut
/// diameter into `out`, with an interference violation when it is negative.
void checkHexapodLegDistance(const HexapodModel& model,
                             const HexapodData& data,
                             HexapodCheckResult& out) {
  // Leg-to-leg distance between joint-centre segments; pairs that share a joint are skipped because
  // their axes always meet at the joint.
  out.min_leg_distance = kInf;
  const double d = model.strut_diameter;
  for (int i = 0; i < kStruts; ++i) {
    for (int j = i + 1; j < kStruts; ++j) {
      const Eigen::Vector3d bi = model.effectiveBase(i), bj = model.effectiveBase(j);
      const auto& pi = data.world_p_platform_joint[static_cast<std::size_t>(i)];
      const auto& pj = data.world_p_platform_joint[static_cast<std::size_t>(j)];
      const double share_tol = std::max(d, 1e-9 * (bi.norm() + pi.norm()));
      if ((bi - bj).norm() <= share_tol || (pi - pj).norm() <= share_tol) {
        ++out.unchecked_pairs;
        continue;
      }
      const double dist = geometry::segmentDistance(bi, pi, bj, pj).distance;
      if (dist < out.min_leg_distance) {
        out.min_leg_distance = dist;
        out.closest_pair[0] = i;
        out.closest_pair[1] = j;
      }
    }
  }
  out.interference_margin = d > 0.0 ? out.min_leg_distance - d : kInf;
  if (out.interference_margin < 0.0)
    out.violations.push_back({LimitKind::kInterference,
                              fmt::format("struts {}-{}", out.closest_pair[0], out.closest_pair[1]),
                              out.min_leg_distance,
                              d,
                              out.interference_margin});
}
}  // namespace

std::string_view toString(LimitKind kind) {
  switch (kind) {
    case LimitKind::kStroke:
      return "stroke";
    case LimitKind::kJointAngle:
      return "joint_angle";
    case LimitKind::kInterference:
      return "interference";
    case LimitKind::kSingular:
      return "singular";
    case LimitKind::kDegenerate:
      return "degenerate";
  }
  return "unknown";
}

std::string_view HexapodCheckResult::status() const {
  return violations.empty() ? std::string_view("ok") : toString(violations.front().kind);
}

HexapodCheckResult checkPose(const HexapodModel& model, HexapodData& data, const PoseRpy& pose) {
  HexapodCheckResult out;
  out.readings = inverseKinematics(model, data, pose);
  checkHexapodStruts(model, data, out);
  checkHexapodLegDistance(model, data, out);
  computeStrutJacobian(model, data);
  out.condition_number = scaledConditionNumber(model, data);
  out.condition_margin = model.max_condition - out.condition_number;
  if (!(out.condition_margin >= 0.0))
    out.violations.push_back({LimitKind::kSingular,
                              "jacobian",
                              out.condition_number,
                              model.max_condition,
                              out.condition_margin});
  return out;
}

}  // namespace pkm::kinematics
