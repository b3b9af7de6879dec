/// @file
/// @brief The hexapod a LinuxCNC configuration computes with, read from its files: the genhexkins
/// `setp` lines of a HAL file it loads, or the parameter file of pkm's own component pkmhexkins
/// (`[KINS] KINEMATICS = pkmhexkins params=FILE`, docs/linuxcnc.md "The pkmhexkins parameter
/// file"), with the INI's home, unit and joint limits.
#pragma once

#include <optional>
#include <string>

#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/linuxcnc_patch.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::io {

/// Parses a pkmhexkins parameter file (io::linuxcncHexapodParameters writes it): `base.i`,
/// `platform.i` (three numbers each), `length-offset.i` for the six struts, `tool` (three),
/// `spindle-offset`, `home` (x y z, a b c in degrees) and the forward-kinematics settings
/// (`convergence-criterion`, `limit-iterations`, `max-backtracks`, `singular-pivot-ratio`,
/// `max-step-translation`, `max-step-rotation` in rad, `continuation-step`; `max-error` is read
/// and ignored); `#` starts a comment. Lengths stay in the file's unit, which is `unit` (the INI's
/// LINEAR_UNITS). Strokes, cones and the strut diameter are not in the file: unbounded. Throws
/// pkm::IoError "NAME:LINE: message" for an unknown name, a wrong count of numbers, a non-finite
/// number, a name given twice or a strut coordinate missing.
[[nodiscard]] HexapodMachine parsePkmhexkinsParameters(const NamedText& params,
                                                       LengthUnit unit = LengthUnit::kMillimetre);

/// The parameter file of a configuration that loads pkmhexkins: the `params=FILE` of its [KINS]
/// KINEMATICS line (FILE relative to the INI's folder), read; nullopt when the INI loads another
/// module. Throws pkm::IoError naming the INI's line when the file cannot be read.
[[nodiscard]] std::optional<NamedText> pkmhexkinsParamsFile(const NamedText& ini);

/// The hexapod of the configuration `ini`: pkmhexkins' parameter file when its [KINS] loads
/// pkmhexkins with one, else the HAL file among its HALFILEs that sets genhexkins pins
/// (io::readLinuxcncHal); then the INI's [TRAJ] HOME, LINEAR_UNITS and [JOINT_n] limits
/// (io::applyLinuxcncIni). `kinematics` is set to "pkmhexkins" or "genhexkins" and `file` to the
/// file read. Throws pkm::IoError naming the INI when neither is found, or the file and line of a
/// malformed entry.
struct LinuxcncHexapod {
  HexapodMachine machine;
  std::string kinematics;  ///< "pkmhexkins" or "genhexkins"
  std::string file;        ///< the parameter or HAL file the geometry came from
};
[[nodiscard]] LinuxcncHexapod readLinuxcncHexapod(const std::string& ini);

/// `params` (a pkmhexkins parameter file) replaced by linuxcncHexapodParameters(machine): every
/// value line whose numbers differ is a change (key = the parameter's name, line = its line in the
/// new text). The INI is not touched: pkmhexkins' joints are the struts' encoder readings, which a
/// calibration does not change (docs/linuxcnc.md, "pkm linuxcnc install"). Throws pkm::IoError as
/// parsePkmhexkinsParameters for a file that is not one, and when `machine`'s unit is not `unit`.
[[nodiscard]] TextPatch patchPkmhexkinsParameters(const NamedText& params,
                                                  const HexapodMachine& machine,
                                                  LengthUnit unit);

}  // namespace pkm::io
