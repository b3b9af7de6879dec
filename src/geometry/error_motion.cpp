#include "pkm/geometry/error_motion.hpp"

#include <cassert>

#include "pkm/geometry/so3.hpp"

namespace pkm::geometry {

Eigen::Isometry3d errorMotionHtm(const ErrorMotion& e) {
  return makeIsometry(so3Exp(errorRotation(e)), errorTranslation(e));
}

Eigen::Matrix4d errorMotionHtmFirstOrder(const ErrorMotion& e) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() += hat(errorRotation(e));
  m.topRightCorner<3, 1>() = errorTranslation(e);
  return m;
}

Eigen::Vector3d firstOrderDisplacement(const ErrorMotion& e, const Eigen::Vector3d& point) {
  return errorTranslation(e) + errorRotation(e).cross(point);
}

Eigen::Isometry3d makeIsometry(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  assert((R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-6);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = p;
  return T;
}

Eigen::Isometry3d translationHtm(const Eigen::Vector3d& p) {
  return makeIsometry(Eigen::Matrix3d::Identity(), p);
}

Eigen::Isometry3d rotationHtm(const Eigen::Vector3d& w) {
  return makeIsometry(so3Exp(w), Eigen::Vector3d::Zero());
}

}  // namespace pkm::geometry
