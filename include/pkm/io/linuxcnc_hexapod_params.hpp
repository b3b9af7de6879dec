/// @file
/// @brief The parameter file of pkmhexkins, pkm's LinuxCNC kinematics component for hexapods
/// (src/linuxcnc/, docs/linuxcnc.md "The pkmhexkins parameter file"): the machine's geometry,
/// home pose and forward-kinematics settings as `name value...` lines that the component reads
/// and checks at load (`loadrt pkmhexkins params=FILE`).
#pragma once

#include <string>

#include "pkm/io/hexapod_machine.hpp"

namespace pkm::io {

/// The pkmhexkins parameter file of `machine`: per strut i `base.i` (world frame),
/// `platform.i` (platform frame) and `length-offset.i`; `tool` (the controlled point in the
/// platform frame); `spindle-offset` (HexapodModel::spindle_offset, a genhexkins tool-offset
/// imported with the machine included: G43 lengths come on the component's tool-offset pin);
/// `home` (x y z in the machine's unit, a b c in degrees: LinuxCNC's [TRAJ] HOME and the second
/// forward-kinematics seed); the FkOptions as `convergence-criterion`, `limit-iterations`,
/// `max-backtracks`, `singular-pivot-ratio`, `max-step-translation`, `max-step-rotation` (rad),
/// `continuation-step`, and `max-error 0` (no limit). Lengths in the machine's unit (the
/// component does not convert), numbers in shortest round-trip form, so the C code reads the
/// model's values exactly (home angles within one unit in the last place of the degree
/// conversion). Strokes, joint cones and the strut diameter are not part of it: LinuxCNC's
/// [JOINT_n] MIN_LIMIT/MAX_LIMIT carry the strokes.
[[nodiscard]] std::string linuxcncHexapodParameters(const HexapodMachine& machine);

}  // namespace pkm::io
