#include "pkm/io/linuxcnc_hexapod_params.hpp"

#include <fmt/format.h>

#include <initializer_list>
#include <string_view>

#include "pkm/core/units.hpp"

namespace pkm::io {

namespace {

/// One `name v1 v2 ...` line, numbers in shortest round-trip form.
void paramLine(std::string& out, std::string_view name, std::initializer_list<double> values) {
  out += name;
  for (const double v : values) out += fmt::format(" {}", v);
  out += '\n';
}

}  // namespace

std::string linuxcncHexapodParameters(const HexapodMachine& machine) {
  const kinematics::HexapodModel& m = machine.model;
  const kinematics::FkOptions& fk = machine.fk;
  std::string name = m.name;  // one comment line
  for (char& c : name)
    if (c == '\n' || c == '\r') c = ' ';
  std::string out = fmt::format(
      "# pkmhexkins parameters of {} (lengths in {}, angles in degrees unless named rad)\n"
      "# loadrt pkmhexkins params=THIS-FILE  (docs/linuxcnc.md, \"The pkmhexkins parameter "
      "file\")\n",
      name,
      toString(m.unit));
  out +=
      "# strut i: base joint centre (world frame), platform joint centre (platform frame),\n"
      "# reading + length-offset = joint-centre distance\n";
  for (int i = 0; i < kinematics::kStruts; ++i) {
    const kinematics::Strut& s = m.struts[static_cast<std::size_t>(i)];
    paramLine(out,
              fmt::format("base.{}", i),
              {s.world_p_base.x(), s.world_p_base.y(), s.world_p_base.z()});
    paramLine(out,
              fmt::format("platform.{}", i),
              {s.platform_p_joint.x(), s.platform_p_joint.y(), s.platform_p_joint.z()});
    paramLine(out, fmt::format("length-offset.{}", i), {s.length_offset});
  }
  out += "# the controlled point in the platform frame; added to every joint's z\n";
  paramLine(out, "tool", {m.tool_offset.x(), m.tool_offset.y(), m.tool_offset.z()});
  paramLine(out, "spindle-offset", {m.spindle_offset});
  out += "# home pose x y z a b c ([TRAJ] HOME; the second forward-kinematics seed)\n";
  paramLine(out,
            "home",
            {m.home.position.x(),
             m.home.position.y(),
             m.home.position.z(),
             radToDeg(m.home.rpy.x()),
             radToDeg(m.home.rpy.y()),
             radToDeg(m.home.rpy.z())});
  out += "# forward kinematics (pkm's FkOptions); max-error 0: no limit\n";
  paramLine(out, "convergence-criterion", {fk.tolerance});
  paramLine(out, "limit-iterations", {static_cast<double>(fk.max_iterations)});
  paramLine(out, "max-error", {0.0});
  paramLine(out, "max-backtracks", {static_cast<double>(fk.max_backtracks)});
  paramLine(out, "singular-pivot-ratio", {fk.singular_pivot_ratio});
  paramLine(out, "max-step-translation", {fk.max_step_translation});
  paramLine(out, "max-step-rotation", {fk.max_step_rotation});  // rad
  paramLine(out, "continuation-step", {fk.continuation_step});
  return out;
}

}  // namespace pkm::io
