/// @file
/// @brief A calibrated hexapod written into an existing LinuxCNC configuration in place
/// (docs/linuxcnc.md, "pkm linuxcnc install"): the values of the genhexkins `setp` lines of its
/// kinematics HAL file and the [JOINT_n] HOME, HOME_OFFSET, MIN_LIMIT and MAX_LIMIT of its INI,
/// every other byte of both files kept. Text in, text out: the workflow reads, shows the
/// differences, backs up and writes.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::io {

/// One value a patch changes.
struct PatchedValue {
  std::size_t line = 0;  ///< 1-based line in the file
  std::string key;       ///< e.g. "genhexkins.base.0.y", "[JOINT_2] HOME_OFFSET"
  std::string before, after;
};

/// A file's text before and after a patch.
struct TextPatch {
  std::string name;  ///< the input's name
  std::string before, after;
  std::vector<PatchedValue> changes;  ///< the values that differ, in file order
};

/// The files an INI's [HAL] section loads (HALFILE, POSTGUI_HALFILE), as written ("LIB:..."
/// entries included), in order.
[[nodiscard]] std::vector<std::string> iniHalFiles(const NamedText& ini);

/// A value of an INI file and its 1-based line.
struct IniEntry {
  std::string value;  ///< trimmed
  std::size_t line = 0;
};

/// The first `KEY = VALUE` of `section` ("[KINS]", with brackets) in `ini`; nullopt when absent.
[[nodiscard]] std::optional<IniEntry> iniValue(const NamedText& ini,
                                               std::string_view section,
                                               std::string_view key);

/// The HAL file among the INI's iniHalFiles (relative to the INI's folder; "LIB:" entries
/// skipped) that sets genhexkins pins. Throws pkm::IoError "INI: none of the files its [HAL]
/// HALFILE lines load sets genhexkins pins" when there is none.
[[nodiscard]] NamedText genhexkinsHalFile(const NamedText& ini);

/// The INI's [TRAJ] LINEAR_UNITS (mm/metric, inch/in/imperial); nullopt when it has none. Throws
/// pkm::IoError "NAME:LINE: ..." for another value.
[[nodiscard]] std::optional<LengthUnit> iniLinearUnits(const NamedText& ini);

/// The genhexkins pins of `machine` as LinuxCNC needs them (io::writeLinuxcncSetp's values:
/// platform joints relative to the TCP, the spindle offset): ("base.0.x", value), ….
[[nodiscard]] std::vector<std::pair<std::string, double>> genhexkinsPins(
    const HexapodMachine& machine);

/// A joint's INI values for LinuxCNC, whose joint position is the joint-centre distance: HOME =
/// HOME_OFFSET = the distance at the home pose; the limits = the strut's stroke plus its length
/// offset (none when the stroke is unbounded), rounded to at most 12 significant digits when that
/// is within 1e-12 (relative) of the sum, so that a round limit stays round.
struct LinuxcncJointValues {
  double home = 0.0;
  std::optional<double> min_limit, max_limit;
};

/// The six joints' INI values of `machine` (machine length unit).
[[nodiscard]] std::array<LinuxcncJointValues, 6> linuxcncJointValues(const HexapodMachine& machine);

/// `hal` with the value of every `setp genhexkins.PIN VALUE` line whose pin genhexkinsPins gives
/// replaced (the rest of each line, and every other line, byte for byte). Throws pkm::IoError
/// "NAME: no 'setp genhexkins.base.3.y' line" when a base or platform joint coordinate is not
/// set in the file.
[[nodiscard]] TextPatch patchKinematicsHal(const NamedText& hal, const HexapodMachine& machine);

/// `ini` with [JOINT_0..5] HOME, HOME_OFFSET, MIN_LIMIT and MAX_LIMIT set to linuxcncJointValues,
/// where those keys exist; every other byte kept. Throws
/// pkm::IoError "NAME: ..." when the INI's [TRAJ] LINEAR_UNITS differs from the machine's unit or
/// a [JOINT_n] section of the six is missing.
[[nodiscard]] TextPatch patchHexapodIni(const NamedText& ini, const HexapodMachine& machine);

/// A unified diff (3 lines of context) of a patch, "--- NAME" / "+++ NAME"; "" when unchanged.
[[nodiscard]] std::string unifiedDiff(const TextPatch& patch);

}  // namespace pkm::io
