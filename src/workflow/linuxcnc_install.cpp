// `pkm linuxcnc install` as a workflow (workflow/linuxcnc_install.hpp).
#include "pkm/workflow/linuxcnc_install.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/linuxcnc_machine.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::workflow {
namespace {

namespace fs = std::filesystem;

/// FILE.pkm-backup, or FILE.pkm-backup.N for the first N that does not exist.
std::string backupPath(const std::string& file) {
  std::string p = file + ".pkm-backup";
  for (int n = 1; fs::exists(p); ++n) p = fmt::format("{}.pkm-backup.{}", file, n);
  return p;
}

}  // namespace

void LinuxcncInstallRequest::validate() const {
  if (calibration.empty())
    throw InvalidArgument("--calibration: give the calibrated machine file CAL.json");
  if (ini.empty()) throw InvalidArgument("--ini: give the LinuxCNC configuration's INI file");
}

LinuxcncInstallResult installIntoLinuxcnc(const LinuxcncInstallRequest& request) {
  request.validate();
  if (io::machineTypeOf(request.calibration) != "hexapod")
    throw InvalidArgument(
        fmt::format("{}: not a hexapod: pkm linuxcnc install writes hexapod kinematics "
                    "(genhexkins, pkmhexkins) only",
                    request.calibration));
  const io::HexapodMachine machine = io::loadHexapodMachine(request.calibration);
  io::requireRegisteredFrame(machine, "pkm linuxcnc install");
  const io::NamedText ini = io::readNamedText(request.ini);
  LinuxcncInstallResult result;
  if (const std::optional<io::NamedText> params = io::pkmhexkinsParamsFile(ini)) {
    result.kinematics = "pkmhexkins";
    result.patches = {io::patchPkmhexkinsParameters(
        *params, machine, io::iniLinearUnits(ini).value_or(LengthUnit::kMillimetre))};
  } else {
    const io::NamedText hal = io::genhexkinsHalFile(ini);
    result.patches = {io::patchKinematicsHal(hal, machine), io::patchHexapodIni(ini, machine)};
  }
  for (const io::TextPatch& p : result.patches) result.diff += io::unifiedDiff(p);
  if (!request.force || result.diff.empty()) return result;
  for (const io::TextPatch& p : result.patches) {
    if (p.before == p.after) continue;
    const std::string backup = backupPath(p.name);
    io::writeFileAtomic(backup, p.before, io::Overwrite::kRefuse);
    result.backups.push_back(backup);
    io::writeFileAtomic(p.name, p.after, io::Overwrite::kAllow);
  }
  result.written = true;
  return result;
}

}  // namespace pkm::workflow
