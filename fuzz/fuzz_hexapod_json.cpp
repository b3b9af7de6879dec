// libFuzzer harness for io::parseHexapodJson (hexapod machine files, docs/machine-format.md): any
// input parses or throws pkm::IoError. A machine that parses is written back
// (io::writeHexapodJson) to a file that parses again with the same joints, length offsets and
// stroke limits; describing it and writing its LinuxCNC setp block do not throw.
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/machine_description.hpp"

namespace {

bool sameStruts(const pkm::kinematics::HexapodModel& a, const pkm::kinematics::HexapodModel& b) {
  for (std::size_t i = 0; i < a.struts.size(); ++i) {
    const auto &s = a.struts[i], &t = b.struts[i];
    if (s.world_p_base != t.world_p_base || s.platform_p_joint != t.platform_p_joint ||
        s.length_offset != t.length_offset || s.min_reading != t.min_reading ||
        s.max_reading != t.max_reading)
      return false;
  }
  return a.unit == b.unit && a.tool_offset == b.tool_offset;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(pkm::fuzz::asText(data, size));
  pkm::io::HexapodMachine m;
  if (!pkm::fuzz::accepts([&] { m = pkm::io::parseHexapodJson(text, "fuzz.json"); })) return 0;
  const std::string written = pkm::io::writeHexapodJson(m);
  pkm::io::HexapodMachine back;
  pkm::fuzz::check(pkm::fuzz::accepts([&] { back = pkm::io::parseHexapodJson(written, "back"); }),
                   "a machine written back parses");
  pkm::fuzz::check(sameStruts(m.model, back.model), "a machine written back has the same struts");
  (void)pkm::io::describeHexapodMachine(m);
  (void)pkm::io::writeLinuxcncSetp(m);
  return 0;
}
