#include "pkm/kinematics/pose_rpy.hpp"

#include "pkm/geometry/so3.hpp"

namespace pkm::kinematics {

geometry::RigidTransform toRigidTransform(const PoseRpy& pose) {
  return geometry::makeTransform(geometry::rotationFromRpy(pose.rpy), pose.position);
}

PoseRpy poseRpyFromTransform(const geometry::RigidTransform& T) {
  return {T.translation(), geometry::rpyFromRotation(T.linear())};
}

PoseRpy poseRpyFromTransform(const geometry::RigidTransform& T, const Eigen::Vector3d& near) {
  return {T.translation(), geometry::rpyFromRotation(T.linear(), near)};
}

}  // namespace pkm::kinematics
