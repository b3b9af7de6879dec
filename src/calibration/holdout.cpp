// Held-out validation of a hexapod calibration (holdout.hpp).
#include "pkm/calibration/holdout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::calibration {

HoldoutErrors hexapodHoldoutErrors(const kinematics::HexapodModel& model,
                                   const std::optional<geometry::RigidTransform>& frame,
                                   const HexapodCalibrationData& held,
                                   const std::optional<kinematics::StrutVector>& backlash) {
  HoldoutErrors e;
  kinematics::HexapodData work(model);
  double sum2 = 0.0, sum = 0.0;
  const auto add = [&](const kinematics::StrutVector& readings,
                       const Eigen::Vector3d& measured,
                       const kinematics::StrutVector& approach) {
    kinematics::StrutVector q = readings;
    if (backlash) q -= 0.5 * approach.cwiseProduct(*backlash);  // the estimated hysteresis
    if (!kinematics::forwardKinematics(model, work, q, model.home).ok()) {
      ++e.failures;
      e.errors.push_back(std::numeric_limits<double>::quiet_NaN());
      return;
    }
    Eigen::Vector3d p = work.world_p_tcp;
    if (frame) p = frame->linear().transpose() * (p - frame->translation());
    const double d = (p - measured).norm();
    e.errors.push_back(d);
    sum2 += d * d;
    sum += d;
    e.max = std::max(e.max, d);
    ++e.poses;
  };
  for (const auto& o : held.poses) add(o.readings, o.pose.position, o.approach);
  for (const auto& o : held.points) add(o.readings, o.point, o.approach);
  if (e.poses > 0) {
    e.rms = std::sqrt(sum2 / e.poses);
    e.mean = sum / e.poses;
  }
  return e;
}

namespace {

/// |world_T_measurement · measured − predicted| over observations; `predict` gives nullopt for an
/// observation without a prediction, counted in `failures` when `count_failures`.
template <class Observation, class Predict>
HoldoutErrors targetErrors(const std::vector<Observation>& observations,
                           const std::optional<geometry::RigidTransform>& frame,
                           bool count_failures,
                           Predict predict) {
  HoldoutErrors e;
  double sum = 0.0;
  for (const Observation& o : observations) {
    const std::optional<Eigen::Vector3d> p = predict(o);
    if (!p) {
      if (count_failures) ++e.failures;
      e.errors.push_back(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    const Eigen::Vector3d m =
        frame ? Eigen::Vector3d(frame->linear() * o.point + frame->translation()) : o.point;
    const double d = (m - *p).norm();
    e.errors.push_back(d);
    sum += d * d;
    e.max = std::max(e.max, d);
    ++e.poses;
  }
  e.rms = e.poses > 0 ? std::sqrt(sum / e.poses) : 0.0;
  return e;
}

}  // namespace

HoldoutErrors exechonHoldoutErrors(const kinematics::ExechonModel& model,
                                   const std::optional<geometry::RigidTransform>& frame,
                                   const ExechonCalibrationData& held,
                                   const kinematics::FkOptions& fk) {
  return targetErrors(held.observations, frame, true, [&](const ExechonObservation& o) {
    return exechonTarget(model, o.joints, held.target_offset, model.home, fk);
  });
}

HoldoutErrors hybridHoldoutErrors(const kinematics::HybridMachineModel& model,
                                  const kinematics::GeometricErrors& known,
                                  const kinematics::HybridSquareness& squareness,
                                  const HybridCalibrationData& held,
                                  const std::optional<geometry::RigidTransform>& frame,
                                  const TripodMotion& tripod) {
  return targetErrors(held.observations, frame, false, [&](const HybridObservation& o) {
    return hybridTarget(model, known, squareness, o.command, held.target_offset, tripod);
  });
}

geometry::RigidTransform initialHybridMeasurementFrame(
    const kinematics::HybridMachineModel& model,
    const kinematics::GeometricErrors& known,
    const kinematics::HybridSquareness& squareness,
    const HybridCalibrationData& data,
    const TripodMotion& tripod) {
  std::vector<Eigen::Vector3d> work, measured;
  for (const HybridObservation& o : data.observations)
    if (const auto p =
            hybridTarget(model, known, squareness, o.command, data.target_offset, tripod)) {
      work.push_back(*p);
      measured.push_back(o.point);
    }
  if (work.size() < 3) throw InvalidArgument("hybrid data: fewer than 3 reachable commands");
  return geometry::fitRigidTransform(work, measured);
}

}  // namespace pkm::calibration
