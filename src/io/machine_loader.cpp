#include "pkm/io/machine_loader.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <utility>

#include "pkm/core/error.hpp"
#include "pkm/io/linuxcnc_machine.hpp"

namespace pkm::io {

namespace detail {
const std::vector<std::pair<std::string_view, std::string_view>>& embeddedMachines();
const std::vector<std::pair<std::string_view, std::string_view>>& embeddedErrors();
}  // namespace detail

namespace {

/// The embedded text of `name` if there is one of `type`.
std::optional<std::string> builtinText(const std::string& name, const std::string& type) {
  for (const auto& [stem, text] : detail::embeddedMachines())
    if (stem == name && machineType(std::string(text)) == type) return std::string(text);
  return std::nullopt;
}

[[noreturn]] void noSuchMachine(const std::string& spec, const std::string& type) {
  throw IoError(fmt::format("{}: no such file, and not a built-in {} machine (built-in: {})",
                            spec,
                            type,
                            fmt::join(builtinMachineNames(type), ", ")));
}

/// True when `spec` names an existing file; throws for a directory.
bool isFile(const std::string& spec) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(spec, ec)) return false;
  if (fs::is_directory(spec, ec))
    throw IoError(locate(spec, 0, "is a directory, expected a machine file"));
  return true;
}

/// A kinematics component's parameter file is not a machine description: says what to pass.
void refuseParameterFile(const std::string& spec) {
  if (!spec.ends_with(".params") || !isFile(spec)) return;
  throw IoError(locate(
      spec,
      0,
      "a LinuxCNC kinematics parameter file (pkmhexkins/pkmexechonkins params=, written by `pkm "
      "hexapod|exechon linuxcnc-params` and `pkm linuxcnc config`), not a machine description: "
      "pass the machine it was written from (a pkm machine JSON, a CAL.json, a built-in name) or "
      "a genhexkins .hal file with its --ini"));
}

}  // namespace

std::string machineType(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_object() && j.contains("type") && j["type"].is_string())
    return j["type"].get<std::string>();
  return "hexapod";
}

std::string machineTypeOf(const std::string& spec) {
  if (std::filesystem::is_regular_file(spec)) return machineType(readTextFile(spec));
  for (const auto& n : builtinMachineNames("exechon"))
    if (n == spec) return "exechon";
  return "hexapod";
}

std::vector<std::string> builtinMachineNames(const std::string& type) {
  std::vector<std::string> names;
  for (const auto& [name, text] : detail::embeddedMachines())
    if (type.empty() || machineType(std::string(text)) == type) names.emplace_back(name);
  return names;
}

HexapodMachine builtinMachine(const std::string& name) {
  const std::string wanted = name == "default" ? kDefaultMachine : name;
  if (const auto text = builtinText(wanted, "hexapod"))
    return parseHexapodJson(*text, "builtin:" + wanted);
  noSuchMachine(name, "hexapod");
}

HexapodMachine loadHexapodMachine(const std::string& spec, const HalReadOptions& hal) {
  if (spec.ends_with(".hal")) return readLinuxcncHal(spec, hal);
  // A configuration's parameter file read with the INI that loads it: what LinuxCNC computes with.
  if (spec.ends_with(".params") && hal.ini_path && isFile(spec)) {
    LinuxcncHexapod read = readLinuxcncHexapod(*hal.ini_path);
    std::error_code ec;
    if (read.kinematics == "pkmhexkins" && std::filesystem::equivalent(read.file, spec, ec))
      return std::move(read.machine);
  }
  refuseParameterFile(spec);
  if (isFile(spec)) return readHexapodJson(spec);
  return builtinMachine(spec);
}

ExechonMachine loadExechonMachine(const std::string& spec) {
  refuseParameterFile(spec);
  if (isFile(spec)) return readExechonJson(spec);
  const std::string wanted = spec == "default" ? kDefaultExechonMachine : spec;
  if (const auto text = builtinText(wanted, "exechon"))
    return parseExechonJson(*text, "builtin:" + wanted);
  noSuchMachine(spec, "exechon");
}

std::vector<std::string> builtinErrorNames() {
  std::vector<std::string> names;
  for (const auto& [name, text] : detail::embeddedErrors()) names.emplace_back(name);
  return names;
}

kinematics::GeometricErrors loadGeometricErrors(const std::string& spec) {
  if (isFile(spec)) return readGeometricErrorsJson(spec);
  for (const auto& [stem, text] : detail::embeddedErrors())
    if (stem == spec) return parseGeometricErrorsJson(std::string(text), "builtin:" + spec);
  throw IoError(fmt::format("{}: no such file, and not a built-in error set (built-in: {})",
                            spec,
                            fmt::join(builtinErrorNames(), ", ")));
}

}  // namespace pkm::io
