/// @file
/// @brief Small-angle error motions of a rigid body (six components) as homogeneous transforms
/// (HTMs), exact and to first order. Used for the position-dependent geometric errors (PDGE) of
/// linear axes and of a PKM's working volume.
#pragma once

#include <Eigen/Core>

#include "pkm/geometry/rigid_transform.hpp"

namespace pkm::geometry {

/// An error motion: six components [dx, dy, dz, ex, ey, ez]. (dx, dy, dz) is a translation in the
/// model length unit, (ex, ey, ez) a rotation vector in radians, both in the axes of the frame that
/// the motion perturbs. For a linear axis X these are the ISO 230-1 component errors [EXX, EYX,
/// EZX, EAX, EBX, ECX] (positioning, two straightnesses, roll, pitch, yaw).
using ErrorMotion = Eigen::Matrix<double, 6, 1>;

/// Index of each component in an ErrorMotion (and of each column of an error table of six columns).
enum ErrorComponent : int { kDx = 0, kDy = 1, kDz = 2, kEx = 3, kEy = 4, kEz = 5 };

/// Translational part (dx, dy, dz) of an error motion, model length unit.
[[nodiscard]] inline Eigen::Vector3d errorTranslation(const ErrorMotion& e) { return e.head<3>(); }
/// Rotational part (ex, ey, ez) of an error motion: a rotation vector, radians.
[[nodiscard]] inline Eigen::Vector3d errorRotation(const ErrorMotion& e) { return e.tail<3>(); }

/// The exact HTM of an error motion: E = [exp([ε]×), δ; 0, 1] with δ = (dx, dy, dz) and
/// ε = (ex, ey, ez), i.e. a rotation by the rotation vector ε about the origin of the perturbed
/// frame followed by the translation δ. The SO(3) exponential (so3Exp) is chosen over a product
/// Rx·Ry·Rz because it does not depend on an axis order and matches the project's perturbation
/// convention (docs/conventions.md, "Perturbations"); to first order both are I + [ε]×.
/// Use as nominal_T_actual: actual pose = nominal pose · E (the error acts in the moving frame).
[[nodiscard]] RigidTransform errorMotionHtm(const ErrorMotion& e);

/// The first-order (linearised) HTM of an error motion: [I + [ε]×, δ; 0, 1]. Not a rigid transform
/// (its 3×3 block is not orthonormal); it agrees with errorMotionHtm up to O(|ε|²).
[[nodiscard]] Eigen::Matrix4d errorMotionHtmFirstOrder(const ErrorMotion& e);

/// First-order displacement of a point fixed in the perturbed frame, at `point` (same frame, model
/// length unit): δ + ε × point. Equals errorMotionHtm(e)·point − point up to O(|ε|²·|point|).
[[nodiscard]] Eigen::Vector3d firstOrderDisplacement(const ErrorMotion& e,
                                                     const Eigen::Vector3d& point);

}  // namespace pkm::geometry
