/// @file
/// @brief Uncertainty budgets of an Exechon calibration (docs/calibration.md, "Uncertainty
/// budgets"): every estimated parameter with U = k·u_c and its budget (the laser tracker per its
/// specification on every measured point, set-up repeatability, the fit's residual scatter
/// beyond the instrument), propagated linearly through the fit's least-squares inverse at the
/// estimate (parameter_budget.hpp) and by a Monte Carlo method per GUM Supplement 1; and the
/// predicted tool-point uncertainty at given joint configurations (J_tcp·Σ·J_tcpᵀ).
#pragma once

#include <vector>

#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/calibration/hexapod_budget.hpp"
#include "pkm/calibration/parameter_budget.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::calibration {

/// The linear budgets of an Exechon calibration.
struct ExechonParameterUncertainty {
  /// One budget per free unknown in fit.free_indices order: the free parameters, then the
  /// measurement frame (measurementFrameNames; length unit and rad) when estimated.
  ParameterUncertainty linear;
  std::vector<int> parameter_indices;  ///< per budget: the parameter 0 … 25, or −1 (frame)
  Eigen::MatrixXd covariance;          ///< 26 × 26 (zero rows and columns for fixed parameters)
};

/// The linear budgets of `fit` = calibrateExechon(initial, data, calibration): the point rows of
/// the identification Jacobian at the estimate (exechonTargetJacobian; frame columns δt, δω when
/// a frame is estimated), its inverse on the identifiable subspace (rank fit.identifiability.rank),
/// the tracker's a + b·L per coordinate of every point (L the measured range in a tracker frame,
/// sources.tracker.range_mm otherwise; mm converted to the model's unit) and set-up repeatability
/// when > 0. Tool-direction rows, where the data have them, are not part of the propagation (the
/// budgets then slightly overstate U). Throws pkm::InvalidArgument for invalid sources or a fit
/// that does not belong to the data.
[[nodiscard]] ExechonParameterUncertainty exechonParameterUncertainty(
    const kinematics::ExechonModel& initial,
    const ExechonCalibrationData& data,
    const ExechonCalibrationSummary& fit,
    const ExechonCalibrationOptions& calibration,
    const metrology::UncertaintySources& sources);

/// GUM Supplement 1 propagation of the same inputs as `linear` (JCGM 101:2008 §7.9, adaptive, as
/// hexapodBudgetMonteCarlo): each trial replaces the measured points by what the estimate
/// predicts for their joints (their residuals zero; observations whose FK fails are left out),
/// adds to every coordinate one draw of the tracker's ±(a + b·L) (rectangular), of the set-up
/// repeatability (normal) and of the Type A scatter (normal, σ = linear.linear.fit_sigma), and
/// re-runs calibrateExechon from `initial`. Tool directions are not perturbed (as in `linear`).
/// Returns the unknowns' Monte Carlo summaries in the order of linear's budgets and the 26 × 26
/// sample covariance. Throws pkm::InvalidArgument for invalid options or sources.
[[nodiscard]] BudgetMonteCarloResult exechonBudgetMonteCarlo(
    const kinematics::ExechonModel& initial,
    const ExechonCalibrationData& data,
    const ExechonCalibrationSummary& fit,
    const ExechonCalibrationOptions& calibration,
    const metrology::UncertaintySources& sources,
    const ExechonParameterUncertainty& linear,
    const BudgetMonteCarloOptions& options = {});

/// The predicted uncertainty of the tool point (target offset `target_offset`) of the calibrated
/// model at each joint configuration: k·√λ_max(J·Σ·Jᵀ) with J = exechonTargetJacobian (FK seeded
/// at the model's home) and Σ the 26 × 26 covariance; NaN where the FK does not converge. Throws
/// pkm::InvalidArgument for a covariance that is not 26 × 26 or k <= 0.
[[nodiscard]] TcpUncertainty exechonToolUncertainty(
    const kinematics::ExechonModel& estimated,
    const Eigen::MatrixXd& covariance,
    const std::vector<kinematics::ExechonJoints>& configurations,
    const Eigen::Vector3d& target_offset,
    const kinematics::FkOptions& fk = {},
    double coverage_factor = 2.0);

}  // namespace pkm::calibration
