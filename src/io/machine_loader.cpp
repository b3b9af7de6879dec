#include "pkm/io/machine_loader.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <string_view>
#include <utility>

#include "pkm/core/error.hpp"

namespace pkm::io {

namespace detail {
const std::vector<std::pair<std::string_view, std::string_view>>& embeddedMachines();
}  // namespace detail

std::vector<std::string> builtinMachineNames() {
  std::vector<std::string> names;
  for (const auto& [name, text] : detail::embeddedMachines()) names.emplace_back(name);
  return names;
}

HexapodMachine builtinMachine(const std::string& name) {
  const std::string wanted = name == "default" ? kDefaultMachine : name;
  for (const auto& [stem, text] : detail::embeddedMachines()) {
    if (stem == wanted) {
      HexapodMachine m = parseHexapodJson(std::string(text), "builtin:" + wanted);
      return m;
    }
  }
  throw IoError(fmt::format("{}: no such file, and not a built-in machine (built-in: {})",
                            name,
                            fmt::join(builtinMachineNames(), ", ")));
}

HexapodMachine loadHexapodMachine(const std::string& spec, const HalReadOptions& hal) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (spec.ends_with(".hal")) return readLinuxcncHal(spec, hal);
  if (fs::exists(spec, ec)) {
    if (fs::is_directory(spec, ec))
      throw IoError(locate(spec, 0, "is a directory, expected a machine file"));
    return readHexapodJson(spec);
  }
  return builtinMachine(spec);
}

}  // namespace pkm::io
