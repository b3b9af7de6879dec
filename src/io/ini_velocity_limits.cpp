// The velocity limits of a LinuxCNC INI (io/ini_velocity_limits.hpp).
#include "pkm/io/ini_velocity_limits.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <string_view>

#include "pkm/core/error.hpp"
#include "pkm/core/text.hpp"
#include "pkm/io/csv.hpp"

namespace pkm::io {

namespace {

/// The axis index of an AXIS_<letter> section (0..5 for X..C), or -1.
int axisOf(std::string_view section) {
  constexpr std::string_view kLetters = "XYZABC";
  if (section.size() != 6 || !section.starts_with("AXIS_")) return -1;
  const auto at = kLetters.find(section[5]);
  return at == std::string_view::npos ? -1 : static_cast<int>(at);
}

}  // namespace

bool IniVelocityLimits::any() const {
  if (!std::isnan(linear) || !std::isnan(angular)) return true;
  for (double v : axis)
    if (!std::isnan(v)) return true;
  return false;
}

IniVelocityLimits readIniVelocityLimits(const NamedText& ini) {
  IniVelocityLimits r;
  r.source = ini.name;
  double old_max_velocity = IniVelocityLimits::kUnset;  // [TRAJ] MAX_VELOCITY (LinuxCNC 2.7)
  for (const IniEntry& e : parseIni(ini.text, ini.name)) {
    double* target = nullptr;
    const int axis = axisOf(e.section);
    if (e.section == "TRAJ" && e.key == "MAX_LINEAR_VELOCITY") target = &r.linear;
    if (e.section == "TRAJ" && e.key == "MAX_VELOCITY") target = &old_max_velocity;
    if (e.section == "TRAJ" && e.key == "MAX_ANGULAR_VELOCITY") target = &r.angular;
    if (axis >= 0 && e.key == "MAX_VELOCITY") target = &r.axis[static_cast<std::size_t>(axis)];
    if (target == nullptr) continue;
    const auto values = splitWords(e.value);
    double v = 0.0;
    if (values.size() != 1 || !parseFiniteDouble(values[0], v) || !(v > 0.0))
      throw IoError(locate(
          ini.name, e.line, fmt::format("[{}] {}: expected one number > 0", e.section, e.key)));
    *target = v;
  }
  if (std::isnan(r.linear)) r.linear = old_max_velocity;
  return r;
}

}  // namespace pkm::io
