/// @file
/// @brief Internal: the one Ceres solve of pkm's calibrations — Levenberg–Marquardt with a dense
/// QR linear solver, silent, timed (docs/calibration.md, "Solver") — and the manifold that holds
/// the parameters not being estimated.
#pragma once

#include <ceres/problem.h>

#include <string>
#include <vector>

namespace pkm::calibration::detail {

/// Stopping rules of solveLeastSquares (Ceres' Solver::Options of the same names).
struct LeastSquaresSettings {
  int max_iterations = 100;
  double function_tolerance = 1e-14;
  double gradient_tolerance = 1e-14;
  double parameter_tolerance = 1e-12;
};

/// What the solve reported.
struct LeastSquaresOutcome {
  bool converged = false;     ///< Ceres reported convergence (not the iteration limit, not failure)
  std::string termination;    ///< Ceres' message
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
