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
  /// 3·n × (independent errors); for a source `each` reading on its own, 3·n × 1: the column of
  /// reading r is that entry times the r-th unit vector (the identity, stored as its diagonal).
  Eigen::MatrixXd readings;
  bool each = false;  ///< one independent error per reading
  /// The number of independent errors.
  [[nodiscard]] Eigen::Index errors() const { return each ? readings.rows() : readings.cols(); }
  /// The change of the readings for one draw per error (a vector of errors() values).
  [[nodiscard]] Eigen::VectorXd change(const Eigen::VectorXd& draws) const {
    return each ? Eigen::VectorXd(readings.col(0).cwiseProduct(draws))
                : Eigen::VectorXd(readings * draws);
  }
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
/// differences through the tool FK seeded with model.home): the diagonal blocks of the 3·n × 3·n
/// block-diagonal Jacobian, one 3 × 3 per observation; zero where an FK does not converge.
[[nodiscard]] std::vector<Eigen::Matrix3d> exechonTargetLegJacobian(
    const kinematics::ExechonModel& model,
    const ExechonCalibrationData& data,
    const kinematics::FkOptions& fk);

/// The change of the 3·n target residuals per error of `source` (its effect matrix): the
/// block-diagonal product of `J_target_legs` (exechonTargetLegJacobian) with its reading changes,
/// negated (r = world(y) − p(θ, q)).
[[nodiscard]] Eigen::MatrixXd legEffect(const std::vector<Eigen::Matrix3d>& J_target_legs,
                                        const LegReadingSource& source);

}  // namespace pkm::calibration::detail
