/// @file
/// @brief Internal: Levenberg–Marquardt (Ceres) on residual blocks whose Jacobian is taken by
/// central differences, with fixed parameters, a robust loss, null-space priors and the covariance
/// — the solver behind the Exechon and hybrid calibrations (docs/calibration.md, "Solver").
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/identifiability.hpp"

namespace pkm::calibration::detail {

/// A least-squares problem: unknowns θ (n), blocks of residuals r_b(θ).
struct NumericProblem {
  std::vector<std::string> names;  ///< one per unknown
  Eigen::VectorXd step;            ///< central-difference step per unknown (> 0)
  std::vector<int> rows;           ///< residual rows of each block
  /// Evaluates block b at θ into r (rows[b] values); false when it cannot be evaluated (e.g. an FK
  /// that does not converge). Must be deterministic (same θ, same r).
  std::function<bool(const Eigen::VectorXd& theta, std::size_t b, double* r)> residual;
  [[nodiscard]] Eigen::Index unknowns() const { return static_cast<Eigen::Index>(names.size()); }
  [[nodiscard]] Eigen::Index equations() const;
};

/// Settings of solveNumeric.
struct NumericOptions {
  std::vector<bool> free;  ///< per unknown
  int max_iterations = 100;
  double function_tolerance = 1e-10;  ///< LeastSquaresSettings::function_tolerance
  double gradient_tolerance = 1e-14;
  double parameter_tolerance = 1e-12;
  RobustLoss loss = RobustLoss::kNone;
  double loss_scale = 0.0;
  double measurement_sigma = 0.0;  ///< 0: estimated from the residuals
  IdentifiabilityOptions identifiability;
};

/// Result of solveNumeric.
struct NumericSolution {
  bool converged = false;
  std::string termination;
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0, seconds = 0.0;
  Eigen::VectorXd theta;
  Identifiability identifiability;  ///< of the free unknowns at θ₀
  std::vector<int> free_indices;
  double sigma = 0.0;
  Eigen::MatrixXd covariance;          ///< n × n (zero for fixed unknowns)
  Eigen::VectorXd standard_deviation;  ///< √diag(covariance)
};

/// The stacked residuals and central-difference Jacobian (columns of fixed unknowns zero when
/// `free` is given) at θ; blocks that cannot be evaluated get zero rows and ok[b] = false.
void stackNumeric(const NumericProblem& problem,
                  const Eigen::VectorXd& theta,
                  const std::vector<bool>* free,
                  Eigen::VectorXd* r,
                  Eigen::MatrixXd* J,
                  std::vector<bool>* ok);

/// Minimises Σ ρ(|r_b|²) from θ₀ over the free unknowns; unidentifiable directions at θ₀ are held
/// by priors n·(θ − θ₀). The identifiability is analysed on `structural` (the same unknowns and
/// blocks on data the model at θ₀ explains exactly, so that an unobservable rigid motion of the
/// whole set-up is exactly singular) or, when null, on `problem`. Throws pkm::InvalidArgument when
/// no unknown is free or there are fewer equations than free unknowns.
[[nodiscard]] NumericSolution solveNumeric(const NumericProblem& problem,
                                           const Eigen::VectorXd& theta0,
                                           const NumericOptions& options,
                                           const NumericProblem* structural = nullptr);

}  // namespace pkm::calibration::detail
