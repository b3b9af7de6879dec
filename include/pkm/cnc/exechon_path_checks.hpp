/// @file
/// @brief Limit checks of an Exechon along an interpolated G-code path (`pkm gcode run`): at every
/// point whether the tool pose is reachable (the tool IK solved), and the configuration checks of
/// kinematics/exechon_checks.hpp (leg stroke, tripod angles alpha and beta and the wrist C and A
/// ranges, singularity proximity, degenerate legs); along the path the joint velocity and
/// acceleration of the legs (model length unit) and of the wrist axes (degrees) against their own
/// limits (checkJointRates). Leg-to-leg interference is not modelled for an Exechon (its legs
/// pass through the base's rotating joints): that check is reported as disabled.
#pragma once

#include <vector>

#include "pkm/cnc/exechon_path.hpp"
#include "pkm/cnc/joint_checks.hpp"
#include "pkm/kinematics/exechon_model.hpp"

namespace pkm::cnc {

/// Rate limits of an Exechon: legs A, B, C share `legs` (length unit per s, per s²), the wrist
/// axes C and A share `wrist_velocity` (deg/s) and `wrist_acceleration` (deg/s²); the sixth slot
/// is unlimited.
[[nodiscard]] JointRateLimits exechonRateLimits(const MotionLimits& legs,
                                                double wrist_velocity,
                                                double wrist_acceleration);

/// Names of the Exechon joint slots: "leg A", "leg B", "leg C", "wrist C", "wrist A".
[[nodiscard]] std::string exechonJointName(int joint);

/// Runs every check along points[0..n) with the converter's samples. Reach: a violation at each
/// point the tool IK could not solve (item: the solver's status word, margin −1). The other pose
/// checks are evaluated at the solved points only; joint_angle reports the nearest of alpha, beta,
/// wrist C and wrist A (rad). `keep_violations`: violations each check keeps in its
/// CheckStat::events (0: none). Throws pkm::InvalidArgument on size mismatch or invalid limits.
[[nodiscard]] PathCheckReport checkExechonPath(const kinematics::ExechonModel& model,
                                               const std::vector<PathPoint>& points,
                                               const std::vector<ExechonPathSample>& samples,
                                               const JointRateLimits& limits,
                                               std::size_t keep_violations = 0);

}  // namespace pkm::cnc
