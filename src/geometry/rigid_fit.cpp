#include "pkm/geometry/rigid_fit.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

#include "pkm/core/error.hpp"

namespace pkm::geometry {

RigidTransform fitRigidTransform(const std::vector<Eigen::Vector3d>& a,
                                 const std::vector<Eigen::Vector3d>& b) {
  PKM_CHECK(a.size() == b.size(), "rigid fit: {} points against {}", a.size(), b.size());
  PKM_CHECK(a.size() >= 3, "rigid fit: needs at least 3 points, got {}", a.size());
  Eigen::Vector3d ca = Eigen::Vector3d::Zero(), cb = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < a.size(); ++k) {
    PKM_CHECK(a[k].allFinite() && b[k].allFinite(), "rigid fit: point {} is not finite", k + 1);
    ca += a[k];
    cb += b[k];
  }
  const double n = static_cast<double>(a.size());
  ca /= n;
  cb /= n;
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();  // Σ (b − cb)(a − ca)ᵀ
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < a.size(); ++k) {
    H += (b[k] - cb) * (a[k] - ca).transpose();
    spread += (b[k] - cb) * (b[k] - cb).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> shape(spread);
  PKM_CHECK(shape.singularValues()(1) > 1e-12 * std::max(1.0, shape.singularValues()(0)),
            "rigid fit: the points are collinear");
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) D(2, 2) = -1.0;
  // Assigned, not initialised: Eigen groups the triple product differently in the two forms, and
  // this one keeps the registration's results bit for bit.
  Eigen::Matrix3d R;
  R = svd.matrixV() * D * svd.matrixU().transpose();
  return makeTransform(R, ca - R * cb);
}

}  // namespace pkm::geometry
