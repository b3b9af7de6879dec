#include "pkm/kinematics/hexapod_ik.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <limits>

#include "kinematics/detail/hexapod_legs.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::kinematics {

HexapodData::HexapodData(const HexapodModel& /*model*/) {}

const StrutVector& inverseKinematics(const HexapodModel& model,
                                     HexapodData& data,
                                     const PoseRpy& pose) {
  inverseKinematics(model, data, pose.position, geometry::rotationFromRpy(pose.rpy));
  data.pose = pose;
  return data.readings;
}

namespace detail {
void computeLegs(const HexapodModel& model,
                 HexapodData& data,
                 const Eigen::Vector3d& world_p_tcp,
                 const Eigen::Matrix3d& world_R_platform) {
  data.world_R_platform = world_R_platform;
  data.world_p_tcp = world_p_tcp;
  for (int i = 0; i < kStruts; ++i) {
    const Strut& strut = model.struts[static_cast<std::size_t>(i)];
    const auto k = static_cast<std::size_t>(i);
    data.world_r_joint[k] = world_R_platform * model.effectivePlatform(i);
    data.world_p_platform_joint[k] = world_p_tcp + data.world_r_joint[k];
    data.leg[k] = data.world_p_platform_joint[k] - model.effectiveBase(i);
    const double len = data.leg[k].norm();
    const double inverse = len > 0.0 ? 1.0 / len : 0.0;
    data.joint_distance[i] = len;
    data.inverse_joint_distance[i] = inverse;
    data.unit_leg[k] = data.leg[k] * inverse;
    data.readings[i] = len - strut.length_offset;
  }
}
}  // namespace detail

const StrutVector& inverseKinematics(const HexapodModel& model,
                                     HexapodData& data,
                                     const Eigen::Vector3d& world_p_tcp,
                                     const Eigen::Matrix3d& world_R_platform) {
  detail::computeLegs(model, data, world_p_tcp, world_R_platform);
  data.pose.position = world_p_tcp;
  data.pose.rpy = geometry::rpyFromRotation(world_R_platform);
  return data.readings;
}

const Matrix6d& computeStrutJacobian(const HexapodModel& /*model*/, HexapodData& data) {
  for (int i = 0; i < kStruts; ++i) {
    const auto k = static_cast<std::size_t>(i);
    data.J_q_x.block<1, 3>(i, 0) = data.unit_leg[k].transpose();
    data.J_q_x.block<1, 3>(i, 3) = data.world_r_joint[k].cross(data.unit_leg[k]).transpose();
  }
  return data.J_q_x;
}

double scaledConditionNumber(const HexapodModel& model, const HexapodData& data) {
  Matrix6d scaled = data.J_q_x;
  scaled.rightCols<3>() /= model.characteristicLength();
  const Eigen::JacobiSVD<Matrix6d> svd(scaled);
  const auto& sv = svd.singularValues();
  if (!(sv[kStruts - 1] > 0.0)) return std::numeric_limits<double>::infinity();
  return sv[0] / sv[kStruts - 1];
}

}  // namespace pkm::kinematics
