// Poses checked one by one for a front end that draws the machine (workflow/pose_checks.hpp).
#include "pkm/workflow/pose_checks.hpp"

#include <fmt/format.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/kinematics/pose_rpy.hpp"
#include "pkm/workflow/kinematics_path.hpp"
#include "pose_rows.hpp"

namespace pkm::workflow {
namespace {

namespace kin = pkm::kinematics;

WorldPoint point(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// A margin in degrees (an angle in rad; +infinity stays).
double degrees(double rad) { return std::isinf(rad) ? rad : radToDeg(rad); }

/// "KIND ITEM value V limit L" with angles in degrees.
std::string describe(const kin::LimitViolation& v) {
  const bool angle = v.kind == kin::LimitKind::kJointAngle;
  return fmt::format("{} {} value {:.6g} limit {:.6g}",
                     kin::toString(v.kind),
                     v.item,
                     angle ? radToDeg(v.value) : v.value,
                     angle ? radToDeg(v.limit) : v.limit);
}

PoseCheckRow exechonRow(const io::ExechonMachine& machine,
                        ExechonPosePath& path,
                        const std::array<double, 6>& p) {
  kin::ExechonToolPose tool;
  tool.position = {p[0], p[1], p[2]};
  tool.direction = Eigen::Vector3d(p[3], p[4], p[5]).normalized();
  const ExechonPoseStep step = path.solve(tool);
  if (!step.solved) {
    PoseCheckRow row;
    row.status = std::string(step.status);
    return row;
  }
  PoseCheckRow row = detail::exechonDataRow(machine.model, path.data(), step.check);
  if (machine.hybrid) row.carriage = {step.command.x2, step.command.y2};
  return row;
}

}  // namespace

namespace detail {

PoseCheckRow hexapodPoseRow(const kin::HexapodModel& m,
                            kin::HexapodData& data,
                            const kin::PoseRpy& pose) {
  const kin::HexapodCheckResult c = kin::checkPose(m, data, pose);
  PoseCheckRow row;
  row.status = std::string(c.status());
  for (int i = 0; i < kin::kStruts; ++i) {
    row.joints.push_back(c.readings[i]);
    row.stroke_margin.push_back(c.stroke_margin[i]);
    row.angle_margin.push_back(
        degrees(std::min(c.base_angle_margin[i], c.platform_angle_margin[i])));
    row.base_points.push_back(point(m.effectiveBase(i)));
    row.moving_points.push_back(
        point(pose.position + data.world_r_joint[static_cast<std::size_t>(i)]));
  }
  if (c.closest_pair[0] >= 0) {
    row.clearance = c.interference_margin;
    row.closest_pair = {c.closest_pair[0], c.closest_pair[1]};
  }
  row.condition_number = c.condition_number;
  row.condition_margin = c.condition_margin;
  for (const kin::LimitViolation& v : c.violations) row.violations.push_back(describe(v));
  const Eigen::Matrix3d R = kin::toRigidTransform(pose).linear();
  row.tool_point = point(pose.position);
  row.tool_direction = point(R.col(2));
  return row;
}

PoseCheckRow exechonDataRow(const kin::ExechonModel& model,
                            const kin::ExechonData& d,
                            const kin::ExechonCheckResult& c) {
  PoseCheckRow row;
  row.status = std::string(c.status());
  for (int i = 0; i < 3; ++i) {
    row.joints.push_back(d.readings[i]);
    row.stroke_margin.push_back(c.stroke_margin[i]);
  }
  row.joints.push_back(radToDeg(d.c));
  row.joints.push_back(radToDeg(d.a));
  row.angle_margin = {
      degrees(c.alpha_margin), degrees(c.beta_margin), degrees(c.c_margin), degrees(c.a_margin)};
  row.condition_number = c.condition_number;
  row.condition_margin = c.condition_margin;
  for (const kin::LimitViolation& v : c.violations) row.violations.push_back(describe(v));
  for (std::size_t i = 0; i < 3; ++i) {
    row.base_points.push_back(point(model.world_T_zoppi * d.zoppi_p_base[i]));
    row.moving_points.push_back(point(model.world_T_zoppi * d.zoppi_p_platform_joint[i]));
  }
  row.wrist_points.push_back(point(d.world_p_S));
  row.tool_point = point(d.world_p_tool);
  row.tool_direction = point(d.world_u_tool);
  return row;
}

}  // namespace detail

namespace {}  // namespace

PoseCheckRow checkHexapodPose(const kin::HexapodModel& model,
                              kin::HexapodData& data,
                              const std::array<double, 6>& p) {
  kin::PoseRpy pose;
  pose.position = {p[0], p[1], p[2]};
  pose.rpy = Eigen::Vector3d(degToRad(p[3]), degToRad(p[4]), degToRad(p[5]));
  return detail::hexapodPoseRow(model, data, pose);
}

void PoseCheckRequest::validate() const {
  PKM_CHECK(!poses.empty(), "no poses to check");
  PKM_CHECK(poses.size() <= kMaxPoseChecks,
            "{} poses: at most {} per request",
            poses.size(),
            kMaxPoseChecks);
  for (std::size_t i = 0; i < poses.size(); ++i)
    for (double v : poses[i])
      PKM_CHECK(std::isfinite(v), "pose {}: a value is not a finite number", i);
}

std::array<double, 6> homePose(const std::string& machine, const std::string& ini) {
  if (io::machineTypeOf(machine) == "exechon") {
    const io::ExechonMachine m = io::loadExechonMachine(machine);
    kin::ExechonData data(m.model);
    kin::evaluateConfiguration(m.model, data, m.model.home);
    const Eigen::Vector3d& p = data.world_p_tool;
    const Eigen::Vector3d& u = data.world_u_tool;
    return {p.x(), p.y(), p.z(), u.x(), u.y(), u.z()};
  }
  io::HalReadOptions hal;
  if (!ini.empty()) hal.ini_path = ini;
  const kin::PoseRpy h = io::loadHexapodMachine(machine, hal).model.home;
  return {h.position.x(),
          h.position.y(),
          h.position.z(),
          radToDeg(h.rpy.x()),
          radToDeg(h.rpy.y()),
          radToDeg(h.rpy.z())};
}

PoseCheckResult checkPoses(const PoseCheckRequest& request) {
  request.validate();
  PoseCheckResult r;
  if (io::machineTypeOf(request.machine) == "exechon") {
    const io::ExechonMachine machine = io::loadExechonMachine(request.machine);
    r.machine = machine.model.name;
    r.machine_type = "exechon";
    r.units = std::string(toString(machine.model.unit));
    r.joint_names = {"leg A", "leg B", "leg C", "wrist C", "wrist A"};
    ExechonPosePath path(machine);
    for (const auto& p : request.poses) {
      PKM_CHECK(Eigen::Vector3d(p[3], p[4], p[5]).norm() > 0.0, "a tool direction is zero");
      r.rows.push_back(exechonRow(machine, path, p));
    }
    return r;
  }
  io::HalReadOptions hal;
  if (!request.ini.empty()) hal.ini_path = request.ini;
  const io::HexapodMachine machine = io::loadHexapodMachine(request.machine, hal);
  r.machine = machine.model.name;
  r.machine_type = "hexapod";
  r.units = std::string(toString(machine.model.unit));
  for (int i = 0; i < kin::kStruts; ++i) r.joint_names.push_back(fmt::format("strut {}", i));
  kin::HexapodData data(machine.model);
  for (const auto& p : request.poses) r.rows.push_back(checkHexapodPose(machine.model, data, p));
  return r;
}

}  // namespace pkm::workflow
