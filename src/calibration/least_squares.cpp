#include "detail/least_squares.hpp"

#include <ceres/manifold.h>
#include <ceres/solver.h>

#include <chrono>

namespace pkm::calibration::detail {

LeastSquaresOutcome solveLeastSquares(ceres::Problem& problem,
                                      const LeastSquaresSettings& settings) {
  ceres::Solver::Options solver;
  solver.minimizer_type = ceres::TRUST_REGION;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = settings.max_iterations;
  solver.function_tolerance = settings.function_tolerance;
  solver.gradient_tolerance = settings.gradient_tolerance;
  solver.parameter_tolerance = settings.parameter_tolerance;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  const auto t0 = std::chrono::steady_clock::now();
  ceres::Solve(solver, &problem, &summary);
  LeastSquaresOutcome out;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.termination = summary.message;
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  out.initial_cost = summary.initial_cost;
  out.final_cost = summary.final_cost;
  return out;
}

void holdParameters(ceres::Problem& problem, double* block, int n, const std::vector<int>& fixed) {
  if (fixed.empty()) return;
  problem.SetManifold(block, new ceres::SubsetManifold(n, fixed));
}

}  // namespace pkm::calibration::detail
