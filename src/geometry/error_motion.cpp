#include "pkm/geometry/error_motion.hpp"

#include "pkm/geometry/so3.hpp"

namespace pkm::geometry {

RigidTransform errorMotionHtm(const ErrorMotion& e) {
  return makeTransform(so3Exp(errorRotation(e)), errorTranslation(e));
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

}  // namespace pkm::geometry
