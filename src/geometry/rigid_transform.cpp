#include "pkm/geometry/rigid_transform.hpp"

#include <cassert>
#include <cmath>

#include "pkm/geometry/so3.hpp"

namespace pkm::geometry {

namespace {
/// Below this angle (rad) the coefficient of [w]×² in J_l⁻¹ is taken from its Taylor series:
/// 1 − (θ/2)·cot(θ/2) cancels badly for small θ (next omitted term ~θ⁶/1.2e6, below 1e-24 here).
constexpr double kSeriesBelow = 1e-3;

/// (1 − (θ/2)·cot(θ/2))/θ², θ = sqrt(theta2): 1/12 + θ²/720 + θ⁴/30240 + … near 0.
double inverseJacobianCoefficient(double theta2) {
  const double theta = std::sqrt(theta2);
  if (theta < kSeriesBelow) return 1.0 / 12.0 + theta2 / 720.0 + theta2 * theta2 / 30240.0;
  const double half = 0.5 * theta;
  return (1.0 - half * std::cos(half) / std::sin(half)) / theta2;
}
}  // namespace

RigidTransform makeTransform(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  assert((R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-6);
  RigidTransform T = RigidTransform::Identity();
  T.linear() = R;
  T.translation() = p;
  return T;
}

RigidTransform translationTransform(const Eigen::Vector3d& p) {
  return makeTransform(Eigen::Matrix3d::Identity(), p);
}

RigidTransform rotationTransform(const Eigen::Vector3d& w) {
  return makeTransform(so3Exp(w), Eigen::Vector3d::Zero());
}

RigidTransform perturbedTransform(const RigidTransform& T, const Twist& delta) {
  const Eigen::Matrix3d R = so3Exp(delta.tail<3>()) * T.linear();
  return makeTransform(R, T.translation() + delta.head<3>());
}

RigidTransform se3Exp(const Twist& xi) {
  const Eigen::Vector3d v = xi.head<3>();
  const Eigen::Vector3d w = xi.tail<3>();
  return makeTransform(so3Exp(w), so3LeftJacobian(w) * v);
}

Twist se3Log(const RigidTransform& T) {
  const Eigen::Vector3d w = so3Log(T.linear());
  const Eigen::Matrix3d W = hat(w);
  const Eigen::Matrix3d J_inv =
      Eigen::Matrix3d::Identity() - 0.5 * W + inverseJacobianCoefficient(w.squaredNorm()) * W * W;
  Twist xi;
  xi.head<3>() = J_inv * T.translation();
  xi.tail<3>() = w;
  return xi;
}

}  // namespace pkm::geometry
