// libFuzzer harness for the LinuxCNC INI readers (io/linuxcnc_patch.hpp: [HAL] HALFILE entries,
// [TRAJ] LINEAR_UNITS, patching [JOINT_n] values in place; io::applyLinuxcncIni): any input reads
// or throws pkm::IoError. A patch keeps the number of lines, and patching its result again changes
// nothing; a machine the INI applies to keeps ordered strokes.
#include <algorithm>
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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const pkm::io::NamedText ini{"machine.ini", std::string(pkm::fuzz::asText(data, size))};
  (void)pkm::io::iniHalFiles(ini);
  pkm::fuzz::accepts([&] { (void)pkm::io::iniLinearUnits(ini); });
  pkm::fuzz::accepts([&] {
    pkm::io::HexapodMachine m = simMachine();
    pkm::io::applyLinuxcncIni(ini, m);
    for (const auto& s : m.model.struts)
      pkm::fuzz::check(!(s.min_reading > s.max_reading), "MIN_LIMIT <= MAX_LIMIT");
  });
  pkm::io::TextPatch patch;
  if (!pkm::fuzz::accepts([&] { patch = pkm::io::patchHexapodIni(ini, simMachine()); })) return 0;
  pkm::fuzz::check(patch.before == ini.text, "a patch keeps the text it patched");
  pkm::fuzz::check(std::count(patch.before.begin(), patch.before.end(), '\n') ==
                       std::count(patch.after.begin(), patch.after.end(), '\n'),
                   "a patch keeps the number of lines");
  (void)pkm::io::unifiedDiff(patch);
  const pkm::io::TextPatch again = pkm::io::patchHexapodIni({ini.name, patch.after}, simMachine());
  pkm::fuzz::check(again.changes.empty() && again.after == patch.after,
                   "patching a patched file changes nothing");
  return 0;
}
