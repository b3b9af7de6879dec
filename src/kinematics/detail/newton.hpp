/// @file
/// @brief Internal: the damped Newton iteration shared by the hexapod and Exechon forward
/// kinematics (convergence on the residual, one polishing step, step halving, singularity and NaN
/// guards).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <type_traits>

#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::kinematics::detail {

/// Below this fraction of the tolerance no polishing step is taken after convergence.
inline constexpr double kPolishFraction = 1e-3;

/// Solves residual(x) = 0 for x, starting at `x`, with options' tolerance (max |r_i|), iteration
/// cap and step halving. Callbacks:
///   evaluate(const X& x, Vec& r) -> double: the residual at x and |r|² (+infinity when not
///   finite);
///       it may keep state (data, Jacobian) for x: `solve` is always called right after the
///       evaluation at the current iterate;
///   solve(Vec& delta) -> double: replaces delta = r by J⁻¹·r at the current iterate and returns
///       the smallest/largest pivot ratio (0 when singular); solve(Vec& delta, bool polishing),
///       when it takes the flag, may use the previous iterate's J for the polishing step;
///   retract(const X& x, const Vec& delta, double step) -> X: the iterate x − step·delta.
/// Once every residual is within the tolerance, one more step is taken unless the residual is
/// already below kPolishFraction·tolerance, so that x (not only r) is accurate. On return the
/// callbacks' state is that of the returned x.
template <int N, typename X, typename Evaluate, typename Solve, typename Retract>
FkSummary dampedNewton(
    const FkOptions& options, X& x, Evaluate&& evaluate, Solve&& solve, Retract&& retract) {
  using Vec = Eigen::Matrix<double, N, 1>;
  FkSummary summary;
  Vec r, r_try;
  double norm2 = evaluate(x, r);
  summary.status = FkStatus::kNoConvergence;
  bool polishing = false;
  for (int iter = 0;; ++iter) {
    summary.max_residual = r.cwiseAbs().maxCoeff();
    if (!std::isfinite(norm2)) {
      summary.status = FkStatus::kNoConvergence;
      break;
    }
    if (summary.max_residual <= options.tolerance) {
      summary.status = FkStatus::kOk;
      if (polishing || summary.max_residual <= kPolishFraction * options.tolerance ||
          iter == options.max_iterations)
        break;
      polishing = true;
    }
    if (iter == options.max_iterations) break;

    Vec delta = r;
    double pivot_ratio = 0.0;
    if constexpr (std::is_invocable_v<Solve&, Vec&, bool>)
      pivot_ratio = solve(delta, polishing);
    else
      pivot_ratio = solve(delta);
    if (!(pivot_ratio > options.singular_pivot_ratio) || !delta.allFinite()) {
      summary.status = FkStatus::kSingular;
      break;
    }
    // Backtracking: accept the first step length that reduces |r|.
    double step = 1.0;
    bool accepted = false;
    X x_try = x;
    for (int k = 0; k <= options.max_backtracks; ++k) {
      x_try = retract(x, delta, step);
      const double n2 = evaluate(x_try, r_try);
      if (n2 < norm2 || (!polishing && r_try.cwiseAbs().maxCoeff() <= options.tolerance)) {
        accepted = true;
        norm2 = n2;
        break;
      }
      step *= 0.5;
      ++summary.backtracks;
    }
    ++summary.iterations;
    if (!accepted) {
      norm2 = evaluate(x, r);  // restore the callbacks' state to the best iterate
      summary.max_residual = r.cwiseAbs().maxCoeff();
      if (!polishing) summary.status = FkStatus::kNoConvergence;
      break;
    }
    x = x_try;
    r = r_try;
    if (polishing) {
      summary.max_residual = r.cwiseAbs().maxCoeff();
      break;
    }
  }
  return summary;
}

}  // namespace pkm::kinematics::detail
