/// @file
/// @brief Pose planning for calibration (observability indices, identifiability.hpp): choose N
/// measurement poses from a candidate set so that an observability index of the identification
/// Jacobian is largest, by greedy selection followed by exchange passes (DETMAX-style; Mitchell
/// 1974). Each step ranks the candidates by their D-optimal gain (matrix determinant lemma, cheap)
/// and evaluates the chosen index exactly on the best 24 (on all of them for O1, which the gain
/// orders exactly).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "pkm/calibration/hexapod_parameters.hpp"
#include "pkm/calibration/identifiability.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::calibration {

/// What each planned pose will measure.
enum class PlannedMeasurement {
  kFullPose,  ///< 6 equations (tracker with 6-DOF probe)
  kPoint,     ///< 3 equations (tracker SMR at the TCP)
};

/// Settings of planHexapodPoses.
struct PosePlanOptions {
  int count = 30;                                      ///< poses to choose, ≥ 1
  ObservabilityIndex index = ObservabilityIndex::kO1;  ///< the index to maximise
  PlannedMeasurement measurement = PlannedMeasurement::kFullPose;
  HexapodParameterMask free = allHexapodParametersFree();  ///< parameters to identify
  int exchange_passes = 2;  ///< passes of single swaps after the greedy phase, ≥ 0
  /// Throws pkm::InvalidArgument naming the field when a setting is unusable.
  void validate() const;
};

/// The chosen poses and the quality of the plan.
struct PosePlan {
  std::vector<int> chosen;   ///< indices into the candidates, in the order chosen
  double index_value = 0.0;  ///< the maximised index of the chosen set
  /// All five indices of the chosen set (O1..O5), for comparison.
  std::vector<double> indices;
  double condition_number = 0.0;  ///< of the column-scaled Jacobian of the chosen set
  int rank = 0;                   ///< its numerical rank
  /// Mean index over 20 random subsets of the same size from the candidates (a baseline), seeded
  /// deterministically.
  double random_baseline = 0.0;
  int swaps = 0;  ///< exchanges made
};

/// Chooses options.count of `candidates` (TCP poses, all assumed inside the workspace — see
/// simulation::sampleHexapodWorkspace) for identifying the free parameters of `model`. The
/// Jacobian columns are scaled by their norms over all candidates, so the indices are unit-free.
/// Throws pkm::InvalidArgument when options are invalid or there are fewer candidates than count.
[[nodiscard]] PosePlan planHexapodPoses(const kinematics::HexapodModel& model,
                                        const std::vector<kinematics::PoseRpy>& candidates,
                                        const PosePlanOptions& options);

/// The planner of planHexapodPoses for any machine: `blocks` are the identification Jacobian rows
/// of each candidate (rows of one measurement × the free unknowns; all of one shape and finite).
/// Chooses `count` of them maximising `index`, with `exchange_passes` exchange passes; the columns
/// are scaled by their norms over all candidates. Throws pkm::InvalidArgument for fewer blocks
/// than count, count < 1, exchange_passes < 0, no column, or blocks of different shapes.
[[nodiscard]] PosePlan planFromJacobians(std::vector<Eigen::MatrixXd> blocks,
                                         int count,
                                         ObservabilityIndex index,
                                         int exchange_passes);

}  // namespace pkm::calibration
