// A calibrated hexapod written into a LinuxCNC configuration in place (linuxcnc_patch.hpp).
#include "pkm/io/linuxcnc_patch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <string_view>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::io {
namespace {

namespace kin = pkm::kinematics;

/// A line of a text: [begin, end) without its '\n' (a trailing '\r' is part of it).
struct Line {
  std::size_t begin = 0, end = 0;
};

std::vector<Line> lines(const std::string& text) {
  std::vector<Line> out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    out.push_back({pos, end});
    pos = end + 1;
  }
  return out;
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/// The span [a, b) of the next whitespace-separated word at or after `pos` within [pos, end).
std::optional<std::pair<std::size_t, std::size_t>> word(const std::string& t,
                                                        std::size_t pos,
                                                        std::size_t end) {
  while (pos < end && blank(t[pos])) ++pos;
  if (pos >= end) return std::nullopt;
  std::size_t b = pos;
  while (b < end && !blank(t[b])) ++b;
  return std::pair{pos, b};
}

/// Calls fn(section, key, value, line) for each `KEY = VALUE` line of `ini` ("[SECTION]" with
/// its brackets; key without blanks; value trimmed; line 1-based); comments and blank lines
/// skipped.
template <class Fn>
void forEachIniEntry(const NamedText& ini, Fn fn) {
  std::string_view section;
  const std::string_view text(ini.text);
  const std::vector<Line> all = lines(ini.text);
  for (std::size_t n = 0; n < all.size(); ++n) {
    const auto first = word(ini.text, all[n].begin, all[n].end);
    if (!first) continue;
    const char c = text[first->first];
    if (c == '#' || c == ';') continue;
    if (c == '[') {
      section = text.substr(first->first, first->second - first->first);
      continue;
    }
    const std::string_view raw = text.substr(all[n].begin, all[n].end - all[n].begin);
    const std::size_t eq = raw.find('=');
    if (eq == std::string_view::npos) continue;
    std::string key(raw.substr(0, eq));
    std::erase_if(key, [](char ch) { return blank(ch); });
    std::size_t a = all[n].begin + eq + 1, b = all[n].end;
    while (a < b && blank(text[a])) ++a;
    while (b > a && blank(text[b - 1])) --b;
    fn(section, std::string_view(key), text.substr(a, b - a), n + 1);
  }
}

/// Replaces the value text [a, b) of `patch.after` (offsets into `patch.before`, shifted by
/// `shift`) with `value` when the number differs; records the change.
void replaceValue(TextPatch& patch,
                  std::ptrdiff_t& shift,
                  std::size_t a,
                  std::size_t b,
                  double value,
                  std::size_t line,
                  const std::string& key) {
  const std::string old = patch.before.substr(a, b - a);
  double current = 0.0;
  if (parseFiniteDouble(old, current) && current == value) return;
  const std::string text = formatNumber(value);
  patch.after.replace(
      static_cast<std::size_t>(static_cast<std::ptrdiff_t>(a) + shift), b - a, text);
  shift += static_cast<std::ptrdiff_t>(text.size()) - static_cast<std::ptrdiff_t>(b - a);
  patch.changes.push_back({line, key, old, text});
}

}  // namespace

std::vector<std::string> iniHalFiles(const NamedText& ini) {
  std::vector<std::string> out;
  forEachIniEntry(
      ini,
      [&](std::string_view section, std::string_view key, std::string_view value, std::size_t) {
        if (section == "[HAL]" && (key == "HALFILE" || key == "POSTGUI_HALFILE") && !value.empty())
          out.emplace_back(value.substr(0, value.find_first_of(" \t")));
      });
  return out;
}

std::optional<IniEntry> iniValue(const NamedText& ini,
                                 std::string_view section,
                                 std::string_view key) {
  std::optional<IniEntry> out;
  forEachIniEntry(ini,
                  [&](std::string_view s, std::string_view k, std::string_view v, std::size_t n) {
                    if (!out && s == section && k == key) out = IniEntry{std::string(v), n};
                  });
  return out;
}

NamedText genhexkinsHalFile(const NamedText& ini) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(ini.name).parent_path();
  for (const std::string& entry : iniHalFiles(ini)) {
    if (entry.starts_with("LIB:")) continue;
    const fs::path p = fs::path(entry).is_absolute() ? fs::path(entry) : dir / entry;
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) continue;
    NamedText hal = readNamedText(p.string());
    if (hal.text.find("genhexkins.") != std::string::npos) return hal;
  }
  throw IoError(fmt::format(
      "{}: none of the files its [HAL] HALFILE lines load sets genhexkins pins", ini.name));
}

std::optional<LengthUnit> iniLinearUnits(const NamedText& ini) {
  std::optional<LengthUnit> unit;
  forEachIniEntry(ini,
                  [&](std::string_view section,
                      std::string_view key,
                      std::string_view value,
                      std::size_t line) {
                    if (section != "[TRAJ]" || key != "LINEAR_UNITS") return;
                    if (value == "mm" || value == "metric")
                      unit = LengthUnit::kMillimetre;
                    else if (value == "inch" || value == "in" || value == "imperial")
                      unit = LengthUnit::kInch;
                    else
                      throw IoError(locate(
                          ini.name,
                          line,
                          fmt::format("[TRAJ] LINEAR_UNITS '{}' not understood (mm, metric, inch, "
                                      "in, imperial)",
                                      value)));
                  });
  return unit;
}

std::vector<std::pair<std::string, double>> genhexkinsPins(const HexapodMachine& machine) {
  const kin::HexapodModel& m = machine.model;
  std::vector<std::pair<std::string, double>> pins;
  for (int i = 0; i < kin::kStruts; ++i)
    for (int a = 0; a < 3; ++a)
      pins.emplace_back(fmt::format("base.{}.{}", i, "xyz"[a]),
                        m.struts[static_cast<std::size_t>(i)].world_p_base[a]);
  for (int i = 0; i < kin::kStruts; ++i) {
    const Eigen::Vector3d p =
        m.struts[static_cast<std::size_t>(i)].platform_p_joint - m.tool_offset;
    for (int a = 0; a < 3; ++a) pins.emplace_back(fmt::format("platform.{}.{}", i, "xyz"[a]), p[a]);
  }
  pins.emplace_back("spindle-offset", m.spindle_offset - m.linuxcnc_tool_offset);
  return pins;
}

TextPatch patchKinematicsHal(const NamedText& hal, const HexapodMachine& machine) {
  std::map<std::string, double> pins;
  for (const auto& [pin, value] : genhexkinsPins(machine)) pins.emplace(pin, value);
  TextPatch patch{hal.name, hal.text, hal.text, {}};
  std::ptrdiff_t shift = 0;
  std::map<std::string, bool> seen;
  const std::vector<Line> all = lines(hal.text);
  for (std::size_t n = 0; n < all.size(); ++n) {
    const auto cmd = word(hal.text, all[n].begin, all[n].end);
    if (!cmd || hal.text.compare(cmd->first, cmd->second - cmd->first, "setp") != 0) continue;
    const auto pin = word(hal.text, cmd->second, all[n].end);
    if (!pin) continue;
    const std::string name = hal.text.substr(pin->first, pin->second - pin->first);
    if (!name.starts_with("genhexkins.")) continue;
    const auto it = pins.find(name.substr(11));
    const auto value = word(hal.text, pin->second, all[n].end);
    if (it == pins.end() || !value) continue;
    replaceValue(patch, shift, value->first, value->second, it->second, n + 1, name);
    seen[it->first] = true;
  }
  for (const auto& [pin, value] : pins)
    if (pin != "spindle-offset" && !seen[pin])
      throw IoError(
          fmt::format("{}: no 'setp genhexkins.{}' line: pkm patches the values of "
                      "an existing configuration and adds no lines",
                      hal.name,
                      pin));
  return patch;
}

namespace {

/// A joint limit without the float noise of its sum (stroke + length offset): the shortest decimal
/// of at most 12 significant digits within 1e-14 (relative: float noise, not a real digit) of `v`,
/// else `v`. Round limits (±1000) then print round instead of -999.9999999999973.
double roundLimit(double v) {
  for (int digits = 1; digits <= 12; ++digits) {
    const double r = std::strtod(fmt::format("{:.{}e}", v, digits - 1).c_str(), nullptr);
    if (std::abs(r - v) <= 1e-14 * std::max(1.0, std::abs(v))) return r;
  }
  return v;
}

}  // namespace

std::array<LinuxcncJointValues, 6> linuxcncJointValues(const HexapodMachine& machine) {
  const kin::HexapodModel& m = machine.model;
  kin::HexapodData data(m);
  kin::inverseKinematics(m, data, m.home);
  std::array<LinuxcncJointValues, 6> out;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const kin::Strut& s = m.struts[i];
    out[i].home = data.joint_distance[static_cast<Eigen::Index>(i)];
    if (std::isfinite(s.min_reading))
      out[i].min_limit = roundLimit(s.min_reading + s.length_offset);
    if (std::isfinite(s.max_reading))
      out[i].max_limit = roundLimit(s.max_reading + s.length_offset);
  }
  return out;
}

TextPatch patchHexapodIni(const NamedText& ini, const HexapodMachine& machine) {
  const kin::HexapodModel& m = machine.model;
  const std::array<LinuxcncJointValues, 6> joints = linuxcncJointValues(machine);
  TextPatch patch{ini.name, ini.text, ini.text, {}};
  std::ptrdiff_t shift = 0;
  std::string section;
  std::array<bool, kin::kStruts> joint_seen{};
  const std::vector<Line> all = lines(ini.text);
  for (std::size_t n = 0; n < all.size(); ++n) {
    const auto first = word(ini.text, all[n].begin, all[n].end);
    if (!first || ini.text[first->first] == '#' || ini.text[first->first] == ';') continue;
    if (ini.text[first->first] == '[') {
      section = ini.text.substr(first->first, first->second - first->first);
      continue;
    }
    const std::string_view raw =
        std::string_view(ini.text).substr(all[n].begin, all[n].end - all[n].begin);
    const std::size_t eq = raw.find('=');
    if (eq == std::string_view::npos) continue;
    std::string key(raw.substr(0, eq));
    std::erase_if(key, [](char ch) { return blank(ch); });
    std::size_t a = all[n].begin + eq + 1, b = all[n].end;
    while (a < b && blank(ini.text[a])) ++a;
    while (b > a && blank(ini.text[b - 1])) --b;
    if (section == "[TRAJ]" && key == "LINEAR_UNITS") {
      const std::string units = ini.text.substr(a, b - a);
      const bool inch = units == "inch" || units == "in" || units == "imperial";
      if (inch != (m.unit == LengthUnit::kInch))
        throw IoError(locate(ini.name,
                             n + 1,
                             fmt::format("LINEAR_UNITS = {}, but the calibrated machine is in {}",
                                         units,
                                         toString(m.unit))));
      continue;
    }
    if (section.size() != 9 || !section.starts_with("[JOINT_") || section[7] < '0' ||
        section[7] > '5')
      continue;
    const auto i = static_cast<std::size_t>(section[7] - '0');
    joint_seen[i] = true;
    std::optional<double> value;
    if (key == "HOME" || key == "HOME_OFFSET") value = joints[i].home;
    if (key == "MIN_LIMIT") value = joints[i].min_limit;
    if (key == "MAX_LIMIT") value = joints[i].max_limit;
    if (value) replaceValue(patch, shift, a, b, *value, n + 1, section + " " + key);
  }
  for (std::size_t i = 0; i < joint_seen.size(); ++i)
    if (!joint_seen[i])
      throw IoError(
          fmt::format("{}: no [JOINT_{}] section (a hexapod has six joints)", ini.name, i));
  return patch;
}

std::string unifiedDiff(const TextPatch& patch) {
  const std::vector<Line> before = lines(patch.before), after = lines(patch.after);
  if (patch.before == patch.after) return "";
  assert(before.size() == after.size());  // values change within lines only
  const auto text = [](const std::string& t, const Line& l) {
    return t.substr(l.begin, l.end - l.begin);
  };
  std::vector<std::size_t> changed;
  for (std::size_t k = 0; k < before.size(); ++k)
    if (text(patch.before, before[k]) != text(patch.after, after[k])) changed.push_back(k);
  constexpr std::size_t kContext = 3;
  std::string out = fmt::format("--- {}\n+++ {}\n", patch.name, patch.name);
  for (std::size_t c = 0; c < changed.size();) {
    const std::size_t first = changed[c] >= kContext ? changed[c] - kContext : 0;
    std::size_t last = changed[c];
    std::size_t d = c;
    while (d + 1 < changed.size() && changed[d + 1] <= last + 2 * kContext + 1) last = changed[++d];
    last = std::min(before.size() - 1, last + kContext);
    out += fmt::format(
        "@@ -{},{} +{},{} @@\n", first + 1, last - first + 1, first + 1, last - first + 1);
    for (std::size_t k = first; k <= last; ++k) {
      const bool diff = std::binary_search(changed.begin() + static_cast<std::ptrdiff_t>(c),
                                           changed.begin() + static_cast<std::ptrdiff_t>(d) + 1,
                                           k);
      if (diff) {
        out += "-" + text(patch.before, before[k]) + "\n";
        out += "+" + text(patch.after, after[k]) + "\n";
      } else {
        out += " " + text(patch.before, before[k]) + "\n";
      }
    }
    c = d + 1;
  }
  return out;
}

}  // namespace pkm::io
