/// @file
/// @brief The constrained-motion measurement model of Lee et al. ("Development of a Parallel-Typed
/// CNC Machine"), §3: three dial gauges on the platform touch a table; at every station the
/// platform was driven until the gauges read (about) zero, and the commanded strut readings were
/// recorded. Each gauge gives one plane-contact equation per station (Ikits & Hollerbach,
/// "Kinematic calibration using a plane constraint", ICRA 1997).
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "pkm/calibration/hexapod_parameters.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::calibration {

/// One station: the commanded strut readings, the command (FK seed) and the final gauge readings.
struct GaugeStation {
  kinematics::StrutVector readings = kinematics::StrutVector::Zero();  ///< model length unit
  kinematics::PoseRpy command;     ///< the commanded pose, used as the FK seed
  std::array<double, 3> gauges{};  ///< gauge readings, model length unit
};

/// A constrained-motion data set.
struct ConstrainedMotionData {
  /// Gauge tips in the tool frame (relative to the TCP, platform axes), model length unit.
  std::array<Eigen::Vector3d, 3> gauge_points{};
  Eigen::Vector3d table_normal = Eigen::Vector3d::UnitZ();  ///< unit normal, world frame
  GaugeStation reference;                                   ///< where the gauges were zeroed
  std::vector<GaugeStation> stations;                       ///< the constrained stations
};

/// Jacobian of the three gauge residuals of a station with respect to the 42 parameters.
using GaugeParameterJacobian = Eigen::Matrix<double, 3, kHexapodParameters>;

/// The gauge positions along the table normal at a station: g_j = n·(p + R·t_j), (p, R) =
/// FK(readings; θ) from the station's command, t_j the gauge tips. With `J`, dg/dθ by the
/// implicit-function theorem (dx/dθ = −J_q_x⁻¹·∂q/∂θ; d(p + R t) = dp − [R t]×·δθ). nullopt when FK
/// does not converge.
[[nodiscard]] std::optional<Eigen::Vector3d> gaugeHeights(const kinematics::HexapodModel& model,
                                                          kinematics::HexapodData& data,
                                                          const ConstrainedMotionData& set,
                                                          const GaugeStation& station,
                                                          GaugeParameterJacobian* J = nullptr);

/// The residuals of station `k`: r_j = (g_j(station) − g_j(reference)) − reading_j +
/// reading_j(ref), model length unit: zero when the model explains why the gauges read what they
/// did. nullopt when an FK does not converge.
[[nodiscard]] std::optional<Eigen::Vector3d> constrainedResiduals(
    const kinematics::HexapodModel& model,
    kinematics::HexapodData& data,
    const ConstrainedMotionData& set,
    std::size_t k,
    GaugeParameterJacobian* J = nullptr);

}  // namespace pkm::calibration
