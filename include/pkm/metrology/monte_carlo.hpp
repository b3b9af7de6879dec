/// @file
/// @brief Propagation of distributions by a Monte Carlo method (GUM Supplement 1, JCGM
/// 101:2008) beside the law of propagation of uncertainty (metrology/uncertainty_budget.hpp): the
/// same inputs, sampled from their distributions, pushed through the model; the estimate, its
/// standard uncertainty and a probabilistically symmetric coverage interval (JCGM 101 §7.7).
/// docs/analysis.md, "Measurement uncertainty".
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "pkm/metrology/uncertainty_budget.hpp"

namespace pkm::metrology {

/// A measurement model y = f(x): the inputs in the order of the contributors.
using MeasurementModel = std::function<double(std::span<const double> x)>;

/// Options of propagateMonteCarlo.
struct MonteCarloOptions {
  /// Number of trials M (JCGM 101 §7.2.2 recommends 10⁶ for a 95 % interval to two significant
  /// digits; 10⁵ is enough to compare with the linear result to a few per cent). >= 100.
  std::size_t trials = 100000;
  std::uint64_t seed = 20261122u;      ///< fixed seed: the same trials on every run and platform
  double coverage_probability = 0.95;  ///< p of the coverage interval, in (0, 1)

  /// True when every field is usable; otherwise false with the reason in *why (if given).
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// Result of propagateMonteCarlo (JCGM 101 §7.6-7.7).
struct MonteCarloResult {
  double mean = 0.0;                  ///< the average of the M model values (the estimate y)
  double standard_uncertainty = 0.0;  ///< their standard deviation u(y) (divisor M − 1)
  double low = 0.0;                   ///< the probabilistically symmetric coverage interval:
  double high = 0.0;                  ///< the (1−p)/2 and (1+p)/2 quantiles of the model values
  std::size_t trials = 0;             ///< M
};

/// Draws every contributor of `inputs` M times around its `estimate` (normal: standard deviation
/// u(x_i); rectangular: uniform on ±a; triangular: the sum of two uniforms on ±a/2; U-shaped:
/// a·sin of a uniform phase) and evaluates `model` on each draw. Inputs are independent (the
/// correlations of a budget are not sampled). The random numbers come from std::mt19937_64 and
/// are turned into uniforms and normals (Box-Muller) here, so the trials are the same everywhere.
/// Throws pkm::InvalidArgument for invalid options, an empty model, an invalid budget, or a model
/// value that is not finite.
[[nodiscard]] MonteCarloResult propagateMonteCarlo(const MeasurementModel& model,
                                                   const UncertaintyBudget& inputs,
                                                   const MonteCarloOptions& options = {});

/// The sensitivity coefficients c_i = ∂f/∂x_i at the estimates by central differences (step:
/// the input's standard uncertainty × 1e-3, or 1e-6 when it is 0), written into a copy of
/// `inputs`, and `value` = f(estimates): the linear (GUM §5.1) budget of the same model.
/// Throws pkm::InvalidArgument for an empty model or an invalid budget.
[[nodiscard]] UncertaintyBudget linearizeModel(const MeasurementModel& model,
                                               const UncertaintyBudget& inputs);

}  // namespace pkm::metrology
