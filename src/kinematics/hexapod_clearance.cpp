// The platform joints' height above a hexapod's base plane (kinematics/hexapod_clearance.hpp).
#include "pkm/kinematics/hexapod_clearance.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <limits>

#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::kinematics {

namespace {

/// The platform joint centres in the world frame at `pose`.
std::array<Eigen::Vector3d, kStruts> platformJoints(const HexapodModel& model,
                                                    const PoseRpy& pose) {
  const geometry::RigidTransform world_T_tcp = toRigidTransform(pose);
  std::array<Eigen::Vector3d, kStruts> p;
  for (int i = 0; i < kStruts; ++i)
    p[static_cast<std::size_t>(i)] = world_T_tcp * model.effectivePlatform(i);
  return p;
}

}  // namespace

BasePlane basePlane(const HexapodModel& model) {
  BasePlane plane;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i = 0; i < kStruts; ++i) c += model.effectiveBase(i);
  c /= kStruts;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (int i = 0; i < kStruts; ++i) {
    const Eigen::Vector3d d = model.effectiveBase(i) - c;
    scatter += d * d.transpose();
  }
  // The eigenvector of the smallest eigenvalue (sorted ascending) is the plane's normal.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  Eigen::Vector3d n = eig.eigenvectors().col(0).normalized();
  Eigen::Vector3d platform = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : platformJoints(model, model.home)) platform += p;
  if (n.dot(platform / kStruts - c) < 0.0) n = -n;
  plane.world_p_centre = c;
  plane.world_n = n;
  return plane;
}

double platformClearance(const HexapodModel& model, const BasePlane& plane, const PoseRpy& pose) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : platformJoints(model, pose))
    lowest = std::min(lowest, plane.world_n.dot(p - plane.world_p_centre));
  return lowest;
}

int assemblyBranch(const HexapodModel& model, HexapodData& data, const PoseRpy& pose) {
  constexpr double kSingularPivotRatio = 1e-12;
  inverseKinematics(model, data, pose);
  Matrix6d J = computeStrutJacobian(model, data);
  J.rightCols<3>() /= model.characteristicLength();
  const Eigen::FullPivLU<Matrix6d> lu(J);
  const Eigen::VectorXd pivots = lu.matrixLU().diagonal().cwiseAbs();
  if (!(pivots.minCoeff() > kSingularPivotRatio * pivots.maxCoeff())) return 0;
  return lu.determinant() > 0.0 ? 1 : -1;
}

}  // namespace pkm::kinematics
