/// @file
/// @brief The length unit of the machine a measurement result is for (`--machine M` or `--ini
/// INI` of `pkm analyze iso230-2` and `pkm compensate table`, docs/analysis.md "Machine unit"):
/// the unit a controller table is written in, and the check that files without a stated unit
/// were not read in the wrong one.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pkm/core/units.hpp"

namespace pkm::workflow {

/// A machine's length unit and where it was read.
struct MachineUnit {
  LengthUnit unit = LengthUnit::kMillimetre;
  /// What gave it: "INI [TRAJ] LINEAR_UNITS" or the machine's spec (file or built-in name).
  std::string source;
};

/// The unit of the machine a result is for: with `ini` (a LinuxCNC INI, whatever the machine's
/// kinematics), its [TRAJ] LINEAR_UNITS; else `machine`'s unit (a machine file, a LinuxCNC
/// `.hal` file or a built-in name); nullopt when both are "". Throws pkm::IoError for an
/// unreadable or malformed file, or an INI without LINEAR_UNITS.
[[nodiscard]] std::optional<MachineUnit> machineUnit(const std::string& machine,
                                                     const std::string& ini);

/// Warnings for the inputs (`unstated`: their names) whose lengths were read as millimetres for
/// want of a stated unit, when the machine is in inches: the likely cause and the option that
/// fixes it. None without a machine or for a millimetre machine.
[[nodiscard]] std::vector<std::string> unitMismatchWarnings(
    std::span<const std::string> unstated, const std::optional<MachineUnit>& machine);

}  // namespace pkm::workflow
