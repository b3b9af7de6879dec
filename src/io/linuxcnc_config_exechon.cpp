// The LinuxCNC configuration of an Exechon with pkmexechonkins (io/linuxcnc_config.hpp).
#include <fmt/format.h>

#include <cmath>

#include "detail/linuxcnc_config_detail.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/linuxcnc_config.hpp"
#include "pkm/io/linuxcnc_exechon.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_ik.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"

namespace pkm::io {

namespace kin = pkm::kinematics;

namespace {

/// An angle range's ends in degrees, an open side as ±kOpenAngleLimit.
std::array<double, 2> degrees(const kin::AngleRange& r) {
  return {std::isfinite(r.min) ? radToDeg(r.min) : -detail::kOpenAngleLimit,
          std::isfinite(r.max) ? radToDeg(r.max) : detail::kOpenAngleLimit};
}

/// X, Y, Z: how far the tool point reaches from home along each coordinate, the wrist held and the
/// tripod followed by continuity, within every limit `pkm exechon check` applies.
std::vector<detail::IniAxis> toolPointAxes(const kin::ExechonModel& model,
                                           const kin::ExechonData& home,
                                           double velocity,
                                           double acceleration) {
  const double length = model.characteristicLength();
  std::vector<detail::IniAxis> axes;
  for (int k = 0; k < 3; ++k) {
    std::array<double, 2> side{};
    for (int s = 0; s < 2; ++s) {
      const double sign = s == 0 ? -1.0 : 1.0;
      kin::ExechonData data(model);
      Eigen::Vector3d e_last = home.e;
      double t_last = 0.0;
      side[static_cast<std::size_t>(s)] = detail::reach(
          [&](double t) {
            Eigen::Vector3d p = home.world_p_tool;
            p[k] += sign * t;
            if (kin::toolPointInverseKinematics(model, data, p, home.c, home.a, e_last) !=
                kin::ExechonIkStatus::kOk)
              return false;
            if (!kin::checkConfiguration(model, data).ok()) return false;
            if (t > t_last) t_last = t, e_last = data.e;
            return true;
          },
          detail::kTranslationCap * length);
    }
    const std::array<double, 2> lim =
        detail::axisLimits(home.world_p_tool[k], side[0], side[1], detail::limitStep(length));
    axes.push_back({"XYZ"[k], lim[0], lim[1], velocity, acceleration});
  }
  return axes;
}

}  // namespace

std::vector<NamedText> exechonLinuxcncConfig(const ExechonMachine& machine,
                                             const LinuxcncConfigOptions& options) {
  constexpr int kJoints = 5;
  options.validate(kJoints);
  const kin::ExechonModel& model = machine.model;
  kin::ExechonData home(model);
  kin::evaluateConfiguration(model, home, model.home);
  const kin::ExechonCheckResult at_home = kin::checkConfiguration(model, home);
  if (!at_home.ok()) {
    const kin::LimitViolation& v = at_home.violations.front();
    throw InvalidArgument(fmt::format(
        "{}: the home configuration is outside a limit ({} {}): LinuxCNC could not home it",
        machine.source,
        v.item,
        kin::toString(v.kind)));
  }
  const LinuxcncConfigNames names = linuxcncConfigNames(model.name);
  const std::optional<JointRateSpec>& rates = machine.joint_rates;
  auto rate = [&rates](double JointRateSpec::*field, double fallback) {
    return rates && std::isfinite((*rates).*field) ? (*rates).*field : fallback;
  };
  const double velocity = rate(&JointRateSpec::velocity, detail::kDefaultJointVelocity);
  const double acceleration = rate(&JointRateSpec::acceleration, detail::kDefaultJointAcceleration);
  const double wrist_velocity =
      rate(&JointRateSpec::wrist_velocity_deg, detail::kDefaultWristVelocityDeg);
  const double wrist_acceleration =
      rate(&JointRateSpec::wrist_acceleration_deg, detail::kDefaultWristAccelerationDeg);

  detail::IniSpec spec;
  spec.comment = fmt::format(
      "# LinuxCNC configuration of the Exechon {},\n# written by `pkm linuxcnc config` from {}.\n"
      "# Kinematics: pkm's component pkmexechonkins with the parameter file {}; a simulated\n"
      "# machine ({}). World X Y Z: the tool point `pkm exechon fk` reports ({}); world A, C: the\n"
      "# wrist readings (degrees); joints 0-2 the leg readings, 3 wrist C, 4 wrist A.\n"
      "# docs/linuxcnc.md, \"From `pkm linuxcnc config` to a running machine\".\n",
      model.name,
      machine.source,
      names.params,
      names.sim,
      toString(model.unit));
  spec.machine = model.name + " (pkm, pkmexechonkins)";
  spec.unit = model.unit;
  spec.kinematics = "pkmexechonkins params=" + names.params;
  const double c_home = radToDeg(home.c), a_home = radToDeg(home.a);
  spec.home = {
      home.world_p_tool.x(), home.world_p_tool.y(), home.world_p_tool.z(), a_home, 0.0, c_home};
  spec.axes = toolPointAxes(model, home, velocity, acceleration);
  const std::array<double, 2> c_range = degrees(model.limits.c), a_range = degrees(model.limits.a);
  spec.axes.push_back({'A', a_range[0], a_range[1], wrist_velocity, wrist_acceleration});
  spec.axes.push_back({'C', c_range[0], c_range[1], wrist_velocity, wrist_acceleration});
  const double open = 1e9 * model.characteristicLength();
  for (int i = 0; i < kin::kExechonLegs; ++i) {
    const kin::ExechonLeg& leg = model.legs[static_cast<std::size_t>(i)];
    spec.joints.push_back({false,
                           home.readings[i],
                           std::isfinite(leg.min_reading) ? leg.min_reading : -open,
                           std::isfinite(leg.max_reading) ? leg.max_reading : open,
                           velocity,
                           acceleration});
  }
  spec.joints.push_back({true, c_home, c_range[0], c_range[1], wrist_velocity, wrist_acceleration});
  spec.joints.push_back({true, a_home, a_range[0], a_range[1], wrist_velocity, wrist_acceleration});
  spec.linear_velocity = velocity;
  spec.linear_acceleration = acceleration;
  spec.angular_velocity = wrist_velocity;

  const std::string kinematics = fmt::format(
      "# The kinematics: pkm's Exechon component, its parameters read from {} at load\n"
      "# ([KINS] KINEMATICS; the name is relative to this folder, where LinuxCNC runs).\n"
      "loadrt [KINS]KINEMATICS\n",
      names.params);
  return {{names.ini, detail::linuxcncIni(spec, names, options)},
          {names.kinematics, kinematics},
          {names.sim, detail::simulatorHal(kJoints, "pkmexechonkins.tool-offset")},
          {names.tool_table, detail::toolTable(model.unit)},
          {names.params, linuxcncExechonParameters(machine)}};
}

}  // namespace pkm::io
