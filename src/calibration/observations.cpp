#include "detail/observations.hpp"

#include <Eigen/Geometry>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::calibration::detail {

geometry::RigidTransform FrameEstimate::current() const {
  return geometry::perturbedTransform(initial, delta);
}

std::vector<ObservationRef> observations(const HexapodCalibrationData& data) {
  std::vector<ObservationRef> out;
  for (std::size_t k = 0; k < data.poses.size(); ++k)
    out.push_back({ObservationRef::Kind::kPose, k, 0});
  for (std::size_t k = 0; k < data.points.size(); ++k)
    out.push_back({ObservationRef::Kind::kPoint, k, 0});
  for (std::size_t s = 0; s < data.constrained.size(); ++s)
    for (std::size_t k = 0; k < data.constrained[s].stations.size(); ++k)
      out.push_back({ObservationRef::Kind::kGauge, k, s});
  for (std::size_t k = 0; k < data.distances.size(); ++k)
    out.push_back({ObservationRef::Kind::kDistance, k, 0});
  return out;
}

namespace {

bool evaluatePose(const kinematics::HexapodModel& model,
                  kinematics::HexapodData& work,
                  const PoseObservation& obs,
                  const FrameEstimate* frame,
                  double* r,
                  Eigen::MatrixXd* J_theta,
                  Eigen::MatrixXd* J_frame) {
  if (frame == nullptr) {
    PoseParameterJacobian J;
    const kinematics::StrutVector res =
        poseResiduals(model, work, obs, J_theta != nullptr ? &J : nullptr);
    Eigen::Map<kinematics::StrutVector> r_out(r);
    r_out = res;
    if (J_theta != nullptr) *J_theta = J;
    return true;
  }
  // The measured pose expressed in world: p_w = R_f·p_m + t_f, R_w = R_f·R_m.
  const geometry::RigidTransform f = frame->current();
  const Eigen::Vector3d p_rel = f.linear() * obs.pose.position;
  const Eigen::Matrix3d R_w = f.linear() * geometry::rotationFromRpy(obs.pose.rpy);
  const kinematics::StrutVector& q =
      kinematics::inverseKinematics(model, work, p_rel + f.translation(), R_w);
  Eigen::Map<kinematics::StrutVector> r_out(r);
  r_out = q - obs.readings;
  if (J_theta != nullptr) *J_theta = readingParameterJacobian(model, work);
  if (J_frame != nullptr) {
    // d leg_i = δt + (J_l·δω) × (R_f·p_m + R_w·a_i); d r_i = u_iᵀ·d leg_i.
    const Eigen::Matrix3d Jl = geometry::so3LeftJacobian(frame->delta.tail<3>());
    J_frame->resize(6, 6);
    for (int i = 0; i < kinematics::kStruts; ++i) {
      const auto ii = static_cast<std::size_t>(i);
      const Eigen::Vector3d& u = work.unit_leg[ii];
      const Eigen::Vector3d v = p_rel + work.world_r_joint[ii];
      J_frame->block<1, 3>(i, 0) = u.transpose();
      J_frame->block<1, 3>(i, 3) = v.cross(u).transpose() * Jl;
    }
  }
  return true;
}

bool evaluatePoint(const kinematics::HexapodModel& model,
                   kinematics::HexapodData& work,
                   const PointObservation& obs,
                   const FrameEstimate* frame,
                   double* r,
                   Eigen::MatrixXd* J_theta,
                   Eigen::MatrixXd* J_frame) {
  PointObservation world = obs;
  geometry::RigidTransform f = geometry::RigidTransform::Identity();
  if (frame != nullptr) {
    f = frame->current();
    world.point = f.linear() * obs.point + f.translation();
  }
  kinematics::PoseRpy seed = model.home;
  seed.position = world.point;
  PointParameterJacobian J;
  const auto e = pointResiduals(model, work, world, seed, J_theta != nullptr ? &J : nullptr);
  if (!e) return false;
  Eigen::Map<Eigen::Vector3d> r_out(r);
  r_out = *e;
  if (J_theta != nullptr) *J_theta = J;
  if (frame != nullptr && J_frame != nullptr) {
    // e = p_FK − (R_f·p_m + t_f): de = −δt + [R_f·p_m]x·J_l·δω.
    J_frame->resize(3, 6);
    J_frame->leftCols<3>() = -Eigen::Matrix3d::Identity();
    J_frame->rightCols<3>() =
        geometry::hat(f.linear() * obs.point) * geometry::so3LeftJacobian(frame->delta.tail<3>());
  }
  return true;
}

}  // namespace

namespace {

bool evaluateUnshifted(const kinematics::HexapodModel& model,
                       kinematics::HexapodData& work,
                       const HexapodCalibrationData& data,
                       const ObservationRef& ref,
                       const FrameEstimate* frame,
                       double* r,
                       Eigen::MatrixXd* J_theta,
                       Eigen::MatrixXd* J_frame) {
  switch (ref.kind) {
    case ObservationRef::Kind::kPose:
      return evaluatePose(model, work, data.poses[ref.index], frame, r, J_theta, J_frame);
    case ObservationRef::Kind::kPoint:
      return evaluatePoint(model, work, data.points[ref.index], frame, r, J_theta, J_frame);
    case ObservationRef::Kind::kGauge: {
      GaugeParameterJacobian J;
      const auto res = constrainedResiduals(
          model, work, data.constrained[ref.set], ref.index, J_theta != nullptr ? &J : nullptr);
      if (!res) return false;
      Eigen::Map<Eigen::Vector3d> r_out(r);
      r_out = *res;
      if (J_theta != nullptr) *J_theta = J;
      if (J_frame != nullptr) J_frame->setZero(3, 6);  // gauges do not see the tracker frame
      return true;
    }
    case ObservationRef::Kind::kDistance: {
      DistanceParameterJacobian J;
      const auto res = distanceResidual(
          model, work, data.distances[ref.index], model.home, J_theta != nullptr ? &J : nullptr);
      if (!res) return false;
      r[0] = *res;
      if (J_theta != nullptr) *J_theta = J;
      if (J_frame != nullptr) J_frame->setZero(1, 6);  // distances do not see the frame
      return true;
    }
  }
  return false;
}

}  // namespace

kinematics::StrutVector approachOf(const HexapodCalibrationData& data, const ObservationRef& ref) {
  switch (ref.kind) {
    case ObservationRef::Kind::kPose:
      return data.poses[ref.index].approach;
    case ObservationRef::Kind::kPoint:
      return data.points[ref.index].approach;
    case ObservationRef::Kind::kGauge:
    case ObservationRef::Kind::kDistance:
      break;
  }
  return kinematics::StrutVector::Zero();
}

bool evaluate(const kinematics::HexapodModel& model,
              kinematics::HexapodData& work,
              const HexapodCalibrationData& data,
              const ObservationRef& ref,
              const FrameEstimate* frame,
              double* r,
              Eigen::MatrixXd* J_theta,
              Eigen::MatrixXd* J_frame,
              const kinematics::StrutVector* backlash,
              Eigen::MatrixXd* J_backlash) {
  if (backlash == nullptr) {
    if (J_backlash != nullptr) J_backlash->setZero(ref.rows(), kinematics::kStruts);
    return evaluateUnshifted(model, work, data, ref, frame, r, J_theta, J_frame);
  }
  // The backlash shifts each strut's length offset by −approach·b/2 for this observation.
  const kinematics::StrutVector d = approachOf(data, ref);
  kinematics::HexapodModel shifted = model;
  for (int i = 0; i < kinematics::kStruts; ++i)
    shifted.struts[static_cast<std::size_t>(i)].length_offset -= 0.5 * d(i) * (*backlash)(i);
  Eigen::MatrixXd Jt;
  Eigen::MatrixXd* jt = J_theta != nullptr ? J_theta : (J_backlash != nullptr ? &Jt : nullptr);
  if (!evaluateUnshifted(shifted, work, data, ref, frame, r, jt, J_frame)) return false;
  if (J_backlash != nullptr) {
    J_backlash->resize(ref.rows(), kinematics::kStruts);
    for (int i = 0; i < kinematics::kStruts; ++i)
      J_backlash->col(i) = -0.5 * d(i) * jt->col(offsetParameter(i));
  }
  return true;
}

HexapodCalibrationData predictedData(const kinematics::HexapodModel& model,
                                     const HexapodCalibrationData& data,
                                     const std::optional<geometry::RigidTransform>& frame) {
  HexapodCalibrationData out = data;
  kinematics::HexapodData work(model);
  const geometry::RigidTransform f = frame.value_or(geometry::RigidTransform::Identity());
  const Eigen::Matrix3d Rt = f.linear().transpose();
  for (PoseObservation& o : out.poses) {
    const kinematics::PoseRpy seed =
        kinematics::poseRpyFromTransform(f * kinematics::toRigidTransform(o.pose));
    if (!kinematics::forwardKinematics(model, work, o.readings, seed).ok()) continue;
    o.pose.position = Rt * (work.world_p_tcp - f.translation());
    o.pose.rpy = geometry::rpyFromRotation(Rt * work.world_R_platform);
  }
  for (PointObservation& o : out.points) {
    kinematics::PoseRpy seed = model.home;
    seed.position = f.linear() * o.point + f.translation();
    if (!kinematics::forwardKinematics(model, work, o.readings, seed).ok()) continue;
    o.point = Rt * (work.world_p_tcp - f.translation());
  }
  for (DistanceObservation& o : out.distances) {
    DistanceObservation exact = o;
    exact.distance = 0.0;
    if (const auto d = distanceResidual(model, work, exact, model.home)) o.distance = *d;
  }
  for (ConstrainedMotionData& c : out.constrained) {
    const auto ref = gaugeHeights(model, work, c, c.reference);
    if (!ref) continue;
    c.reference.gauges = {0.0, 0.0, 0.0};
    for (GaugeStation& st : c.stations) {
      const auto g = gaugeHeights(model, work, c, st);
      if (!g) continue;
      for (int j = 0; j < 3; ++j) st.gauges[static_cast<std::size_t>(j)] = (*g)(j) - (*ref)(j);
    }
  }
  return out;
}

}  // namespace pkm::calibration::detail
