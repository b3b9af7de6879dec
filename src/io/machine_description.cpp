// The description of a hexapod machine (machine_description.hpp).
#include "pkm/io/machine_description.hpp"

#include <fmt/format.h>

#include "pkm/core/units.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"

namespace pkm::io {

std::string describeHexapodMachine(const HexapodMachine& machine) {
  std::string o;
  const kinematics::HexapodModel& m = machine.model;
  const std::string u(toString(m.unit));
  o += fmt::format("machine      {} ({})\n", m.name, machine.source);
  if (!machine.description.empty()) o += fmt::format("description  {}\n", machine.description);
  o += fmt::format("units        {} (angles in degrees)\n", u);
  o += fmt::format("home         x {:g} y {:g} z {:g} a {:g} b {:g} c {:g}\n",
                   m.home.position.x(),
                   m.home.position.y(),
                   m.home.position.z(),
                   radToDeg(m.home.rpy.x()),
                   radToDeg(m.home.rpy.y()),
                   radToDeg(m.home.rpy.z()));
  o += fmt::format("tool offset  [{:g}, {:g}, {:g}] {} (TCP in the platform frame)\n",
                   m.tool_offset.x(),
                   m.tool_offset.y(),
                   m.tool_offset.z(),
                   u);
  if (m.spindle_offset != 0.0)
    o += fmt::format("spindle off. {:g} {} (genhexkins)\n", m.spindle_offset, u);
  o += fmt::format("strut dia.   {:g} {}{}\n",
                   m.strut_diameter,
                   u,
                   m.strut_diameter > 0 ? "" : " (interference check off)");
  o += fmt::format("FK           tolerance {:g} {}, at most {} iterations\n",
                   machine.fk.tolerance,
                   u,
                   machine.fk.max_iterations);
  kinematics::HexapodData data(m);
  const kinematics::HexapodCheckResult home = kinematics::checkPose(m, data, m.home);
  o += fmt::format("{:>5} {:>30} {:>30} {:>9} {:>21} {:>12} {:>8} {:>8}\n",
                   "strut",
                   "base joint (world)",
                   "platform joint (platform)",
                   "offset",
                   "stroke",
                   "home read.",
                   "base°",
                   "plat.°");
  for (int i = 0; i < kinematics::kStruts; ++i) {
    const kinematics::Strut& s = m.struts[static_cast<std::size_t>(i)];
    const auto lim = [](double a) {
      return a > 0 ? fmt::format("{:.1f}", radToDeg(a)) : std::string("-");
    };
    o += fmt::format(
        "{:>5} {:>30} {:>30} {:>9.3f} {:>21} {:>12.6f} {:>8} {:>8}\n",
        i,
        fmt::format(
            "[{:.4f}, {:.4f}, {:.4f}]", s.world_p_base.x(), s.world_p_base.y(), s.world_p_base.z()),
        fmt::format("[{:.4f}, {:.4f}, {:.4f}]",
                    s.platform_p_joint.x(),
                    s.platform_p_joint.y(),
                    s.platform_p_joint.z()),
        s.length_offset,
        fmt::format("[{:g}, {:g}]", s.min_reading, s.max_reading),
        home.readings[i],
        lim(s.base_cone.max_angle),
        lim(s.platform_cone.max_angle));
  }
  o += fmt::format(
      "at home      status {}, condition number {:.2f} (limit {:g}), closest struts {:.3f} {}\n",
      home.status(),
      home.condition_number,
      m.max_condition,
      home.min_leg_distance,
      u);
  return o;
}

}  // namespace pkm::io
