// The length unit of the machine a measurement result is for (workflow/machine_unit.hpp).
#include "pkm/workflow/machine_unit.hpp"

#include <fmt/format.h>

#include "pkm/core/error.hpp"
#include "pkm/io/linuxcnc_patch.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::workflow {

std::optional<MachineUnit> machineUnit(const std::string& machine, const std::string& ini) {
  if (!ini.empty()) {
    const io::NamedText text{ini, io::readTextFile(ini)};
    const std::optional<LengthUnit> unit = io::iniLinearUnits(text);
    if (!unit) throw IoError(fmt::format("{}: no [TRAJ] LINEAR_UNITS", ini));
    return MachineUnit{*unit, ini + " [TRAJ] LINEAR_UNITS"};
  }
  if (machine.empty()) return std::nullopt;
  if (io::machineTypeOf(machine) == "exechon")
    return MachineUnit{io::loadExechonMachine(machine).model.unit, machine};
  return MachineUnit{io::loadHexapodMachine(machine).model.unit, machine};
}

std::vector<std::string> unitMismatchWarnings(std::span<const std::string> unstated,
                                              const std::optional<MachineUnit>& machine) {
  std::vector<std::string> out;
  if (!machine || machine->unit == LengthUnit::kMillimetre) return out;
  for (const std::string& name : unstated)
    out.push_back(fmt::format(
        "{}: its header states no length unit, so its positions were read as mm, but the machine "
        "is in {} ({}): inches read as mm? Give --unit inch (or the unit in the header, e.g. "
        "'Target (in)') if they are inches",
        name,
        toString(machine->unit),
        machine->source));
  return out;
}

}  // namespace pkm::workflow
