/// @file
/// @brief Internal: the errors of an Exechon calibration's leg readings as inputs of its budgets
/// (docs/calibration.md, "Uncertainty budgets"), shared by the linear budgets
/// (exechon_budget.cpp) and their Monte Carlo (exechon_budget_monte_carlo.cpp), so that both
/// propagate exactly the same inputs.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/metrology/uncertainty_budget.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::calibration::detail {

/// One error source on the leg readings: the contributor as the budgets list it, and per
/// independent error (column) the change of the 3·n leg readings (row 3·i + leg) when that error
/// is at the contributor's reference standard uncertainty u_ref (∂q/∂e · u(e)/u_ref), model
/// length unit.
struct LegReadingSource {
  metrology::UncertaintyContributor contributor;
  Eigen::MatrixXd readings;  ///< 3·n × (independent errors)
};

/// The leg readings' error sources of `data` for a tripod described by `model`: encoder
/// resolution (rectangular), repeatability (normal) and backlash (U-shaped) per reading; the
/// screws' lead error as one rectangular slope per leg, zero at mid-stroke (at the readings'
/// mean when the stroke is unbounded), and their travel variation per reading
/// (ActuatorReadings); the head's weight (ExechonHead, when its mass is stated) as one normal
/// error of standard uncertainty the largest deflection, scaling the deflections the statics
/// predict at every observation (legs' axial stiffness and joint clearance; loads by virtual
/// work, C_l = m·g·∂z_c/∂q_l, gravity along −z of the model's world). Sources with a zero value
/// are left out. Throws pkm::InvalidArgument for invalid sources.
[[nodiscard]] std::vector<LegReadingSource> exechonLegReadingSources(
    const kinematics::ExechonModel& model,
    const ExechonCalibrationData& data,
    const metrology::UncertaintySources& sources,
    const kinematics::FkOptions& fk);

/// ∂p/∂q of the target of every observation with respect to its three leg readings (central
/// differences through the tool FK seeded with model.home), as the 3·n × 3·n block diagonal;
/// zero blocks where an FK does not converge.
[[nodiscard]] Eigen::MatrixXd exechonTargetLegJacobian(const kinematics::ExechonModel& model,
                                                       const ExechonCalibrationData& data,
                                                       const kinematics::FkOptions& fk);

}  // namespace pkm::calibration::detail
