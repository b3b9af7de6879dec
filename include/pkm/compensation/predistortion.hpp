/// @file
/// @brief Pose pre-distortion for a hexapod whose controller keeps its nominal kinematics (e.g. a
/// LinuxCNC genhexkins set-up that is not re-parameterised): the command that makes the calibrated
/// (true) machine reach a desired pose (docs/compensation.md, "Pre-distortion").
///
///   q      = IK_calibrated(X)        the strut readings at which the real machine is at X
///   X_cmd  = FK_nominal(q)           the pose the nominal controller turns into those readings
///
/// so IK_nominal(X_cmd) = IK_calibrated(X): the controller commands exactly the struts the real
/// machine needs. Poses are TCP poses in the project convention (docs/conventions.md "Pose":
/// R = Rz(c)·Ry(b)·Rx(a), fixed axes); inside the library a, b, c are radians (`PoseRpy::rpy`),
/// converted from/to the degrees of files and the CLI at the boundary.
#pragma once

#include <span>
#include <vector>

#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::compensation {

/// Options of predistort.
struct PredistortionOptions {
  /// The nominal FK solve (tolerance on the strut residual, model length unit).
  kinematics::FkOptions fk;
};

/// The pre-distorted command of one pose.
struct PredistortionResult {
  kinematics::PoseRpy command;       ///< X_cmd = FK_nominal(q); valid only when ok()
  kinematics::StrutVector readings;  ///< q = IK_calibrated(X), model length unit
  kinematics::FkSummary fk;          ///< the nominal FK solve (status, iterations, residual)
  /// True when the FK converged: command is then usable.
  [[nodiscard]] bool ok() const { return fk.ok(); }
};

/// X_cmd = FK_nominal(IK_calibrated(desired)), FK seeded at `seed` (the desired pose, or the
/// previous command along a path). Failure to converge is a result (fk.status), not an exception.
/// Throws pkm::InvalidArgument when a model fails validate(), the models' length units differ,
/// `desired` is not finite or the options are invalid.
[[nodiscard]] PredistortionResult predistort(const kinematics::HexapodModel& nominal,
                                             const kinematics::HexapodModel& calibrated,
                                             const kinematics::PoseRpy& desired,
                                             const kinematics::PoseRpy& seed,
                                             const PredistortionOptions& options = {});
/// As above, seeded at `desired`.
[[nodiscard]] PredistortionResult predistort(const kinematics::HexapodModel& nominal,
                                             const kinematics::HexapodModel& calibrated,
                                             const kinematics::PoseRpy& desired,
                                             const PredistortionOptions& options = {});

/// The commands of a sequence of poses (a path). Pose k's FK is seeded with desired_k plus the
/// previous converged correction (command_{k−1} − desired_{k−1}), which is nearly constant along a
/// path; the first, and any after a failure, with desired_k. One result per pose. Throws as
/// predistort.
[[nodiscard]] std::vector<PredistortionResult> predistortPath(
    const kinematics::HexapodModel& nominal,
    const kinematics::HexapodModel& calibrated,
    std::span<const kinematics::PoseRpy> desired,
    const PredistortionOptions& options = {});

}  // namespace pkm::compensation
