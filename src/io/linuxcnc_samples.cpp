// LinuxCNC's sample configurations that pkm reads as machines (io/linuxcnc_samples.hpp).
#include "pkm/io/linuxcnc_samples.hpp"

#include <system_error>

namespace pkm::io {

std::vector<LinuxcncSample> installedLinuxcncSamples(const std::filesystem::path& root) {
  struct Known {
    const char* name;
    const char* folder;
    const char* hal;
    const char* ini;
    const char* description;
  };
  static constexpr Known kKnown[] = {
      {"linuxcnc-hexapod-sim",
       "sim/axis/vismach/hexapod-sim",
       "kinematics.hal",
       "hexapod.ini",
       "LinuxCNC's hexapod-sim sample (genhexkins)"},
  };
  std::vector<LinuxcncSample> out;
  for (const Known& k : kKnown) {
    const std::filesystem::path folder = root / k.folder;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(folder / k.hal, ec) ||
        !std::filesystem::is_regular_file(folder / k.ini, ec))
      continue;
    out.push_back({k.name, folder / k.hal, folder / k.ini, k.description});
  }
  return out;
}

}  // namespace pkm::io
