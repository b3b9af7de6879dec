/// @file
/// @brief LinuxCNC's own hexapod-sim sample configuration, unpacked by scripts/fetch-linuxcnc.sh
/// into .cache/linuxcnc (absent: the tests that need it skip).
#pragma once

#include <filesystem>

namespace pkm::test {

/// The hexapod-sim configuration folder (kinematics.hal, hexapod.ini); may not exist.
inline std::filesystem::path linuxcncHexapodSim() {
  return std::filesystem::path(PKM_SOURCE_DIR) /
         ".cache/linuxcnc/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/vismach/"
         "hexapod-sim";
}

}  // namespace pkm::test
