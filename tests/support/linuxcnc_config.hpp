// The LinuxCNC configuration `pkm linuxcnc config --machine hexapod-default` writes, for the tests
// of the live calibration and its server routes (a real INI and parameter file for stand-ins).
#pragma once

#include <filesystem>
#include <string>

#include "pkm/workflow/linuxcnc_config.hpp"

namespace pkm::test {

/// Writes hexapod-default's configuration into DIR/cfg; returns its INI's path.
inline std::string writeHexapodDefaultConfig(const std::filesystem::path& dir) {
  workflow::LinuxcncConfigRequest config;
  config.machine = "hexapod-default";
  config.out = (dir / "cfg").string();
  return workflow::writeLinuxcncConfig(config).ini;
}

}  // namespace pkm::test
