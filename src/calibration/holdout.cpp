// Held-out validation of a hexapod calibration (holdout.hpp).
#include "pkm/calibration/holdout.hpp"

#include <algorithm>
#include <cmath>

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
      return;
    }
    Eigen::Vector3d p = work.world_p_tcp;
    if (frame) p = frame->rotation.transpose() * (p - frame->translation);
    const double d = (p - measured).norm();
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

}  // namespace pkm::calibration
