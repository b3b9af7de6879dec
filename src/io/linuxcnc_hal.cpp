#include "pkm/io/linuxcnc_hal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/linuxcnc_patch.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::io {

namespace kin = pkm::kinematics;
namespace fs = std::filesystem;

namespace {

constexpr std::string_view kPrefix = "genhexkins.";

/// The HAL and INI files pkm reads are small; a larger file is refused.
constexpr std::size_t kMaxConfigBytes = 16u << 20;

/// The lines of `text`, without their '\n' and a trailing '\r'.
std::vector<std::string> halLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
  }
  return lines;
}

/// Whether the INI at `ini` loads `hal_name` through one of its [HAL] HALFILE entries.
bool iniLoadsHal(const std::string& ini, const std::string& hal_name) {
  for (const std::string& entry : iniHalFiles(readNamedText(ini)))
    if (fs::path(entry).filename() == hal_name) return true;
  return false;
}

/// Parses "x y z a b c" (length unit, degrees) into a pose; `fail` throws with the location.
template <typename Fail>
kin::PoseRpy parseHome(std::string_view label,
                       const std::vector<std::string_view>& values,
                       Fail&& fail) {
  if (values.size() != 6)
    fail(fmt::format("{}: expected 6 numbers (x y z a b c), found {}", label, values.size()));
  std::array<double, 6> v{};
  for (std::size_t i = 0; i < 6; ++i)
    if (!parseFiniteDouble(values[i], v[i]))
      fail(fmt::format("{}: '{}' is not a finite number", label, values[i]));
  kin::PoseRpy home;
  home.position = {v[0], v[1], v[2]};
  home.rpy = {degToRad(v[3]), degToRad(v[4]), degToRad(v[5])};
  return home;
}

/// A line of a HAL file; called with a message, throws pkm::IoError "FILE:LINE: message".
struct HalLine {
  const std::string& path;
  std::size_t number;  ///< 1-based
  [[noreturn]] void operator()(const std::string& what) const {
    throw IoError(locate(path, number, what));
  }
};

/// What the HAL lines set besides the machine.
struct HalPins {
  std::array<std::array<bool, 3>, kin::kStruts> base_set{}, platform_set{};
  double tool_offset = 0.0;
  bool pkm_home = false;  ///< a "# pkm: home" line was read
};

/// A "# pkm: home = x y z a b c" / "# pkm: units = mm|inch" line (`meta`: its words), written by
/// writeLinuxcncSetp so that its output is loadable on its own; an INI file overrides them.
void parsePkmComment(HexapodMachine& m,
                     HalPins& pins,
                     const std::vector<std::string_view>& meta,
                     const HalLine& fail) {
  if (meta.size() >= 4 && meta[2] == "home" && meta[3] == "=") {
    m.model.home = parseHome("# pkm: home", {meta.begin() + 4, meta.end()}, fail);
    pins.pkm_home = true;
  } else if (meta.size() == 5 && meta[2] == "units" && meta[3] == "=") {
    const auto unit = lengthUnitFromString(meta[4]);
    if (!unit) fail(fmt::format("units '{}': expected mm or inch", meta[4]));
    m.model.unit = *unit;
  } else {
    fail("'# pkm:' lines are 'home = x y z a b c' or 'units = mm|inch'");
  }
}

/// `setp genhexkins.PIN VALUE`: base.N.x / platform.N.x joint coordinates, the offsets and the
/// forward-kinematics settings; pins pkm does not use become notices, unknown ones errors.
void setPin(
    HexapodMachine& m, HalPins& pins, std::string_view pin, double value, const HalLine& fail) {
  const bool is_base = pin.starts_with("base.");
  const bool is_platform = pin.starts_with("platform.");
  if ((is_base || is_platform)) {
    const std::string_view rest = pin.substr(is_base ? 5 : 9);
    if (rest.size() != 3 || rest[1] != '.' || rest[0] < '0' || rest[0] > '5' || rest[2] < 'x' ||
        rest[2] > 'z')
      fail(fmt::format("unknown pin genhexkins.{}", pin));
    const auto i = static_cast<std::size_t>(rest[0] - '0');
    const int axis = rest[2] - 'x';
    kin::Strut& s = m.model.struts[i];
    (is_base ? s.world_p_base : s.platform_p_joint)[axis] = value;
    (is_base ? pins.base_set : pins.platform_set)[i][static_cast<std::size_t>(axis)] = true;
  } else if (pin == "spindle-offset") {
    m.model.spindle_offset = value;  // as in HAL, the last setp wins
  } else if (pin == "tool-offset") {
    pins.tool_offset = value;
  } else if (pin == "convergence-criterion") {
    if (!(value > 0.0)) fail("convergence-criterion must be > 0");
    m.fk.tolerance = value;
  } else if (pin == "limit-iterations") {
    if (value < 1 || value > 1e6 || value != std::floor(value))
      fail("limit-iterations must be an integer >= 1");
    m.fk.max_iterations = static_cast<int>(value);
  } else if (pin == "screw-lead") {
    if (value != 0.0)
      fail("screw-lead != 0: the screw-twist strut correction is not supported by pkm");
  } else if (pin.starts_with("base-n.") || pin.starts_with("platform-n.") || pin == "max-error") {
    m.notices.push_back(locate(
        fail.path, fail.number, fmt::format("ignored: genhexkins.{} (not used by pkm)", pin)));
  } else {
    fail(fmt::format("unknown pin genhexkins.{}", pin));
  }
}

/// One line of the HAL file: a "# pkm:" comment, a genhexkins `setp`, or anything else (a notice).
void parseHalLine(HexapodMachine& m, HalPins& pins, std::string_view text, const HalLine& fail) {
  if (const auto meta = splitWords(text); meta.size() >= 2 && meta[0] == "#" && meta[1] == "pkm:") {
    parsePkmComment(m, pins, meta, fail);
    return;
  }
  if (const auto hash = text.find('#'); hash != std::string_view::npos) text = text.substr(0, hash);
  const auto words = splitWords(text);
  if (words.empty()) return;
  const bool is_setp = words[0] == "setp" && words.size() >= 2 && words[1].starts_with(kPrefix);
  if (!is_setp) {
    m.notices.push_back(
        locate(fail.path, fail.number, fmt::format("ignored: {}", fmt::join(words, " "))));
    return;
  }
  if (words.size() != 3) fail(fmt::format("expected 'setp {} VALUE'", words[1]));
  double value = 0.0;
  if (!parseFiniteDouble(words[2], value))
    fail(fmt::format("'{}' is not a finite number", words[2]));
  setPin(m, pins, words[1].substr(kPrefix.size()), value, fail);
}

/// Throws pkm::IoError naming `hal_path` when a joint coordinate was not set.
void checkJointsSet(const std::string& hal_path, const HalPins& pins) {
  std::vector<std::string> missing;
  for (std::size_t i = 0; i < kin::kStruts; ++i)
    for (std::size_t a = 0; a < 3; ++a) {
      if (!pins.base_set[i][a]) missing.push_back(fmt::format("base.{}.{}", i, "xyz"[a]));
      if (!pins.platform_set[i][a]) missing.push_back(fmt::format("platform.{}.{}", i, "xyz"[a]));
    }
  if (!missing.empty())
    throw IoError(locate(hal_path,
                         0,
                         fmt::format("genhexkins pins not set: {} (set every joint coordinate "
                                     "explicitly; pkm does not assume genhexkins' defaults)",
                                     fmt::join(missing, ", "))));
}

/// The one INI file in the HAL file's folder that loads it (a notice in `m` says which, or that
/// several do and none is used).
std::optional<std::string> discoverIni(const std::string& hal_path, HexapodMachine& m) {
  const fs::path dir =
      fs::path(hal_path).parent_path().empty() ? fs::path(".") : fs::path(hal_path).parent_path();
  const std::string hal_name = fs::path(hal_path).filename().string();
  std::vector<std::string> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().extension() == ".ini" && iniLoadsHal(entry.path().string(), hal_name))
      found.push_back(entry.path().string());
  if (found.size() == 1) {
    m.notices.push_back(
        fmt::format("using INI {} (its [HAL] HALFILE loads {})", found.front(), hal_name));
    return found.front();
  }
  if (found.size() > 1)
    m.notices.push_back(fmt::format("several INI files load {}; none used (pass --ini)", hal_name));
  return std::nullopt;
}

/// Cone axes: the strut direction at home (LinuxCNC has no joint-angle limits; max_angle stays 0).
void setConeAxes(kin::HexapodModel& model) {
  kin::HexapodData data(model);
  kin::inverseKinematics(model, data, model.home);
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    if (data.unit_leg[i].norm() == 0.0) continue;
    model.struts[i].base_cone.axis = data.unit_leg[i];
    model.struts[i].platform_cone.axis = data.world_R_platform.transpose() * data.unit_leg[i];
  }
}

/// The machine the lines of `hal` set (its name is the source); `pins` gets what they set besides.
HexapodMachine halMachine(const NamedText& hal, HalPins& pins) {
  HexapodMachine m;
  m.source = hal.name;
  m.model.name = fs::path(hal.name).stem().string();
  m.description = fmt::format("Imported from LinuxCNC genhexkins configuration {}", hal.name);
  const auto lines = halLines(hal.text);
  for (std::size_t n = 0; n < lines.size(); ++n)
    parseHalLine(m, pins, lines[n], HalLine{hal.name, n + 1});
  checkJointsSet(hal.name, pins);
  m.model.spindle_offset += pins.tool_offset;  // genhexkins adds both to the z of every joint
  m.model.linuxcnc_tool_offset = pins.tool_offset;
  return m;
}

/// After the INI (`have_ini`): the cone axes, and the machine checked.
void finishHalMachine(HexapodMachine& m,
                      const std::string& hal_name,
                      const HalPins& pins,
                      bool have_ini) {
  if (!have_ini && !pins.pkm_home)
    m.notices.emplace_back(
        "no INI file: assuming mm and home 0 0 0 0 0 0 (pass --ini for [TRAJ] HOME and units)");
  setConeAxes(m.model);
  try {
    m.model.validate();
  } catch (const InvalidArgument& e) {
    throw IoError(locate(
        hal_name,
        0,
        fmt::format("{}{}",
                    e.what(),
                    have_ini || pins.pkm_home ? ""
                                              : " (no INI file was found, so home "
                                                "was taken as 0 0 0 0 0 0: pass --ini with [TRAJ] "
                                                "HOME)")));
  }
}

}  // namespace

HexapodMachine readLinuxcncHal(const std::string& hal_path, const HalReadOptions& options) {
  HalPins pins;
  HexapodMachine m = halMachine({hal_path, readTextFile(hal_path, kMaxConfigBytes)}, pins);
  std::optional<std::string> ini = options.ini_path;
  if (!ini && options.discover_ini) ini = discoverIni(hal_path, m);
  if (ini) applyLinuxcncIni(*ini, m);
  finishHalMachine(m, hal_path, pins, ini.has_value());
  return m;
}

HexapodMachine parseLinuxcncHal(const NamedText& hal, const std::optional<NamedText>& ini) {
  HalPins pins;
  HexapodMachine m = halMachine(hal, pins);
  if (ini) applyLinuxcncIni(*ini, m);
  finishHalMachine(m, hal.name, pins, ini.has_value());
  return m;
}

void applyLinuxcncIni(const std::string& ini_path, HexapodMachine& machine) {
  applyLinuxcncIni(NamedText{ini_path, readTextFile(ini_path, kMaxConfigBytes)}, machine);
}

void applyLinuxcncIni(const NamedText& ini, HexapodMachine& machine) {
  machine.ini_velocity = readIniVelocityLimits(ini);  // the rapid rate's limits (gcode run)
  const std::string& ini_path = ini.name;
  std::string section;
  const auto lines = halLines(ini.text);
  for (std::size_t n = 0; n < lines.size(); ++n) {
    const std::size_t line_no = n + 1;
    auto fail = [&](const std::string& what) { throw IoError(locate(ini_path, line_no, what)); };
    std::string_view text = lines[n];
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
      text.remove_prefix(1);
    if (text.empty() || text.front() == '#' || text.front() == ';') continue;
    if (text.front() == '[') {
      const auto close = text.find(']');
      if (close == std::string_view::npos) fail("unterminated section header");
      section = std::string(text.substr(0, close + 1));
      continue;
    }
    const auto eq = text.find('=');
    if (eq == std::string_view::npos) continue;
    const auto key_words = splitWords(text.substr(0, eq));
    if (key_words.size() != 1) continue;
    const std::string_view key = key_words[0];
    const auto values = splitWords(text.substr(eq + 1));
    if (section == "[RS274NGC]" && key == "RS274NGC_STARTUP_CODE") {
      std::string_view code = text.substr(eq + 1);
      while (!code.empty() && std::isspace(static_cast<unsigned char>(code.front())))
        code.remove_prefix(1);
      while (!code.empty() && std::isspace(static_cast<unsigned char>(code.back())))
        code.remove_suffix(1);
      machine.startup_code = std::string(code);
      machine.startup_code_source = fmt::format("{}:{}", ini_path, line_no);
    } else if (section == "[TRAJ]" && key == "HOME") {
      machine.model.home = parseHome("[TRAJ] HOME", values, fail);
    } else if (section == "[TRAJ]" && key == "LINEAR_UNITS") {
      const std::string u = values.empty() ? "" : std::string(values[0]);
      if (u == "mm" || u == "metric")
        machine.model.unit = LengthUnit::kMillimetre;
      else if (u == "inch" || u == "in" || u == "imperial")
        machine.model.unit = LengthUnit::kInch;
      else
        fail(fmt::format("[TRAJ] LINEAR_UNITS '{}' not understood (mm, metric, inch, in, imperial)",
                         u));
    } else if (section.size() == 9 && section.starts_with("[JOINT_") && section[7] >= '0' &&
               section[7] <= '5' && (key == "MIN_LIMIT" || key == "MAX_LIMIT")) {
      double v = 0.0;
      if (values.size() != 1 || !parseFiniteDouble(values[0], v))
        fail(fmt::format("{} {}: expected one number", section, key));
      kin::Strut& s = machine.model.struts[static_cast<std::size_t>(section[7] - '0')];
      (key == "MIN_LIMIT" ? s.min_reading : s.max_reading) = v;
    } else if (section.size() == 9 && section.starts_with("[JOINT_") && section[7] >= '0' &&
               section[7] <= '5' && (key == "MAX_VELOCITY" || key == "MAX_ACCELERATION")) {
      // One limit for all struts: the smallest of the joints' (pkm's rates are uniform).
      double v = 0.0;
      if (values.size() != 1 || !parseFiniteDouble(values[0], v) || !(v > 0.0))
        fail(fmt::format("{} {}: expected one number > 0", section, key));
      if (!machine.joint_rates) machine.joint_rates.emplace();
      double& limit =
          key == "MAX_VELOCITY" ? machine.joint_rates->velocity : machine.joint_rates->acceleration;
      limit = std::isnan(limit) ? v : std::min(limit, v);
    }
  }
  for (int i = 0; i < kin::kStruts; ++i) {
    const kin::Strut& s = machine.model.struts[static_cast<std::size_t>(i)];
    if (s.min_reading > s.max_reading)
      throw IoError(locate(
          ini_path,
          0,
          fmt::format("[JOINT_{}] MIN_LIMIT {} > MAX_LIMIT {}", i, s.min_reading, s.max_reading)));
  }
}

}  // namespace pkm::io
