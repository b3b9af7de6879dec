// The velocity limits of a LinuxCNC INI (io/ini_velocity_limits.hpp).
#include "pkm/io/ini_velocity_limits.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <string_view>

#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"

namespace pkm::io {

namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

/// The axis index of an [AXIS_<letter>] section (0..5 for X..C), or -1.
int axisOf(std::string_view section) {
  constexpr std::string_view kLetters = "XYZABC";
  if (section.size() != 8 || !section.starts_with("[AXIS_") || section[7] != ']') return -1;
  const auto at = kLetters.find(section[6]);
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
  std::string section;
  std::size_t line_no = 0;
  std::string_view rest = ini.text;
  while (!rest.empty()) {
    const auto end = rest.find('\n');
    const std::string_view text = trimmed(rest.substr(0, end));
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    ++line_no;
    if (text.empty() || text.front() == '#' || text.front() == ';') continue;
    if (text.front() == '[') {
      section = std::string(text.substr(0, text.find(']') + 1));
      continue;
    }
    const auto eq = text.find('=');
    if (eq == std::string_view::npos) continue;
    const std::string_view key = trimmed(text.substr(0, eq));
    double* target = nullptr;
    const int axis = axisOf(section);
    if (section == "[TRAJ]" && key == "MAX_LINEAR_VELOCITY") target = &r.linear;
    if (section == "[TRAJ]" && key == "MAX_VELOCITY") target = &old_max_velocity;
    if (section == "[TRAJ]" && key == "MAX_ANGULAR_VELOCITY") target = &r.angular;
    if (axis >= 0 && key == "MAX_VELOCITY") target = &r.axis[static_cast<std::size_t>(axis)];
    if (target == nullptr) continue;
    const auto values = splitWords(text.substr(eq + 1));
    double v = 0.0;
    if (values.size() != 1 || !parseFiniteDouble(values[0], v) || !(v > 0.0))
      throw IoError(
          locate(ini.name, line_no, fmt::format("{} {}: expected one number > 0", section, key)));
    *target = v;
  }
  if (std::isnan(r.linear)) r.linear = old_max_velocity;
  return r;
}

}  // namespace pkm::io
