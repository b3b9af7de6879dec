#include "pkm/calibration/distance_measurements.hpp"

namespace pkm::calibration {

std::optional<double> distanceResidual(const kinematics::HexapodModel& model,
                                       kinematics::HexapodData& data,
                                       const DistanceObservation& observation,
                                       const kinematics::PoseRpy& seed,
                                       DistanceParameterJacobian* J) {
  PointParameterJacobian Ja, Jb = PointParameterJacobian::Zero();
  PointObservation a;
  a.readings = observation.readings;  // point 0: the residual is the FK point itself
  const auto pa = pointResiduals(model, data, a, seed, J != nullptr ? &Ja : nullptr);
  if (!pa) return std::nullopt;
  Eigen::Vector3d pb = observation.from_point;
  if (observation.readings_from) {
    PointObservation b;
    b.readings = *observation.readings_from;
    const auto p = pointResiduals(model, data, b, seed, J != nullptr ? &Jb : nullptr);
    if (!p) return std::nullopt;
    pb = *p;
  }
  const Eigen::Vector3d d = *pa - pb;
  const double length = d.norm();
  if (!(length > 0.0)) return std::nullopt;
  if (J != nullptr) *J = (d / length).transpose() * (Ja - Jb);
  return length - observation.distance;
}

}  // namespace pkm::calibration
