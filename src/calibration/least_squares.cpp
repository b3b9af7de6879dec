#include "detail/least_squares.hpp"

#include <ceres/iteration_callback.h>
#include <ceres/manifold.h>
#include <ceres/solver.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <string>

namespace pkm::calibration::detail {

namespace {

/// The function tolerance of LeastSquaresSettings, tested after each iteration (accepted or not).
class CostChangeStop final : public ceres::IterationCallback {
 public:
  explicit CostChangeStop(double tolerance) : tolerance_(tolerance) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& it) final {
    // Radius r: the LM damping is diag(JᵀJ)/r on the Jacobi-scaled problem (unit diagonal).
    constexpr double kUndampedRadius = 1.0;
    if (it.iteration == 0 || !it.step_is_valid || it.trust_region_radius < kUndampedRadius)
      return ceres::SOLVER_CONTINUE;
    const double relative = std::abs(it.cost_change) / it.cost;
    if (!(relative <= tolerance_)) return ceres::SOLVER_CONTINUE;
    message_ =
        fmt::format("Function tolerance reached. |cost_change|/cost: {:e} <= {:e} ({} step).",
                    relative,
                    tolerance_,
                    it.step_is_successful ? "accepted" : "rejected");
    return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
  }
  [[nodiscard]] const std::string& message() const { return message_; }

 private:
  double tolerance_;
  std::string message_;
};

}  // namespace

LeastSquaresOutcome solveLeastSquares(ceres::Problem& problem,
                                      const LeastSquaresSettings& settings) {
  ceres::Solver::Options solver;
  solver.minimizer_type = ceres::TRUST_REGION;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = settings.max_iterations;
  // Ceres' own function test would drop the accepted step that meets it: CostChangeStop instead.
  solver.function_tolerance = 0.0;
  CostChangeStop stop(settings.function_tolerance);
  solver.callbacks.push_back(&stop);
  solver.gradient_tolerance = settings.gradient_tolerance;
  solver.parameter_tolerance = settings.parameter_tolerance;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  const auto t0 = std::chrono::steady_clock::now();
  ceres::Solve(solver, &problem, &summary);
  LeastSquaresOutcome out;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const bool stopped = summary.termination_type == ceres::USER_SUCCESS;
  out.converged = summary.termination_type == ceres::CONVERGENCE || stopped;
  out.termination = stopped ? stop.message() : summary.message;
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
