// The registration of a measurement frame to the machine's world frame
// (calibration/frame_registration.hpp).
#include "pkm/calibration/frame_registration.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_fit.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::calibration {

namespace {

/// A = [I, −[p]×]: the displacement at p of the left perturbation (δt, δω).
Eigen::Matrix<double, 3, 6> displacementJacobian(const Eigen::Vector3d& p) {
  Eigen::Matrix<double, 3, 6> A;
  A.leftCols<3>().setIdentity();
  A.rightCols<3>() = -geometry::hat(p);
  return A;
}

}  // namespace

double FrameRegistration::uncertaintyAt(const Eigen::Vector3d& p) const {
  const Eigen::Matrix<double, 3, 6> A = displacementJacobian(p);
  const Eigen::Matrix3d C = A * covariance * A.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff()));
}

FrameRegistration registerMeasurementFrame(const std::vector<Eigen::Vector3d>& world,
                                           const std::vector<Eigen::Vector3d>& measured,
                                           double stated_sigma) {
  PKM_CHECK(std::isfinite(stated_sigma) && stated_sigma >= 0.0,
            "the stated registration sigma {} must be finite and >= 0",
            stated_sigma);
  FrameRegistration r;
  r.world_T_measurement = geometry::fitRigidTransform(world, measured);
  r.references = static_cast<int>(world.size());
  double sum = 0.0;
  Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
  for (std::size_t k = 0; k < world.size(); ++k) {
    const Eigen::Vector3d p = r.world_T_measurement * measured[k];
    const double e = (world[k] - p).norm();
    r.residuals.push_back(e);
    r.max = std::max(r.max, e);
    sum += e * e;
    const Eigen::Matrix<double, 3, 6> A = displacementJacobian(p);
    normal += A.transpose() * A;
  }
  const double n = static_cast<double>(world.size());
  r.rms = std::sqrt(sum / n);
  const double dof = 3.0 * n - 6.0;
  r.sigma = std::max(stated_sigma, dof > 0.0 ? std::sqrt(sum / dof) : 0.0);
  r.covariance = r.sigma * r.sigma * normal.inverse();
  return r;
}

void expressInWorld(HexapodCalibrationData& data,
                    const geometry::RigidTransform& world_T_measurement) {
  for (PoseObservation& o : data.poses)
    o.pose = kinematics::poseRpyFromTransform(world_T_measurement *
                                              kinematics::toRigidTransform(o.pose));
  for (PointObservation& o : data.points) o.point = world_T_measurement * o.point;
  data.measurement_frame.reset();
}

}  // namespace pkm::calibration
