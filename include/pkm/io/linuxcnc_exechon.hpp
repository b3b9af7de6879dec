/// @file
/// @brief The parameter file of pkmexechonkins, the LinuxCNC kinematics component for an Exechon
/// (src/linuxcnc/, docs/linuxcnc.md "Exechon kinematics in LinuxCNC"): the machine's model as
/// `name value...` lines that the component's C code reads at load.
#pragma once

#include <string>

#include "pkm/io/exechon_machine.hpp"

namespace pkm::io {

/// The pkmexechonkins parameter file of `machine`: Zoppi's tripod (dA ... hz, the branch signs),
/// the legs' length offsets and strokes, the alpha, beta, C and A ranges (degrees, `inf` when
/// open), the wrist (axes, zero offsets in degrees, senses, tool length), world_T_zoppi as a
/// row-major rotation and a position, the home configuration (degrees and the machine's unit), the
/// condition-number limit and the forward-kinematics settings. Lengths in the machine's unit (the
/// component does not convert), numbers in shortest round-trip form, so the C code reads the
/// model's values exactly (angles within one unit in the last place of the degree conversion).
/// A hybrid machine's X2/Y2 are not part of it: the tripod's world frame is the PKM frame P.
[[nodiscard]] std::string linuxcncExechonParameters(const ExechonMachine& machine);

}  // namespace pkm::io
