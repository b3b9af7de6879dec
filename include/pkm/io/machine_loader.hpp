/// @file
/// @brief Loads a hexapod machine from a JSON file, a LinuxCNC HAL file, or a built-in name.
#pragma once

#include <string>
#include <vector>

#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/linuxcnc_hal.hpp"

namespace pkm::io {

/// Name of the embedded default machine (data/machines/hexapod-default.json).
inline constexpr const char* kDefaultMachine = "hexapod-default";

/// Names of the machine files embedded at build time (file stems of data/machines/*.json).
[[nodiscard]] std::vector<std::string> builtinMachineNames();

/// Parses the embedded machine `name`. Throws pkm::IoError if there is none by that name.
[[nodiscard]] HexapodMachine builtinMachine(const std::string& name);

/// `spec` ending in ".hal": readLinuxcncHal; an existing file: readHexapodJson; otherwise a
/// built-in name ("default" means kDefaultMachine). Throws pkm::IoError naming the file and line on
/// bad input.
[[nodiscard]] HexapodMachine loadHexapodMachine(const std::string& spec,
                                                const HalReadOptions& hal = {});

}  // namespace pkm::io
