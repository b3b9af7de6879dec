// The drawing-and-margins row of one solved pose (workflow/pose_checks.hpp), shared by
// checkPoses and the frames of a G-code run (gcode_run.hpp).
#pragma once

#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_model.hpp"
#include "pkm/kinematics/pose_rpy.hpp"
#include "pkm/workflow/pose_checks.hpp"

namespace pkm::workflow::detail {

/// A hexapod at `pose` (machine unit, rad): IK, every check, the joint centres.
[[nodiscard]] PoseCheckRow hexapodPoseRow(const kinematics::HexapodModel& model,
                                          kinematics::HexapodData& data,
                                          const kinematics::PoseRpy& pose);

/// An Exechon as held in `data` (a solved configuration) with its check result `check`.
[[nodiscard]] PoseCheckRow exechonDataRow(const kinematics::ExechonModel& model,
                                          const kinematics::ExechonData& data,
                                          const kinematics::ExechonCheckResult& check);

}  // namespace pkm::workflow::detail
