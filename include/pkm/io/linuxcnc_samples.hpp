/// @file
/// @brief LinuxCNC's own sample configurations that pkm reads as machines (docs/web.md, the
/// machine list): the hexapod of `sim/axis/vismach/hexapod-sim` (genhexkins, its kinematics.hal
/// with hexapod.ini), where LinuxCNC (linuxcnc-uspace) has installed its examples.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pkm::io {

/// Where Debian's linuxcnc-uspace installs the sample configurations.
inline constexpr const char* kLinuxcncSampleRoot =
    "/usr/share/doc/linuxcnc/examples/sample-configs";

/// One sample configuration as a machine: its name in machine lists ("linuxcnc-hexapod-sim"),
/// its HAL file and INI, and a line saying what it is.
struct LinuxcncSample {
  std::string name;
  std::filesystem::path hal, ini;
  std::string description;
};

/// The samples pkm knows that are present under `root` (both files readable); none when LinuxCNC
/// is not installed. Never throws.
[[nodiscard]] std::vector<LinuxcncSample> installedLinuxcncSamples(
    const std::filesystem::path& root = kLinuxcncSampleRoot);

}  // namespace pkm::io
