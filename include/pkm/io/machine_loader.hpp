/// @file
/// @brief Loads a machine from a JSON file, a LinuxCNC HAL file, or a built-in name.
#pragma once

#include <string>
#include <vector>

#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/geometric_errors.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/linuxcnc_hal.hpp"

namespace pkm::io {

/// Name of the embedded default machine (data/machines/hexapod-default.json).
inline constexpr const char* kDefaultMachine = "hexapod-default";
/// Name of the embedded default Exechon machine (data/machines/mxt700s-like.json).
inline constexpr const char* kDefaultExechonMachine = "mxt700s-like";

/// Names of the machine files embedded at build time (file stems of data/machines/*.json), of the
/// given type ("hexapod", "exechon"), or of every type when `type` is empty.
[[nodiscard]] std::vector<std::string> builtinMachineNames(const std::string& type = "hexapod");

/// The "type" of a machine JSON text ("hexapod" when the key is absent or the text is not an
/// object; the typed readers report malformed text).
[[nodiscard]] std::string machineType(const std::string& text);

/// The type of machine `spec` names: an existing file's "type" (machineType), "exechon" for a
/// built-in Exechon's name, else "hexapod" (the loaders report a spec that names nothing).
/// Throws pkm::IoError when the file cannot be read.
[[nodiscard]] std::string machineTypeOf(const std::string& spec);

/// Parses the embedded hexapod machine `name` ("default" means kDefaultMachine). Throws
/// pkm::IoError if there is no hexapod by that name.
[[nodiscard]] HexapodMachine builtinMachine(const std::string& name);

/// `spec` ending in ".hal": readLinuxcncHal; a pkmhexkins parameter file (".params") with
/// hal.ini_path the INI that loads it: that configuration's hexapod (readLinuxcncHexapod); an
/// existing file: readHexapodJson; otherwise a built-in name ("default" means kDefaultMachine).
/// Throws pkm::IoError naming the file and line on bad input.
[[nodiscard]] HexapodMachine loadHexapodMachine(const std::string& spec,
                                                const HalReadOptions& hal = {});

/// An existing file: readExechonJson; otherwise a built-in Exechon name ("default" means
/// kDefaultExechonMachine). Throws pkm::IoError naming the file and line on bad input.
[[nodiscard]] ExechonMachine loadExechonMachine(const std::string& spec);

/// Names of the geometric-error files embedded at build time (file stems of data/errors/*.json).
[[nodiscard]] std::vector<std::string> builtinErrorNames();

/// An existing file: readGeometricErrorsJson; otherwise a built-in error set by name. Throws
/// pkm::IoError naming the file and line on bad input.
[[nodiscard]] kinematics::GeometricErrors loadGeometricErrors(const std::string& spec);

}  // namespace pkm::io
