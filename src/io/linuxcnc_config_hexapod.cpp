// The LinuxCNC configuration of a hexapod with pkmhexkins (io/linuxcnc_config.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "detail/linuxcnc_config_detail.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/linuxcnc_config.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/linuxcnc_hexapod_params.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_clearance.hpp"
#include "pkm/kinematics/hexapod_data.hpp"

namespace pkm::io {

namespace kin = pkm::kinematics;

namespace {

/// Largest rotations (degrees) the axis limits search (translations: detail::kTranslationCap).
constexpr std::array<double, 3> kRotationCapDeg{90.0, 90.0, 180.0};
constexpr double kAngleStepDeg = 0.01;

/// A pose the axis limits may reach: every limit `pkm hexapod check` applies holds, every
/// platform joint stays kClearanceFraction characteristic lengths above the base plane (the
/// singular plane, beyond which lies the mirror assembly), and the strut Jacobian's determinant
/// has home's sign (no singular configuration lies between home and the pose on that count;
/// pkmhexkins refuses a pose of the other sign).
struct PoseAdmissible {
  const kin::HexapodModel& model;
  kin::HexapodData& data;
  kin::BasePlane plane;
  double margin;
  int home_branch;
  bool operator()(const kin::PoseRpy& pose) const {
    return kin::platformClearance(model, plane, pose) >= margin &&
           kin::assemblyBranch(model, data, pose) == home_branch &&
           kin::checkPose(model, data, pose).ok();
  }
};

/// The pose of world coordinates X Y Z A B C (degrees).
kin::PoseRpy poseOf(const std::array<double, 6>& w) {
  kin::PoseRpy pose;
  pose.position = {w[0], w[1], w[2]};
  pose.rpy = {degToRad(w[3]), degToRad(w[4]), degToRad(w[5])};
  return pose;
}

/// The box's 64 corners all admissible.
bool cornersAdmissible(const PoseAdmissible& ok, const std::vector<detail::IniAxis>& axes) {
  for (int mask = 0; mask < 64; ++mask) {
    std::array<double, 6> w{};
    for (std::size_t k = 0; k < 6; ++k) w[k] = (mask >> k) & 1 ? axes[k].max : axes[k].min;
    if (!ok(poseOf(w))) return false;
  }
  return true;
}

/// The axes with each side's reach scaled by `s` and rounded towards home.
std::vector<detail::IniAxis> scaledAxes(const std::vector<detail::IniAxis>& reach,
                                        const std::array<double, 6>& home,
                                        double length,
                                        double s) {
  std::vector<detail::IniAxis> axes = reach;
  for (std::size_t k = 0; k < 6; ++k) {
    const double step = k >= 3 ? kAngleStepDeg : detail::limitStep(length);
    const std::array<double, 2> lim = detail::axisLimits(
        home[k], s * (home[k] - reach[k].min), s * (reach[k].max - home[k]), step);
    axes[k].min = lim[0];
    axes[k].max = lim[1];
  }
  return axes;
}

/// The world axes: how far the machine reaches from home along each coordinate (min/max = home ∓
/// the reach, unrounded), every limit of PoseAdmissible held.
std::vector<detail::IniAxis> hexapodReach(const kin::HexapodModel& model,
                                          const PoseAdmissible& ok,
                                          const std::array<double, 6>& home,
                                          double velocity,
                                          double acceleration) {
  const double length = model.characteristicLength();
  std::vector<detail::IniAxis> axes;
  for (int k = 0; k < 6; ++k) {
    const bool angular = k >= 3;
    const double cap = angular ? kRotationCapDeg[static_cast<std::size_t>(k - 3)]
                               : detail::kTranslationCap * length;
    std::array<double, 2> side{};
    for (int s = 0; s < 2; ++s) {
      const double sign = s == 0 ? -1.0 : 1.0;
      side[static_cast<std::size_t>(s)] = detail::reach(
          [&](double t) {
            kin::PoseRpy pose = model.home;
            if (angular)
              pose.rpy[k - 3] += degToRad(sign * t);
            else
              pose.position[k] += sign * t;
            return ok(pose);
          },
          cap);
    }
    const double h = home[static_cast<std::size_t>(k)];
    const double rate = angular ? radToDeg(1.0 / length) : 1.0;
    axes.push_back({"XYZABC"[k], h - side[0], h + side[1], velocity * rate, acceleration * rate});
  }
  return axes;
}

/// The axis limits: each axis's reach alone, rounded towards home, then all six shrunk together
/// (the largest common fraction of the reach, found by bisection to 1/1024) until every corner of
/// the box is admissible; a notice says by how much when they shrank.
std::vector<detail::IniAxis> hexapodAxes(const kin::HexapodModel& model,
                                         const std::array<double, 6>& home,
                                         double velocity,
                                         double acceleration,
                                         std::vector<std::string>* notices) {
  const double length = model.characteristicLength();
  kin::HexapodData data(model);
  const kin::BasePlane plane = kin::basePlane(model);
  const double at_home = kin::platformClearance(model, plane, model.home);
  if (!(at_home > 0.0))
    throw InvalidArgument(fmt::format(
        "{}: the home pose puts a platform joint {} {} from the base plane: a singular or mirror "
        "pose, LinuxCNC could not home the machine",
        model.name,
        formatNumber(at_home),
        toString(model.unit)));
  // The margin: a tenth of the characteristic length, less for a home closer to the plane.
  const int home_branch = kin::assemblyBranch(model, data, model.home);
  if (home_branch == 0)
    throw InvalidArgument(fmt::format(
        "{}: the home pose is singular (strut Jacobian of rank < 6): LinuxCNC could not home "
        "the machine",
        model.name));
  const PoseAdmissible ok{model,
                          data,
                          plane,
                          std::min(kin::kMirrorClearanceFraction * length, 0.5 * at_home),
                          home_branch};
  const std::vector<detail::IniAxis> reach = hexapodReach(model, ok, home, velocity, acceleration);
  std::vector<detail::IniAxis> axes = scaledAxes(reach, home, length, 1.0);
  if (cornersAdmissible(ok, axes)) return axes;
  double good = 0.0, bad = 1.0;
  while (bad - good > 1.0 / 1024.0) {
    const double mid = 0.5 * (good + bad);
    (cornersAdmissible(ok, scaledAxes(reach, home, length, mid)) ? good : bad) = mid;
  }
  axes = scaledAxes(reach, home, length, good);
  if (notices != nullptr)
    notices->push_back(fmt::format(
        "axis limits shrunk to {:.1f} % of each axis's reach from home, so that every corner of "
        "the X Y Z A B C limit box is within the strokes, joint cones, interference and "
        "conditioning limits, on home's assembly branch and {} {} above the base plane (no "
        "singular or mirror pose)",
        100.0 * good,
        fmt::format("{:.3g}", ok.margin),
        toString(model.unit)));
  return axes;
}
}  // namespace

std::vector<NamedText> hexapodLinuxcncConfig(const HexapodMachine& machine,
                                             const LinuxcncConfigOptions& options,
                                             std::vector<std::string>* notices) {
  options.validate(kin::kStruts);
  const kin::HexapodModel& model = machine.model;
  kin::HexapodData data(model);
  const kin::HexapodCheckResult at_home = kin::checkPose(model, data, model.home);
  for (const kin::LimitViolation& v : at_home.violations)
    if (v.kind == kin::LimitKind::kStroke || v.kind == kin::LimitKind::kDegenerate)
      throw InvalidArgument(fmt::format(
          "{}: the home pose puts {} at {} ({}, limit {}): LinuxCNC could not home the machine",
          machine.source,
          v.item,
          formatNumber(v.value),
          kin::toString(v.kind),
          formatNumber(v.limit)));
  const LinuxcncConfigNames names = linuxcncConfigNames(model.name);
  const double velocity = machine.joint_rates && std::isfinite(machine.joint_rates->velocity)
                              ? machine.joint_rates->velocity
                              : detail::kDefaultJointVelocity;
  const double acceleration =
      machine.joint_rates && std::isfinite(machine.joint_rates->acceleration)
          ? machine.joint_rates->acceleration
          : detail::kDefaultJointAcceleration;

  detail::IniSpec spec;
  spec.comment = fmt::format(
      "# LinuxCNC configuration of the hexapod {},\n# written by `pkm linuxcnc config` from {}.\n"
      "# Kinematics: pkm's component pkmhexkins with the parameter file {}; a simulated\n"
      "# machine ({}).\n"
      "# World X Y Z A B C: the pose `pkm hexapod fk` reports for this machine ({}, degrees);\n"
      "# joints 0-5: the strut readings. docs/linuxcnc.md, \"From `pkm linuxcnc config` to a\n"
      "# running machine\".\n",
      model.name,
      machine.source,
      names.params,
      names.sim,
      toString(model.unit));
  spec.machine = model.name + " (pkm, pkmhexkins)";
  spec.unit = model.unit;
  spec.kinematics = "pkmhexkins params=" + names.params;
  spec.home = {model.home.position.x(),
               model.home.position.y(),
               model.home.position.z(),
               radToDeg(model.home.rpy.x()),
               radToDeg(model.home.rpy.y()),
               radToDeg(model.home.rpy.z())};
  spec.axes = hexapodAxes(model, spec.home, velocity, acceleration, notices);
  const double open = 1e9 * model.characteristicLength();
  for (const PkmhexkinsJointValues& j : pkmhexkinsJointValues(machine))
    spec.joints.push_back({false,
                           j.home,
                           j.min_limit.value_or(-open),
                           j.max_limit.value_or(open),
                           velocity,
                           acceleration});
  spec.linear_velocity = velocity;
  spec.linear_acceleration = acceleration;
  spec.angular_velocity = spec.axes[3].velocity;

  const std::string kinematics = fmt::format(
      "# The kinematics: pkm's hexapod component, its geometry, home and solver settings read\n"
      "# from {} at load ([KINS] KINEMATICS; the name is relative to this folder, where\n"
      "# LinuxCNC runs): a file that is missing a value or does not assemble stops LinuxCNC\n"
      "# there, with the reason in its log. The pins (docs/linuxcnc.md) start at the file's\n"
      "# values; a setp after this line would override it.\n"
      "loadrt [KINS]KINEMATICS\n",
      names.params);
  return {{names.ini, detail::linuxcncIni(spec, names, options)},
          {names.kinematics, kinematics},
          {names.sim, detail::simulatorHal(kin::kStruts, "pkmhexkins.tool-offset")},
          {names.tool_table, detail::toolTable(model.unit)},
          {names.params, linuxcncHexapodParameters(machine)}};
}

}  // namespace pkm::io
