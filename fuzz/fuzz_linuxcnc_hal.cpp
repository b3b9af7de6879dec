// libFuzzer harness for the LinuxCNC genhexkins HAL reader (io::parseLinuxcncHal, the text form
// of readLinuxcncHal) with an optional INI after a line "%%ini", and for patching a HAL file in
// place (io::patchKinematicsHal): any input reads or throws pkm::IoError. A machine that reads is
// written as a setp block (io::writeLinuxcncSetp) that reads again with the same base joints. A
// patch keeps the number of lines, and patching its result again changes nothing.
#include <algorithm>
#include <optional>
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/linuxcnc_patch.hpp"
#include "pkm/io/machine_loader.hpp"

namespace {

const pkm::io::HexapodMachine& simMachine() {
  static const pkm::io::HexapodMachine m = pkm::io::builtinMachine("hexapod-linuxcnc-sim");
  return m;
}

void checkPatch(const pkm::io::NamedText& hal) {
  pkm::io::TextPatch patch;
  if (!pkm::fuzz::accepts([&] { patch = pkm::io::patchKinematicsHal(hal, simMachine()); })) return;
  pkm::fuzz::check(patch.before == hal.text, "a patch keeps the text it patched");
  pkm::fuzz::check(std::count(patch.before.begin(), patch.before.end(), '\n') ==
                       std::count(patch.after.begin(), patch.after.end(), '\n'),
                   "a patch keeps the number of lines");
  (void)pkm::io::unifiedDiff(patch);
  const pkm::io::TextPatch again =
      pkm::io::patchKinematicsHal({hal.name, patch.after}, simMachine());
  pkm::fuzz::check(again.changes.empty() && again.after == patch.after,
                   "patching a patched file changes nothing");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const pkm::fuzz::Split parts = pkm::fuzz::splitAt(pkm::fuzz::asText(data, size), "%%ini");
  const pkm::io::NamedText hal{"kinematics.hal", parts.first};
  std::optional<pkm::io::NamedText> ini;
  if (parts.found) ini = pkm::io::NamedText{"machine.ini", parts.second};
  checkPatch(hal);
  pkm::io::HexapodMachine m;
  if (!pkm::fuzz::accepts([&] { m = pkm::io::parseLinuxcncHal(hal, ini); })) return 0;
  const std::string setp = pkm::io::writeLinuxcncSetp(m);
  pkm::io::HexapodMachine back;
  pkm::fuzz::check(pkm::fuzz::accepts([&] {
                     back = pkm::io::parseLinuxcncHal({"setp.hal", setp});
                   }),
                   "a setp block written back reads");
  for (std::size_t i = 0; i < m.model.struts.size(); ++i)
    pkm::fuzz::check(back.model.struts[i].world_p_base == m.model.struts[i].world_p_base,
                     "a setp block written back has the same base joints");
  return 0;
}
