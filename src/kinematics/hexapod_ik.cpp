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
  // The legs alone: the matrix overload's angles (three atan2, a quarter of an IK) would be
  // overwritten by the pose's own.
  detail::computeLegs(model, data, pose.position, geometry::rotationFromRpy(pose.rpy));
  data.pose = pose;
  return data.readings;
}

namespace detail {
namespace {
/// computeLegs's loop; `each(i, reading)` is called with every strut's reading as it is computed.
template <typename Each>
inline void legsLoop(const HexapodModel& model,
                     HexapodData& data,
                     const Eigen::Vector3d& world_p_tcp,
                     const Eigen::Matrix3d& world_R_platform,
                     Each&& each) {
  data.world_R_platform = world_R_platform;
  data.world_p_tcp = world_p_tcp;
  // Two legs at a time, so that their square roots and divisions are packed SSE2 operations (the
  // divider, not the arithmetic, bounds this function), with the pairs built in registers (a pair
  // loaded from two separate stores would stall).
  static_assert(kStruts % 2 == 0);
  for (int i = 0; i < kStruts; i += 2) {
    const auto k = static_cast<std::size_t>(i);
    for (std::size_t j = k; j < k + 2; ++j) {
      const int leg = static_cast<int>(j);
      data.world_r_joint[j] = world_R_platform * model.effectivePlatform(leg);
      data.world_p_platform_joint[j] = world_p_tcp + data.world_r_joint[j];
      data.leg[j] = data.world_p_platform_joint[j] - model.effectiveBase(leg);
    }
    const Eigen::Array2d len =
        Eigen::Array2d(data.leg[k].squaredNorm(), data.leg[k + 1].squaredNorm()).sqrt();
    const Eigen::Array2d inverse = (len > 0.0).select(len.inverse(), 0.0);
    data.joint_distance.segment<2>(i) = len.matrix();
    data.inverse_joint_distance.segment<2>(i) = inverse.matrix();
    for (int j = 0; j < 2; ++j) {
      const auto leg = k + static_cast<std::size_t>(j);
      data.unit_leg[leg] = data.leg[leg] * inverse[j];
      const double reading = len[j] - model.struts[leg].length_offset;
      data.readings[i + j] = reading;
      each(i + j, reading);
    }
  }
}
}  // namespace

void computeLegs(const HexapodModel& model,
                 HexapodData& data,
                 const Eigen::Vector3d& world_p_tcp,
                 const Eigen::Matrix3d& world_R_platform) {
  legsLoop(model, data, world_p_tcp, world_R_platform, [](int, double) {});
}

double computeLegsResidual(const HexapodModel& model,
                           HexapodData& data,
                           const Eigen::Vector3d& world_p_tcp,
                           const Eigen::Matrix3d& world_R_platform,
                           const StrutVector& target,
                           StrutVector& residual) {
  double worst = 0.0;
  legsLoop(model, data, world_p_tcp, world_R_platform, [&](int i, double reading) {
    const double r = reading - target[i];
    residual[i] = r;
    const double a = std::abs(r);
    worst = a > worst || std::isnan(a) ? a : worst;  // a NaN stays
  });
  return worst;
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
