/// @file
/// @brief Hexapod inverse kinematics of many independent poses at once, on the machine's cores:
/// the batch behind `pkm.Hexapod.ik` on a numpy array (docs/python.md) and `pkm hexapod ik`.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::workflow {

/// Strut readings of `rows` poses: row i of `poses` is x, y, z (machine unit), a, b, c (degrees,
/// R = Rz(c) Ry(b) Rx(a), docs/conventions.md) at poses[6 i ...]; its readings l0..l5 go to
/// readings[6 i ...]. With `status` (size rows), each pose is also checked against the machine's
/// limits (kinematics::checkPose) and its status word stored ("ok" or the first violation);
/// without, the readings alone (kinematics::inverseKinematics). Rows are independent, so they are
/// computed in chunks on the cores; the result does not depend on the number of cores.
/// Preconditions: poses.size() == readings.size() == 6 rows; status empty or of size rows.
void hexapodIkRows(const kinematics::HexapodModel& model,
                   std::span<const double> poses,
                   std::span<double> readings,
                   std::span<std::string_view> status = {});

}  // namespace pkm::workflow
