/// @file
/// @brief Uncertainty budgets of calibrated parameters (docs/calibration.md, "Uncertainty
/// budgets"): the errors of the observations (the instrument per its specification, set-up) and
/// the fit's own residual scatter propagated linearly through the identification's least-squares
/// inverse, δθ = −J⁺·δr (GUM JCGM 100:2008 §5.1.2 eq. 10 applied to every parameter; the
/// covariance J⁺·Σ_r·J⁺ᵀ is GUM §F.2 / JCGM 102:2011 §6.2.1.3's linear propagation of a vector
/// measurand), one metrology::UncertaintyBudget per parameter. Machine independent: the hexapod
/// and Exechon calibrations build the inputs (hexapod_budget.hpp, exechon_budget.hpp).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "pkm/metrology/uncertainty_budget.hpp"

namespace pkm::calibration {

/// One independent source of error on the observations, as a budget lists it.
struct ObservationErrorSource {
  /// The contributor as the budgets show it: name, stated spread `value` (the reference spread),
  /// unit, distribution, source. Its `sensitivity` is ignored here: parameterBudgets sets it per
  /// parameter.
  metrology::UncertaintyContributor contributor;
  /// m × q: column j is the change of the m stacked residuals caused by the j-th independent
  /// error of this source at one reference standard uncertainty u_ref =
  /// contributor.standardUncertainty() (∂r/∂e_j · u(e_j)/u_ref). The q errors are independent
  /// and share the contributor's distribution; u(e_j) may differ (a tracker's a + b·L). Sparse:
  /// an error moves only the residuals of its own observation (or of its constrained set), so a
  /// source of one error per reading is m × m with a few entries per column (only the stored
  /// entries are multiplied).
  Eigen::SparseMatrix<double> effect;
};

/// The least-squares inverse of an identification Jacobian restricted to its `rank` largest
/// singular values (the identifiable subspace, as the calibrations' covariance σ²(JᵀJ)⁺): J⁺ of
/// size n × rows(J), of which the first `observation_rows` columns map a change of the
/// observations' residuals to the change of the estimate (δθ = −J⁺·δr); rows of J below them are
/// priors (Tikhonov rows, no measurement error). Throws pkm::InvalidArgument when rank < 0 or
/// observation_rows > rows(J).
[[nodiscard]] Eigen::MatrixXd identificationInverse(const Eigen::MatrixXd& J,
                                                    int rank,
                                                    Eigen::Index observation_rows);

/// What parameterBudgets needs.
struct ParameterBudgetInput {
  std::vector<std::string> names;  ///< one per unknown
  std::vector<std::string> units;  ///< one per unknown ("mm", "rad")
  Eigen::VectorXd values;          ///< the estimates
  /// n × m: identificationInverse's observation columns (the sign does not matter).
  Eigen::MatrixXd inverse;
  /// The residual σ of the fit, √(Σr²/(m − rank)) (or the stated measurement σ), residual unit.
  double residual_sigma = 0.0;
  std::string residual_unit = "mm";             ///< the residuals' length unit
  std::vector<ObservationErrorSource> sources;  ///< the instrument and set-up sources
  double coverage_factor = 2.0;                 ///< k of U = k·u_c, > 0
  /// n × p: the identification inverse's columns of the p prior (Tikhonov) rows; empty: no prior.
  Eigen::MatrixXd prior_inverse;
  /// The prior's own error, when prior_inverse is set: the geometry the prior pulls toward (the
  /// machine file) is an input quantity whose true value lies within the stated σ_θ (Type B, GUM
  /// §4.3); its effect has p rows (the prior rows' change per reference uncertainty). In the
  /// directions the data do not fix, the estimate is the prior's value and its uncertainty is
  /// σ_θ: without this term those parameters would claim the instrument's U for a value the
  /// measurement never saw (docs/calibration.md, "Uncertainty budgets").
  ObservationErrorSource prior;

  /// True when the sizes agree (names, units, values and inverse rows; every source's effect has
  /// m rows; a prior's inverse has n rows and its effect as many rows as the inverse has columns),
  /// σ ≥ 0 and k > 0; otherwise false with the reason in *why (if given).
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// The parameters' budgets and their joint covariance.
struct ParameterUncertainty {
  /// One budget per unknown in input order (quantity = its name): one contributor per source with
  /// its sensitivity c_k = ‖(J⁺·E_s)_k‖ (root sum of squares over the source's independent
  /// errors) and the fit's residual scatter beyond the instrument (Type A, GUM §4.2).
  std::vector<metrology::UncertaintyBudget> budgets;
  /// n × n: Σ_θ = Σ_s u_s²·J⁺E_sE_sᵀJ⁺ᵀ + σ_A²·J⁺J⁺ᵀ (+ u_p²·J_p⁺E_pE_pᵀJ_p⁺ᵀ for a prior; the
  /// sources are independent).
  Eigen::MatrixXd covariance;
  /// √(Σ_s u_s²·‖E_s‖²_F / m): the instrument's RMS standard uncertainty per residual row.
  double instrument_sigma = 0.0;
  /// σ_A = √max(0, σ² − instrument_sigma²): the residual scatter the instrument does not
  /// explain (unmodelled machine errors, set-up), the Type A contributor. Subtracting keeps the
  /// instrument's random error from being counted twice (once by its specification, once by the
  /// residuals it causes).
  double fit_sigma = 0.0;
};

/// Propagates every source and the fit's Type A scatter to the parameters. Throws
/// pkm::InvalidArgument when `input` is not valid.
[[nodiscard]] ParameterUncertainty parameterBudgets(const ParameterBudgetInput& input);

/// The expanded uncertainty of a position whose Jacobian with respect to the unknowns is `J` (3 ×
/// n) under the parameter covariance Σ (n × n): k·√λ_max(J·Σ·Jᵀ), the standard uncertainty along
/// the worst direction times k (a bound for the uncertainty of any distance or error component
/// at that position). Throws pkm::InvalidArgument when the sizes do not agree or k <= 0.
[[nodiscard]] double positionExpandedUncertainty(const Eigen::MatrixXd& J,
                                                 const Eigen::MatrixXd& covariance,
                                                 double coverage_factor);

}  // namespace pkm::calibration
