// The LinuxCNC genhexkins `setp` block of a hexapod (io/linuxcnc_hal.hpp), with the "# pkm:"
// lines readLinuxcncHal reads back and the INI values of the geometry as comments.
#include <fmt/format.h>

#include <cmath>

#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/linuxcnc_patch.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::io {

namespace kin = pkm::kinematics;

std::string writeLinuxcncSetp(const HexapodMachine& machine) {
  const kin::HexapodModel& model = machine.model;
  std::string out =
      fmt::format("# genhexkins geometry written by pkm from {}\n# machine: {}, units: {}\n",
                  machine.source,
                  model.name,
                  toString(model.unit));
  const bool tcp = model.tool_offset.norm() > 0.0;
  if (tcp)
    out +=
        "# The TCP offset of the pkm model is folded into the platform joints (platform = joint - "
        "TCP).\n";
  auto setp = [&out](const std::string& pin, double v) {
    out += "setp genhexkins." + pin + " ";
    appendNumber(out, v);
    out += '\n';
  };
  // genhexkinsPins: 18 base coordinates, 18 platform coordinates, then spindle-offset.
  const std::vector<std::pair<std::string, double>> pins = genhexkinsPins(machine);
  for (std::size_t k = 0; k < pins.size(); ++k) {
    if (k == 0) out += "\n# Base joints positions in base (world) coordinates\n";
    if (k == 3 * kin::kStruts) out += "\n# Platform joints positions in platform coordinates\n";
    if (k == 6 * kin::kStruts) out += "\n";
    setp(pins[k].first, pins[k].second);
  }
  if (model.linuxcnc_tool_offset != 0.0) setp("tool-offset", model.linuxcnc_tool_offset);
  setp("convergence-criterion", machine.fk.tolerance);
  out += fmt::format("setp genhexkins.limit-iterations {}\n", machine.fk.max_iterations);

  const std::string home = fmt::format("{} {} {} {} {} {}",
                                       formatNumber(model.home.position.x()),
                                       formatNumber(model.home.position.y()),
                                       formatNumber(model.home.position.z()),
                                       formatNumber(radToDeg(model.home.rpy.x())),
                                       formatNumber(radToDeg(model.home.rpy.y())),
                                       formatNumber(radToDeg(model.home.rpy.z())));
  // Read back by readLinuxcncHal (an INI file, when found, overrides them).
  out += fmt::format("\n# pkm: units = {}\n", toString(model.unit));
  out += fmt::format("# pkm: home = {}\n", home);
  out +=
      "\n# INI values for this geometry (LinuxCNC joint positions are joint-centre distances):\n";
  out += fmt::format("# [TRAJ] HOME = {}\n", home);
  out +=
      fmt::format("# [TRAJ] LINEAR_UNITS = {}\n", model.unit == LengthUnit::kInch ? "inch" : "mm");
  const std::array<LinuxcncJointValues, 6> joints = linuxcncJointValues(machine);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    out += fmt::format("# [JOINT_{}] HOME = HOME_OFFSET = {}", i, formatNumber(joints[i].home));
    if (joints[i].min_limit) out += ", MIN_LIMIT = " + formatNumber(*joints[i].min_limit);
    if (joints[i].max_limit) out += ", MAX_LIMIT = " + formatNumber(*joints[i].max_limit);
    const double offset = model.struts[i].length_offset;
    if (offset != 0.0)
      out += fmt::format(" (pkm reading + length offset {})", formatNumber(offset));
    out += '\n';
  }
  return out;
}

}  // namespace pkm::io
