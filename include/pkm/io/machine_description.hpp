/// @file
/// @brief The human-readable description of a hexapod machine (`pkm hexapod describe`, the head of
/// `pkm demo`): name, source, units, home, offsets, FK settings, the strut table and the checks at
/// home.
#pragma once

#include <string>

#include "pkm/io/hexapod_machine.hpp"

namespace pkm::io {

/// The description of `machine`, one item per line, each line ending in a newline: the strut
/// table lists the base joints (world frame) and platform joints (platform frame) in the machine
/// unit, offsets, strokes, the readings at home and the joint cone limits in degrees ("-": none);
/// the last line is kinematics::checkPose at home (status, scaled condition number, closest
/// struts).
[[nodiscard]] std::string describeHexapodMachine(const HexapodMachine& machine);

}  // namespace pkm::io
