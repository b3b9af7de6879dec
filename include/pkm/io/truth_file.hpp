/// @file
/// @brief A hexapod's truth read back from the truth.json that `pkm simulate` writes
/// (docs/formats.md, "truth.json"): the nominal machine, the injected assembly errors and the
/// actuation, to build the same true machine again (e.g. the simulated machine in LinuxCNC's loop,
/// docs/linuxcnc.md).
#pragma once

#include <string>

#include "pkm/io/hexapod_machine.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"

namespace pkm::io {

/// A hexapod truth.
struct HexapodTruth {
  std::string source;                        ///< the file
  std::string machine;                       ///< the nominal machine's spec, as the file names it
  HexapodMachine nominal;                    ///< that machine, loaded (machine_loader.hpp)
  simulation::HexapodAssemblyErrors errors;  ///< true − nominal, mm
  simulation::StrutActuation actuation;      ///< encoder resolution, backlash, repeatability
};

/// Parses a truth.json text (`source` names it in messages) whose "machine_kind" is "hexapod":
/// "machine", "errors" {"base_joint", "platform_joint": six [x, y, z]; "length_offset": six
/// numbers} and "actuation" {"encoder_resolution", "backlash": six, "repeatability_sigma"}; other
/// keys are ignored. Relative machine paths are taken from the file's folder. The nominal machine
/// must be in mm. Throws pkm::IoError "SOURCE:LINE: /json/pointer: message" for malformed JSON,
/// a missing or mistyped key, a non-finite number, an Exechon truth or a machine that cannot be
/// loaded.
[[nodiscard]] HexapodTruth parseHexapodTruth(const std::string& text, const std::string& source);

/// Reads and parses a truth.json file. Throws pkm::IoError naming the file.
[[nodiscard]] HexapodTruth readHexapodTruth(const std::string& path);

/// The true machine of `truth`: a HexapodVirtualMachine of its nominal model, errors and
/// actuation, reset with `noise_seed`.
[[nodiscard]] simulation::HexapodVirtualMachine trueMachine(const HexapodTruth& truth,
                                                            std::uint64_t noise_seed = 0);

}  // namespace pkm::io
