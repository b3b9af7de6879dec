/// @file
/// @brief Rotations: hat/vee, exponential and logarithm maps of SO(3), and the LinuxCNC
/// roll-pitch-yaw convention R = Rz(c)·Ry(b)·Rx(a) (docs/conventions.md, "Pose").
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace pkm::geometry {

namespace detail {
/// Below this angle, rad, so3Exp and so3LeftJacobian use their Taylor series.
inline constexpr double kSo3SeriesBelow = 1e-3;
}  // namespace detail

/// Skew-symmetric matrix [w]x such that [w]x·v = w × v.
[[nodiscard]] Eigen::Matrix3d hat(const Eigen::Vector3d& w);

/// Rotation exp([w]x) for a rotation vector w (axis·angle, radians); exact, with a Taylor
/// expansion below 1e-3 rad (exact to rounding there, and smooth at the identity). Inline: the
/// forward kinematics calls it once or twice a row, and a result passed back through memory cost
/// more than the function itself (its element stores, read back as pairs, stall).
[[nodiscard]] inline Eigen::Matrix3d so3Exp(const Eigen::Vector3d& w) {
  // Rodrigues: R = I + a·[w]× + b·[w]×², with [w]×² = w·wᵀ − θ²·I.
  const double theta2 = w.squaredNorm();
  double a;  // sin(theta)/theta
  double b;  // (1 - cos(theta))/theta^2
  if (theta2 < detail::kSo3SeriesBelow * detail::kSo3SeriesBelow) {
    // Taylor series (the next terms, θ⁶/5040 and θ⁶/40320, are below 1e-21 here): exact to
    // rounding, and no sin/cos for the small steps of the Newton solvers.
    a = 1.0 - theta2 / 6.0 + theta2 * theta2 / 120.0;
    b = 0.5 - theta2 / 24.0 + theta2 * theta2 / 720.0;
  } else {
    const double theta = std::sqrt(theta2);
    a = std::sin(theta) / theta;
    b = (1.0 - std::cos(theta)) / theta2;
  }
  Eigen::Matrix3d R = b * (w * w.transpose());
  R.diagonal().array() += 1.0 - b * theta2;
  const Eigen::Vector3d aw = a * w;
  R(0, 1) -= aw.z();
  R(1, 0) += aw.z();
  R(0, 2) += aw.y();
  R(2, 0) -= aw.y();
  R(1, 2) -= aw.x();
  R(2, 1) += aw.x();
  return R;
}

/// The left Jacobian J_l(w) of SO(3): so3Exp(w + δ) ≈ so3Exp([J_l(w)·δ]x)·so3Exp(w) to first order,
/// J_l = I + (1 − cos θ)/θ²·[w]x + (θ − sin θ)/θ³·[w]x², θ = |w| (Taylor expansion near 0).
[[nodiscard]] Eigen::Matrix3d so3LeftJacobian(const Eigen::Vector3d& w);

/// Rotation vector w with so3Exp(w) == R, |w| in [0, pi]. Precondition: R is a rotation matrix
/// (orthonormal, det +1); this is asserted, not checked.
[[nodiscard]] Eigen::Vector3d so3Log(const Eigen::Matrix3d& R);

/// R = Rz(c)·Ry(b)·Rx(a): roll a about the fixed X axis, then pitch b about fixed Y, then yaw c
/// about fixed Z (LinuxCNC posemath pmRpyMatConvert). Angles in radians; rpy = (a, b, c).
[[nodiscard]] Eigen::Matrix3d rotationFromRpy(const Eigen::Vector3d& rpy);

/// Roll-pitch-yaw angles (a, b, c) in radians of a rotation matrix, with b in [-pi/2, pi/2] and a,
/// c in
/// (-pi, pi]. At b = ±pi/2 (gimbal lock) a is set to 0.
[[nodiscard]] Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& R);

/// As rpyFromRotation, but of the equivalent angle triples (including the second branch
/// (a+pi, pi-b, c+pi) and shifts by 2·pi) returns the one closest to `near` (radians). Used to keep
/// angles continuous along a path, as a servo loop does.
[[nodiscard]] Eigen::Vector3d rpyFromRotation(const Eigen::Matrix3d& R,
                                              const Eigen::Vector3d& near);

/// Of the angle triples equivalent to `rpy` (radians: rpyFromRotation's of a rotation, the second
/// branch (a+pi, pi-b, c+pi) and shifts by 2·pi), the one closest to `near`:
/// rpyFromRotation(R, near) == nearestRpy(rpyFromRotation(R), near).
[[nodiscard]] Eigen::Vector3d nearestRpy(const Eigen::Vector3d& rpy, const Eigen::Vector3d& near);

}  // namespace pkm::geometry
