/// @file
/// @brief RigidTransform: the one rigid-transform (SE(3)) type of the library, its constructors
/// and the SE(3) exponential and logarithm maps.
///
/// Naming is frame-explicit: `a_T_b` is the pose of frame b in frame a, so that a point given in b
/// maps to a as x_a = a_T_b · x_b (= a_R_b · x_b + a_p_b). Transforms compose by matching inner
/// frames, a_T_c = a_T_b * b_T_c, and invert as b_T_a = a_T_b.inverse(Eigen::Isometry). Points
/// are in the model length unit, rotations and rotation vectors in radians
/// (docs/conventions.md, "Frames and names" and "Pose").
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pkm::geometry {

/// A rigid transform a_T_b = [a_R_b, a_p_b; 0, 1]: a rotation matrix (`linear()`) and a translation
/// (`translation()`); `T * x` is `linear() * x + translation()` up to rounding (Eigen's operator*
/// adds in another order, so spell out the latter where results must be reproducible bit for bit).
/// Eigen's default constructor leaves it uninitialised: start from RigidTransform::Identity() or
/// one of the functions below.
using RigidTransform = Eigen::Isometry3d;

/// A twist ξ = (v, w) ∈ ℝ⁶, the coordinates of se(3): v (first three) the translational part in
/// the model length unit, w (last three) a rotation vector in radians; ξ^ = [[w]×, v; 0, 0].
using Twist = Eigen::Matrix<double, 6, 1>;

/// The transform [R, p; 0, 1]. Precondition (asserted, not checked): R is a rotation matrix.
[[nodiscard]] RigidTransform makeTransform(const Eigen::Matrix3d& R, const Eigen::Vector3d& p);

/// The pure translation [I, p; 0, 1].
[[nodiscard]] RigidTransform translationTransform(const Eigen::Vector3d& p);

/// The pure rotation [exp([w]×), 0; 0, 1] for a rotation vector w (radians, so3Exp).
[[nodiscard]] RigidTransform rotationTransform(const Eigen::Vector3d& w);

/// T perturbed in the project's pose-perturbation convention (docs/conventions.md,
/// "Perturbations"): (exp([δω]×)·R, p + δt) for δ = (δt, δω), δt in the model length unit and δω
/// a rotation vector in radians, both in the axes of T's reference frame (the left frame a of
/// a_T_b). Not se3Exp(δ)·T: the translation is not rotated by δω.
[[nodiscard]] RigidTransform perturbedTransform(const RigidTransform& T, const Twist& delta);

/// The SE(3) exponential exp(ξ^) of a twist ξ = (v, w), in closed form:
/// [exp([w]×), J_l(w)·v; 0, 1] with J_l the left Jacobian of SO(3) (so3LeftJacobian): Murray, Li &
/// Sastry, "A Mathematical Introduction to Robotic Manipulation" (1994), ch. 2 (exponential of a
/// twist); Barfoot, "State Estimation for Robotics" (2017), ch. 7 (SE(3) exponential map). Exact
/// for any |w|, smooth at w = 0.
[[nodiscard]] RigidTransform se3Exp(const Twist& xi);

/// The SE(3) logarithm: the twist ξ = (v, w) with se3Exp(ξ) == T and |w| in [0, pi]:
/// w = so3Log(R), v = J_l(w)⁻¹·p with the closed-form inverse
/// J_l⁻¹ = I − ½[w]× + (1 − (θ/2)·cot(θ/2))/θ²·[w]×², θ = |w| (Barfoot 2017, ch. 7; a Taylor
/// series near θ = 0). At θ = pi the rotation axis' sign is that of so3Log. Precondition
/// (asserted, not checked): T.linear() is a rotation matrix.
[[nodiscard]] Twist se3Log(const RigidTransform& T);

}  // namespace pkm::geometry
