// The predefined named parameters of LinuxCNC 2.9 (G-code overview, "Predefined Named
// Parameters", "System Parameters", "HAL pins and INI values"): read-only values computed from
// the interpreter's state; their values at start-up were read off rs274.
#include <fmt/format.h>

#include <optional>
#include <string>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {

constexpr double kVersionMajor = 2.9;  // LinuxCNC 2.9, whose dialect pkm reads
constexpr double kVersionMinor = 0.0;
constexpr std::string_view kIniPrefix = "_ini[";

/// Index of axis letter `c` among X Y Z A B C; -1 for U V W (not supported, always 0).
int axisIndex(char c) {
  switch (c) {
    case 'x':
      return 0;
    case 'y':
      return 1;
    case 'z':
      return 2;
    case 'a':
      return 3;
    case 'b':
      return 4;
    case 'c':
      return 5;
    default:
      return -1;
  }
}

bool isAxisLetter(char c) { return axisIndex(c) >= 0 || c == 'u' || c == 'v' || c == 'w'; }

/// The plane as #<_plane> reports it: G17 is 170, G18 180, G19 190.
double planeCode(Plane p) { return p == Plane::kXY ? 170 : p == Plane::kXZ ? 180 : 190; }

}  // namespace

std::optional<double> Interpreter::Impl::systemParameter(const std::string& name) const {
  if (name.size() < 2 || name[0] != '_') return std::nullopt;
  if (name.compare(0, kIniPrefix.size(), kIniPrefix) == 0) {
    const auto it = options.ini_values.find(name.substr(kIniPrefix.size()));
    if (it == options.ini_values.end()) return std::nullopt;
    return it->second;
  }
  const std::string_view n = std::string_view(name).substr(1);
  if (n.size() == 1 && isAxisLetter(n[0])) {
    const int i = axisIndex(n[0]);
    return i < 0 ? 0.0
                 : st.program(static_cast<std::size_t>(i)) /
                       st.axisScale(static_cast<std::size_t>(i));
  }
  if (n.size() == 5 && n.substr(0, 4) == "abs_" && isAxisLetter(n[4])) {
    const int i = axisIndex(n[4]);
    return i < 0 ? 0.0
                 : st.machine[static_cast<std::size_t>(i)] /
                       st.axisScale(static_cast<std::size_t>(i));
  }
  const auto flag = [](bool b) { return b ? 1.0 : 0.0; };
  if (n == "vmajor") return kVersionMajor;
  if (n == "vminor") return kVersionMinor;
  if (n == "line") return static_cast<double>(current_line);
  if (n == "motion_mode") return st.motion;
  if (n == "plane") return planeCode(st.plane);
  if (n == "ccomp") return 400.0;
  if (n == "metric") return flag(!st.inch);
  if (n == "imperial") return flag(st.inch);
  if (n == "absolute") return flag(!st.incremental);
  if (n == "incremental") return flag(st.incremental);
  if (n == "inverse_time") return flag(st.inverse_time);
  if (n == "units_per_minute") return flag(!st.inverse_time);
  if (n == "units_per_rev") return 0.0;
  if (n == "coord_system") {
    static constexpr double kCodes[] = {540, 550, 560, 570, 580, 590, 591, 592, 593};
    return kCodes[st.coordinate_system - 1];
  }
  if (n == "tool_offset") return flag(st.tool_length_mode != 490);
  if (n == "retract_r_plane") return flag(st.retract_to_r);  // rs274: 1 under G99
  if (n == "retract_old_z") return flag(!st.retract_to_r);
  if (n == "spindle_rpm_mode") return 1.0;
  if (n == "spindle_css_mode" || n == "lathe_diameter_mode" || n == "lathe_radius_mode" ||
      n == "adaptive_feed" || n == "task" || n == "remap_level")
    return 0.0;
  if (n == "ijk_absolute_mode") return flag(st.ijk_absolute);
  if (n == "spindle_on") return flag(st.spindle_direction != 0);
  if (n == "spindle_cw") return flag(st.spindle_direction > 0);
  if (n == "mist") return flag(st.mist);
  if (n == "flood") return flag(st.flood);
  if (n == "speed_override" || n == "feed_override") return flag(st.overrides_enabled);
  if (n == "feed_hold") return 1.0;
  if (n == "feed") return st.angular_feed;
  if (n == "rpm") return st.spindle_speed;
  if (n == "current_tool" || n == "current_pocket") return st.tool_in_spindle;
  if (n == "selected_tool" || n == "selected_pocket") return st.selected_tool;
  if (n == "call_level") return static_cast<double>(params.callDepth());
  return std::nullopt;
}

double Interpreter::Impl::named(const std::string& name) {
  if (const auto v = systemParameter(name)) return *v;
  if (name.compare(0, kIniPrefix.size(), kIniPrefix) == 0)
    throw GcodeError(fmt::format("named parameter #<{}> not defined (no such INI entry{})",
                                 name,
                                 options.ini_values.empty() ? "; no --ini was given" : ""));
  return params.named(name);
}

bool Interpreter::Impl::exists(const std::string& name) {
  return systemParameter(name).has_value() || params.exists(name);
}

void Interpreter::Impl::setNamedChecked(const std::string& name, double value) {
  if (systemParameter(name) || name.compare(0, kIniPrefix.size(), kIniPrefix) == 0 ||
      name == "_value" || name == "_value_returned")
    throw GcodeError(fmt::format("cannot assign to read-only parameter #<{}>", name));
  params.setNamed(name, value);
}

}  // namespace pkm::cnc
