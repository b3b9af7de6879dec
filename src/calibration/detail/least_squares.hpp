/// @file
/// @brief Internal: the one Ceres solve of pkm's calibrations — Levenberg–Marquardt with a dense
/// QR linear solver, silent, timed (docs/calibration.md, "Solver") — and the manifold that holds
/// the parameters not being estimated.
#pragma once

#include <ceres/problem.h>

#include <string>
#include <vector>

namespace pkm::calibration::detail {

/// Stopping rules of solveLeastSquares. gradient_tolerance and parameter_tolerance are Ceres'
/// Solver::Options of the same names. function_tolerance is applied by solveLeastSquares itself:
/// converged when a step changes the cost ½Σr² by at most function_tolerance × the cost, counted
/// only while the Levenberg–Marquardt damping is at most the scaled Jacobian's diagonal (trust
/// region radius ≥ 1; a step shrunk by heavy damping is no sign of convergence). Unlike Ceres' own
/// test it keeps an accepted step, and it is reachable on noisy data: there the cost of a step at
/// the minimum differs from the current one only by the rounding of the residuals, ~1e-12 of the
/// cost, while Ceres' parameter test (a relative step of 1e-12) is met only after the trust region
/// has been shrunk by a run of rejected steps.
struct LeastSquaresSettings {
  int max_iterations = 100;
  double function_tolerance = 1e-10;
  double gradient_tolerance = 1e-14;
  double parameter_tolerance = 1e-12;
};

/// What the solve reported.
struct LeastSquaresOutcome {
  bool converged = false;     ///< a stopping rule was met (not the iteration limit, not failure)
  std::string termination;    ///< Ceres' message, or the function tolerance's
  int iterations = 0;         ///< LM iterations taken
  double initial_cost = 0.0;  ///< ½Σr² before
  double final_cost = 0.0;    ///< ½Σr² after
  double seconds = 0.0;       ///< wall time of the solve, s

  /// Copies the fields into a result struct that has members of the same names.
  template <class Result>
  void copyTo(Result& out) const {
    out.converged = converged;
    out.termination = termination;
    out.iterations = iterations;
    out.initial_cost = initial_cost;
    out.final_cost = final_cost;
    out.seconds = seconds;
  }
};

/// Solves `problem` from its current parameter values (updated in place).
[[nodiscard]] LeastSquaresOutcome solveLeastSquares(ceres::Problem& problem,
                                                    const LeastSquaresSettings& settings);

/// Holds the entries k of the parameter block `block` (size n) with free(k) false at their values
/// (ceres::SubsetManifold); does nothing when every entry is free.
template <class FreeMask>
void holdFixedParameters(ceres::Problem& problem, double* block, int n, const FreeMask& free);

/// The indices k < n with !free[k].
template <class FreeMask>
[[nodiscard]] std::vector<int> fixedIndices(int n, const FreeMask& free) {
  std::vector<int> fixed;
  for (int k = 0; k < n; ++k)
    if (!free[static_cast<std::size_t>(k)]) fixed.push_back(k);
  return fixed;
}

/// As the template, given the fixed indices.
void holdParameters(ceres::Problem& problem, double* block, int n, const std::vector<int>& fixed);

template <class FreeMask>
void holdFixedParameters(ceres::Problem& problem, double* block, int n, const FreeMask& free) {
  holdParameters(problem, block, n, fixedIndices(n, free));
}

}  // namespace pkm::calibration::detail
