/// @file
/// @brief Random poses inside a hexapod's workspace: uniform draws in a box of commands, kept when
/// every limit of kinematics::checkPose holds (stroke, joint cones, interference, conditioning).
/// Used for the laser-tracker pose sets and as calibration candidate sets.
#pragma once

#include <vector>

#include "pkm/kinematics/hexapod_model.hpp"
#include "pkm/simulation/random.hpp"

namespace pkm::simulation {

/// A box of commands (x, y, z, a, b, c): mm and radians, [lo, hi] per axis.
struct PoseBox {
  Eigen::Matrix<double, 6, 1> lo = Eigen::Matrix<double, 6, 1>::Zero();  ///< lower bounds
  Eigen::Matrix<double, 6, 1> hi = Eigen::Matrix<double, 6, 1>::Zero();  ///< upper bounds
  /// Throws pkm::InvalidArgument when a bound is not finite or lo > hi.
  void validate() const;
};

/// `count` commands drawn uniformly from `box` (six uniform variates per draw, in axis order)
/// and kept in draw order when checkPose on `model` reports no violation. Gives up after
/// `max_draws_per_pose`·count draws. Throws pkm::InvalidArgument for an invalid box, count < 0,
/// max_draws_per_pose < 1, or when too few draws satisfy the limits (the box is mostly outside the
/// workspace).
[[nodiscard]] std::vector<Eigen::VectorXd> sampleHexapodWorkspace(
    const kinematics::HexapodModel& model,
    const PoseBox& box,
    int count,
    RandomStream& rng,
    int max_draws_per_pose = 100);

}  // namespace pkm::simulation
