// The LinuxCNC pkmhexkins `setp` block of a hexapod and its joints' INI values
// (io/linuxcnc_hal.hpp; docs/linuxcnc.md, "The pkmhexkins kinematics component").
#include <fmt/format.h>

#include <cmath>

#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::io {

namespace kin = pkm::kinematics;

std::array<PkmhexkinsJointValues, 6> pkmhexkinsJointValues(const HexapodMachine& machine) {
  const kin::HexapodModel& m = machine.model;
  kin::HexapodData data(m);
  kin::inverseKinematics(m, data, m.home);
  std::array<PkmhexkinsJointValues, 6> out;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const kin::Strut& s = m.struts[i];
    out[i].home = data.readings[static_cast<Eigen::Index>(i)];
    if (std::isfinite(s.min_reading)) out[i].min_limit = s.min_reading;
    if (std::isfinite(s.max_reading)) out[i].max_limit = s.max_reading;
  }
  return out;
}

std::string writePkmhexkinsSetp(const HexapodMachine& machine) {
  const kin::HexapodModel& model = machine.model;
  std::string out = fmt::format(
      "# pkmhexkins geometry written by pkm from {}\n# machine: {}, units: {}\n"
      "# Pins: docs/linuxcnc.md, \"The pkmhexkins kinematics component\". Load the module first\n"
      "# (loadrt pkmhexkins); net pkmhexkins.tool-offset to motion.tooloffset.z for G43.\n",
      machine.source,
      model.name,
      toString(model.unit));
  auto setp = [&out](const std::string& pin, double v) {
    out += "setp pkmhexkins." + pin + " ";
    appendNumber(out, v);
    out += '\n';
  };
  static constexpr std::array<const char*, 3> kXyz{"x", "y", "z"};
  out += "\n# Base joint centres b_i, world frame\n";
  for (std::size_t i = 0; i < model.struts.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k)
      setp(fmt::format("base.{}.{}", i, kXyz[k]),
           model.struts[i].world_p_base[static_cast<Eigen::Index>(k)]);
  out += "\n# Platform joint centres a_i, platform frame\n";
  for (std::size_t i = 0; i < model.struts.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k)
      setp(fmt::format("platform.{}.{}", i, kXyz[k]),
           model.struts[i].platform_p_joint[static_cast<Eigen::Index>(k)]);
  out += "\n# Strut length offsets: reading (joint position) + offset = joint-centre distance\n";
  for (std::size_t i = 0; i < model.struts.size(); ++i)
    setp(fmt::format("length-offset.{}", i), model.struts[i].length_offset);
  out += "\n# The controlled point (tool point) in the platform frame, and the spindle offset\n";
  for (std::size_t k = 0; k < 3; ++k)
    setp(fmt::format("tool.{}", kXyz[k]), model.tool_offset[static_cast<Eigen::Index>(k)]);
  setp("spindle-offset", model.spindle_offset);
  out +=
      "\n# Forward kinematics: the seed a failed solve is retried from ([TRAJ] HOME), and the\n"
      "# convergence criterion (largest strut residual) and Newton step cap\n";
  const std::array<double, 6> home{model.home.position.x(),
                                   model.home.position.y(),
                                   model.home.position.z(),
                                   radToDeg(model.home.rpy.x()),
                                   radToDeg(model.home.rpy.y()),
                                   radToDeg(model.home.rpy.z())};
  static constexpr std::array<const char*, 6> kPose{"x", "y", "z", "a", "b", "c"};
  for (std::size_t k = 0; k < home.size(); ++k) setp(fmt::format("home.{}", kPose[k]), home[k]);
  setp("convergence-criterion", machine.fk.tolerance);
  out += fmt::format("setp pkmhexkins.limit-iterations {}\n", machine.fk.max_iterations);

  out += "\n# INI values for this geometry (pkmhexkins joint positions are the strut readings):\n";
  out += fmt::format("# [TRAJ] HOME = {} {} {} {} {} {}\n",
                     formatNumber(home[0]),
                     formatNumber(home[1]),
                     formatNumber(home[2]),
                     formatNumber(home[3]),
                     formatNumber(home[4]),
                     formatNumber(home[5]));
  out +=
      fmt::format("# [TRAJ] LINEAR_UNITS = {}\n", model.unit == LengthUnit::kInch ? "inch" : "mm");
  const std::array<PkmhexkinsJointValues, 6> joints = pkmhexkinsJointValues(machine);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    out += fmt::format("# [JOINT_{}] HOME = HOME_OFFSET = {}", i, formatNumber(joints[i].home));
    if (joints[i].min_limit) out += ", MIN_LIMIT = " + formatNumber(*joints[i].min_limit);
    if (joints[i].max_limit) out += ", MAX_LIMIT = " + formatNumber(*joints[i].max_limit);
    out += '\n';
  }
  return out;
}

}  // namespace pkm::io
