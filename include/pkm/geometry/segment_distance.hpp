/// @file
/// @brief Minimum distance between two line segments in 3-D (used for leg-to-leg interference).
#pragma once

#include <Eigen/Core>

namespace pkm::geometry {

/// Closest points of two segments and their distance.
struct SegmentDistance {
  double distance = 0.0;                        ///< |p - q|, same unit as the inputs
  double s = 0.0;                               ///< parameter of p on segment 1, in [0, 1]
  double t = 0.0;                               ///< parameter of q on segment 2, in [0, 1]
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  ///< closest point on segment 1
  Eigen::Vector3d q = Eigen::Vector3d::Zero();  ///< closest point on segment 2
};

/// Minimum distance between segment [p0, p1] and segment [q0, q1]. Handles parallel and degenerate
/// (zero-length) segments exactly.
[[nodiscard]] SegmentDistance segmentDistance(const Eigen::Vector3d& p0,
                                              const Eigen::Vector3d& p1,
                                              const Eigen::Vector3d& q0,
                                              const Eigen::Vector3d& q1);

}  // namespace pkm::geometry
