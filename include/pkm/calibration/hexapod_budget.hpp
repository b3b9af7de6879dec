/// @file
/// @brief Uncertainty budgets of a hexapod calibration (docs/calibration.md, "Uncertainty
/// budgets"): every estimated unknown with its expanded uncertainty U = k·u_c and its budget
/// (the laser tracker and the 6-DOF probe per their specification, the dial gauges, the distance
/// instrument, set-up repeatability, the fit's residual scatter beyond the instrument), propagated
/// linearly (J⁺ covariance, parameter_budget.hpp) and by a Monte Carlo method per GUM Supplement 1
/// (JCGM 101:2008 §7.9: the calibration re-fitted on perturbed observations, adaptive number of
/// trials); and the expanded uncertainty of the TCP position the calibrated model predicts at
/// given poses (J_tcp·Σ·J_tcpᵀ).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/parameter_budget.hpp"
#include "pkm/metrology/monte_carlo.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::calibration {

/// The linear budgets of a hexapod calibration.
struct HexapodParameterUncertainty {
  /// One budget per unknown: the free parameters in index order, then the measurement frame
  /// (measurementFrameNames; mm and rad) when estimated, then the backlash (backlashNames) when
  /// estimated.
  ParameterUncertainty linear;
  /// Per budget: the parameter index 0 … 41, or −1 for a frame or backlash unknown.
  std::vector<int> parameter_indices;
  /// 42 × 42 covariance of the parameters (zero rows and columns for fixed ones), model unit².
  Eigen::MatrixXd covariance;
};

/// The linear budgets of `fit` (calibrateHexapod(initial, data, calibration)): the observation
/// errors of `sources` (lengths converted from mm to the model's unit) mapped to the residuals by
/// central differences and to the unknowns by the fit's least-squares inverse at the estimate
/// (identifiable subspace of rank fit.identifiability.rank, Tikhonov rows included; robust-loss
/// weights are not applied). The tracker's a + b·L uses the measured range |y| for readings in a
/// tracker frame (data.measurement_frame set) and sources.tracker.range_mm otherwise. Throws
/// pkm::InvalidArgument when the sources are not valid or `fit` does not belong to `data`.
[[nodiscard]] HexapodParameterUncertainty hexapodParameterUncertainty(
    const kinematics::HexapodModel& initial,
    const HexapodCalibrationData& data,
    const HexapodCalibrationSummary& fit,
    const HexapodCalibrationOptions& calibration,
    const metrology::UncertaintySources& sources);

/// Settings of hexapodBudgetMonteCarlo (JCGM 101:2008 §7.9, adaptive Monte Carlo procedure).
struct BudgetMonteCarloOptions {
  int batch = 50;         ///< trials per batch (JCGM 101's M of one of the h runs), >= 10
  int max_trials = 2000;  ///< stop here even when not stabilised, >= 2 × batch
  /// Significant digits n_dig of the standard uncertainties that must be stable (JCGM 101
  /// §7.9.2: δ = ½·10^l with u = c·10^l, c an n_dig-digit integer), 1 … 3.
  int significant_digits = 1;
  std::uint64_t seed = 20261127u;  ///< fixed: the same trials on every run, for any thread count
  int threads = 1;                 ///< worker threads; 0: std::thread::hardware_concurrency()
  double coverage_probability = 0.95;      ///< p of the coverage intervals, in (0, 1)
  std::function<void(int, int)> progress;  ///< (trials done, max_trials); may be empty
  /// True when every field is usable; otherwise false with the reason in *why (if given).
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// What hexapodBudgetMonteCarlo found.
struct BudgetMonteCarloResult {
  int trials = 0;           ///< trials with an estimate
  int failures = 0;         ///< trials whose calibration threw
  int batches = 0;          ///< h
  bool stabilised = false;  ///< the §7.9.4 criterion met before max_trials
  /// Per linear budget (same order): mean, standard uncertainty and coverage interval of the
  /// re-fitted unknown over the trials.
  std::vector<metrology::MonteCarloResult> unknowns;
  Eigen::MatrixXd covariance;  ///< 42 × 42 sample covariance of the parameters
  double seconds = 0.0;        ///< wall time
};

/// GUM Supplement 1 propagation of the same inputs as `linear`: each trial replaces the
/// observations by what the estimate predicts (their residuals zero) plus one draw of every
/// instrument and set-up error from its distribution and a normal draw of the Type A scatter
/// (σ = linear.linear.fit_sigma) on every residual, and re-runs calibrateHexapod from `initial`.
/// Trials run in batches of options.batch; after each batch (h >= 2) the procedure stops when,
/// for every unknown with a non-zero uncertainty, twice the standard deviation of the batch
/// standard uncertainties divided by √h is at most δ (JCGM 101 §7.9.4, applied to u(θ_k)), or
/// at max_trials. Trial k draws from its own stream (seed, k). Throws pkm::InvalidArgument for
/// invalid options or sources.
[[nodiscard]] BudgetMonteCarloResult hexapodBudgetMonteCarlo(
    const kinematics::HexapodModel& initial,
    const HexapodCalibrationData& data,
    const HexapodCalibrationSummary& fit,
    const HexapodCalibrationOptions& calibration,
    const metrology::UncertaintySources& sources,
    const HexapodParameterUncertainty& linear,
    const BudgetMonteCarloOptions& options = {});

/// The predicted TCP uncertainty of a calibrated hexapod at given poses.
struct TcpUncertainty {
  /// Per pose: U = k·√λ_max(J_tcp·Σ·J_tcpᵀ) (positionExpandedUncertainty), model length unit;
  /// NaN where the FK does not converge.
  std::vector<double> expanded;
  double max = 0.0;   ///< largest U
  double mean = 0.0;  ///< mean U
  int poses = 0;      ///< poses with a value
  /// The model's remainder included in `expanded` (addTcpRemainder), model length unit; 0: none.
  double remainder = 0.0;
};

/// Adds what the model leaves at the tool to a predicted TCP uncertainty: each U ← √(U² + R²),
/// R = k·rms/√3 with `rms` the RMS |TCP error| the calibrated model leaves at held-out poses
/// (one coordinate's share of a 3-D RMS). The parameters' covariance carries only the
/// measurement's errors; geometry the model cannot represent (lead errors, joint imperfections,
/// compliance) is what the held-out poses show beyond it. The held-out errors include their own
/// readings' noise, so R bounds the remainder from above. Throws pkm::InvalidArgument for a
/// negative or non-finite rms or k <= 0.
void addTcpRemainder(TcpUncertainty& tcp, double rms, double coverage_factor);

/// The uncertainty of the TCP position the calibrated controller reaches at each commanded pose:
/// q = IK_estimated(X), J_tcp = ∂p_FK(q; θ)/∂θ (forwardPoseError's position rows) and Σ the
/// 42 × 42 parameter covariance. With `align_rigid` (a calibration whose measurement frame was
/// estimated: the data fix the machine only up to a rigid motion of the world), the stacked
/// covariance of the TCP positions is first projected onto the complement of the rigid motions
/// δt + δω × p_i of the poses (the linear counterpart of the rigid alignment in
/// monteCarloHexapod), needs >= 3 poses. Throws pkm::InvalidArgument for a covariance that is not
/// 42 × 42 or k <= 0.
[[nodiscard]] TcpUncertainty hexapodTcpUncertainty(const kinematics::HexapodModel& estimated,
                                                   const Eigen::MatrixXd& covariance,
                                                   const std::vector<kinematics::PoseRpy>& poses,
                                                   double coverage_factor = 2.0,
                                                   bool align_rigid = false);

}  // namespace pkm::calibration
