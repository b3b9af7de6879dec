/// @file
/// @brief Best-fit rigid transform between two point sets (Kabsch 1976 / Umeyama 1991 without
/// scale): the registration of a measuring instrument's frame to the machine frame.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "pkm/geometry/rigid_transform.hpp"

namespace pkm::geometry {

/// The rigid transform a_T_b minimising Σ|a_k − a_T_b·b_k|² (SVD of the cross-covariance with the
/// reflection guard, so the result is a proper rotation). Throws pkm::InvalidArgument when the
/// sets differ in size, have fewer than 3 points, contain a non-finite value, or the points of b
/// are collinear (the rotation about their line is undetermined).
[[nodiscard]] RigidTransform fitRigidTransform(const std::vector<Eigen::Vector3d>& a,
                                               const std::vector<Eigen::Vector3d>& b);

}  // namespace pkm::geometry
