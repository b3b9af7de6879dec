/// @file
/// @brief Pose planning for an Exechon calibration by tracker points (docs/calibration.md, "Pose
/// planning"): the identification Jacobian of each candidate configuration is ∂p/∂θ of the tracker
/// target for the free parameters of exechon_parameters.hpp (exechonTargetJacobian), and the
/// observability planner of pose_planning.hpp chooses the poses.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "pkm/calibration/exechon_parameters.hpp"
#include "pkm/calibration/identifiability.hpp"
#include "pkm/calibration/pose_planning.hpp"
#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::calibration {

/// Settings of planExechonPoses.
struct ExechonPosePlanOptions {
  int count = 30;                                      ///< poses to choose, ≥ 1
  ObservabilityIndex index = ObservabilityIndex::kO1;  ///< the index to maximise
  /// Parameters to identify. All 26 by default: the base placement's columns span the same rigid
  /// motions as a tracker frame, so the plan also suits tracker-frame data.
  ExechonParameterMask free = allExechonParametersFree();
  int exchange_passes = 2;  ///< passes of single swaps after the greedy phase, ≥ 0
  Eigen::Vector3d target_offset = Eigen::Vector3d::Zero();  ///< tracker target, tool frame
  kinematics::FkOptions fk;                                 ///< the FK inside the Jacobian
  /// Throws pkm::InvalidArgument naming the field when a setting is unusable.
  void validate() const;
};

/// Chooses options.count of `candidates` (configurations inside the workspace, e.g. from the tool
/// IK of sampled tool poses) for identifying the free parameters of `model` from tracker points.
/// Throws pkm::InvalidArgument when the options are invalid, there are fewer candidates than
/// count, or the FK fails at a candidate (a configuration outside the model's assembly).
[[nodiscard]] PosePlan planExechonPoses(
    const kinematics::ExechonModel& model,
    const std::vector<kinematics::ExechonConfiguration>& candidates,
    const ExechonPosePlanOptions& options);

}  // namespace pkm::calibration
