#include "pkm/calibration/constrained_motion.hpp"

#include <Eigen/LU>

#include "pkm/calibration/hexapod_measurements.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::calibration {

std::optional<Eigen::Vector3d> gaugeHeights(const kinematics::HexapodModel& model,
                                            kinematics::HexapodData& data,
                                            const ConstrainedMotionData& set,
                                            const GaugeStation& station,
                                            GaugeParameterJacobian* J) {
  const kinematics::FkSummary fk =
      kinematics::forwardKinematics(model, data, station.readings, station.command);
  if (!fk.ok()) return std::nullopt;
  const Eigen::Vector3d& n = set.table_normal;
  Eigen::Vector3d g;
  Eigen::Matrix<double, 6, kHexapodParameters> dx;
  if (J != nullptr) {
    kinematics::computeStrutJacobian(model, data);
    const Eigen::PartialPivLU<kinematics::Matrix6d> lu(data.J_q_x);
    dx = -lu.solve(readingParameterJacobian(model, data));
  }
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d r = data.world_R_platform * set.gauge_points[static_cast<std::size_t>(j)];
    g(j) = n.dot(data.world_p_tcp + r);
    if (J != nullptr)
      J->row(j) = n.transpose() * (dx.topRows<3>() - geometry::hat(r) * dx.bottomRows<3>());
  }
  return g;
}

std::optional<Eigen::Vector3d> constrainedResiduals(const kinematics::HexapodModel& model,
                                                    kinematics::HexapodData& data,
                                                    const ConstrainedMotionData& set,
                                                    std::size_t k,
                                                    GaugeParameterJacobian* J) {
  GaugeParameterJacobian J_ref, J_k;
  const auto ref = gaugeHeights(model, data, set, set.reference, J != nullptr ? &J_ref : nullptr);
  if (!ref) return std::nullopt;
  const GaugeStation& s = set.stations[k];
  const auto g = gaugeHeights(model, data, set, s, J != nullptr ? &J_k : nullptr);
  if (!g) return std::nullopt;
  Eigen::Vector3d r;
  for (int j = 0; j < 3; ++j) {
    const auto jj = static_cast<std::size_t>(j);
    r(j) = ((*g)(j) - (*ref)(j)) - (s.gauges[jj] - set.reference.gauges[jj]);
  }
  if (J != nullptr) *J = J_k - J_ref;
  return r;
}

}  // namespace pkm::calibration
