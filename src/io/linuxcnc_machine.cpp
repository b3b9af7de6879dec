// The hexapod of a LinuxCNC configuration (pkm/io/linuxcnc_machine.hpp).
#include "pkm/io/linuxcnc_machine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/linuxcnc_hexapod_params.hpp"
#include "pkm/io/linuxcnc_patch.hpp"

namespace pkm::io {
namespace {

namespace fs = std::filesystem;

/// How many numbers each name takes; strut names are matched with their index removed.
std::size_t arity(const std::string& name) {
  static const std::map<std::string, std::size_t> counts = {{"base", 3},
                                                            {"platform", 3},
                                                            {"length-offset", 1},
                                                            {"tool", 3},
                                                            {"spindle-offset", 1},
                                                            {"home", 6},
                                                            {"convergence-criterion", 1},
                                                            {"limit-iterations", 1},
                                                            {"max-error", 1},
                                                            {"max-backtracks", 1},
                                                            {"singular-pivot-ratio", 1},
                                                            {"max-step-translation", 1},
                                                            {"max-step-rotation", 1},
                                                            {"continuation-step", 1}};
  const auto it = counts.find(name);
  return it == counts.end() ? 0 : it->second;
}

/// "base.3" -> ("base", 3); "tool" -> ("tool", -1); a strut name without a valid index -> ("", -1).
std::pair<std::string, int> splitName(const std::string& word) {
  const std::size_t dot = word.rfind('.');
  if (dot == std::string::npos) return {word, -1};
  const std::string stem = word.substr(0, dot), index = word.substr(dot + 1);
  if ((stem != "base" && stem != "platform" && stem != "length-offset") || index.size() != 1 ||
      index[0] < '0' || index[0] > '5')
    return {"", -1};
  return {stem, index[0] - '0'};
}

bool strutName(const std::string& stem) {
  return stem == "base" || stem == "platform" || stem == "length-offset";
}

/// Applies one parsed line to the machine.
void apply(HexapodMachine& m, const std::string& stem, int i, const std::vector<double>& v) {
  kinematics::HexapodModel& model = m.model;
  if (i >= 0) {
    kinematics::Strut& s = model.struts[static_cast<std::size_t>(i)];
    if (stem == "base") s.world_p_base = Eigen::Vector3d(v[0], v[1], v[2]);
    if (stem == "platform") s.platform_p_joint = Eigen::Vector3d(v[0], v[1], v[2]);
    if (stem == "length-offset") s.length_offset = v[0];
  } else if (stem == "tool") {
    model.tool_offset = Eigen::Vector3d(v[0], v[1], v[2]);
  } else if (stem == "spindle-offset") {
    model.spindle_offset = v[0];
  } else if (stem == "home") {
    model.home.position = Eigen::Vector3d(v[0], v[1], v[2]);
    model.home.rpy = Eigen::Vector3d(degToRad(v[3]), degToRad(v[4]), degToRad(v[5]));
  } else if (stem == "convergence-criterion") {
    m.fk.tolerance = v[0];
  } else if (stem == "limit-iterations") {
    m.fk.max_iterations = static_cast<int>(v[0]);
  } else if (stem == "max-backtracks") {
    m.fk.max_backtracks = static_cast<int>(v[0]);
  } else if (stem == "singular-pivot-ratio") {
    m.fk.singular_pivot_ratio = v[0];
  } else if (stem == "max-step-translation") {
    m.fk.max_step_translation = v[0];
  } else if (stem == "max-step-rotation") {
    m.fk.max_step_rotation = v[0];
  } else if (stem == "continuation-step") {
    m.fk.continuation_step = v[0];
  }
}

}  // namespace

HexapodMachine parsePkmhexkinsParameters(const NamedText& params, LengthUnit unit) {
  HexapodMachine m;
  m.source = params.name;
  m.model.name = fs::path(params.name).stem().string();
  m.model.unit = unit;
  std::map<std::string, std::size_t> seen;
  std::istringstream in(params.text);
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    auto fail = [&](const std::string& what) { throw IoError(locate(params.name, n, what)); };
    const std::size_t hash = line.find('#');
    std::istringstream words(line.substr(0, hash));
    std::string name, w;
    if (!(words >> name)) continue;
    std::vector<double> values;
    while (words >> w) {
      double v = 0.0;
      if (!parseFiniteDouble(w, v)) fail(fmt::format("{}: '{}' is not a finite number", name, w));
      values.push_back(v);
    }
    const auto [stem, index] = splitName(name);
    const std::size_t want = arity(stem);
    if (want == 0 || (strutName(stem) != (index >= 0)))
      fail(fmt::format("'{}' is not a pkmhexkins parameter", name));
    if (values.size() != want)
      fail(fmt::format(
          "{}: expected {} number{}, found {}", name, want, want == 1 ? "" : "s", values.size()));
    if (const auto [it, fresh] = seen.emplace(name, n); !fresh)
      fail(fmt::format("{} is given again (first on line {})", name, it->second));
    apply(m, stem, index, values);
  }
  for (int i = 0; i < kinematics::kStruts; ++i)
    for (const char* stem : {"base", "platform"})
      if (!seen.count(fmt::format("{}.{}", stem, i)))
        throw IoError(fmt::format("{}: no '{}.{}' line", params.name, stem, i));
  if (std::string why; !m.fk.isValid(&why))
    throw IoError(fmt::format("{}: forward-kinematics settings: {}", params.name, why));
  return m;
}

std::optional<NamedText> pkmhexkinsParamsFile(const NamedText& ini) {
  const std::optional<IniEntry> kins = iniValue(ini, "[KINS]", "KINEMATICS");
  if (!kins) return std::nullopt;
  std::istringstream words(kins->value);
  std::string module, word;
  words >> module;
  if (module != "pkmhexkins") return std::nullopt;
  while (words >> word) {
    if (!word.starts_with("params=")) continue;
    fs::path file = word.substr(7);
    if (file.is_relative()) file = fs::path(ini.name).parent_path() / file;
    try {
      return readNamedText(file.string());
    } catch (const IoError& e) {
      throw IoError(locate(ini.name, kins->line, fmt::format("[KINS] KINEMATICS: {}", e.what())));
    }
  }
  return std::nullopt;
}

namespace {

/// name -> (1-based line, the numbers' text) of a parameter file's value lines.
std::map<std::string, std::pair<std::size_t, std::string>> valueLines(const std::string& text) {
  std::map<std::string, std::pair<std::size_t, std::string>> out;
  std::istringstream in(text);
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string name, w, values;
    if (!(words >> name)) continue;
    while (words >> w) values += (values.empty() ? "" : " ") + w;
    out.emplace(name, std::pair{n, values});
  }
  return out;
}

}  // namespace

TextPatch patchPkmhexkinsParameters(const NamedText& params,
                                    const HexapodMachine& machine,
                                    LengthUnit unit) {
  (void)parsePkmhexkinsParameters(params, unit);  // it is a parameter file
  if (machine.model.unit != unit)
    throw IoError(fmt::format("{}: the configuration is in {}, the calibrated machine in {}",
                              params.name,
                              toString(unit),
                              toString(machine.model.unit)));
  TextPatch patch{params.name, params.text, linuxcncHexapodParameters(machine), {}};
  const auto before = valueLines(patch.before);
  for (const auto& [name, now] : valueLines(patch.after)) {
    const auto it = before.find(name);
    const std::string old = it == before.end() ? "" : it->second.second;
    if (old != now.second) patch.changes.push_back({now.first, name, old, now.second});
  }
  std::sort(patch.changes.begin(),
            patch.changes.end(),
            [](const PatchedValue& a, const PatchedValue& b) { return a.line < b.line; });
  return patch;
}

LinuxcncHexapod readLinuxcncHexapod(const std::string& ini_path) {
  const NamedText ini = readNamedText(ini_path);
  LinuxcncHexapod out;
  if (const std::optional<NamedText> params = pkmhexkinsParamsFile(ini)) {
    out.machine =
        parsePkmhexkinsParameters(*params, iniLinearUnits(ini).value_or(LengthUnit::kMillimetre));
    applyLinuxcncIni(ini, out.machine);
    try {
      out.machine.model.validate();
    } catch (const InvalidArgument& e) {
      throw IoError(fmt::format("{}: {}", params->name, e.what()));
    }
    out.kinematics = "pkmhexkins";
    out.file = params->name;
    return out;
  }
  const NamedText hal = genhexkinsHalFile(ini);
  HalReadOptions options;
  options.ini_path = ini_path;
  out.machine = readLinuxcncHal(hal.name, options);
  out.kinematics = "genhexkins";
  out.file = hal.name;
  return out;
}

}  // namespace pkm::io
