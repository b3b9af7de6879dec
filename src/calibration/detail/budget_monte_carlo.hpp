/// @file
/// @brief Internal: the adaptive Monte Carlo procedure of JCGM 101:2008 §7.9 shared by the
/// calibration budgets' propagations (hexapodBudgetMonteCarlo, exechonBudgetMonteCarlo): trials
/// in batches on worker threads, each drawing from its own streams, stopped when the standard
/// uncertainties of every unknown are stable, then summarised per unknown.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include "noise_stream.hpp"
#include "pkm/calibration/hexapod_budget.hpp"

namespace pkm::calibration::detail {

/// Uniform variates in (0, 1) from a 64-bit Mersenne twister (the same bits on every platform).
class UniformStream {
 public:
  explicit UniformStream(std::uint64_t seed) : engine_(seed) {}
  double operator()() {
    constexpr double kScale = 1.0 / 9007199254740992.0;  // 2^-53
    return (static_cast<double>(engine_() >> 11) + 0.5) * kScale;
  }

 private:
  std::mt19937_64 engine_;
};

/// One trial: the unknowns re-estimated from observations perturbed with draws from `normal` and
/// `uniform` (trial k's own streams); std::nullopt when that re-estimation failed.
using BudgetTrial =
    std::function<std::optional<Eigen::VectorXd>(int k, GaussianStream&, UniformStream&)>;

/// The samples of a budget Monte Carlo run: one column per successful trial.
struct BudgetSamples {
  Eigen::MatrixXd x;  ///< unknowns × trials
  int failures = 0;
  int batches = 0;
  bool stabilised = false;
};

/// Runs `trial` for k = 0, 1, … in batches of options.batch on options.threads threads until the
/// §7.9.4 criterion holds for every unknown flagged in `uncertain` (or max_trials). Trial k's
/// streams are seeded from (options.seed, k), so the samples do not depend on the thread count.
/// Precondition: options.isValid().
[[nodiscard]] BudgetSamples runBudgetMonteCarlo(Eigen::Index unknowns,
                                                const std::vector<bool>& uncertain,
                                                const BudgetMonteCarloOptions& options,
                                                const BudgetTrial& trial);

/// The summary of `samples` (all but the wall time): trials, failures, batches, stabilised, per
/// unknown summariseSamples with coverage probability `p`, and the parameters' sample covariance
/// (`parameters` × `parameters`; unknown k is parameter parameter_of_unknown[k], −1 for none).
[[nodiscard]] BudgetMonteCarloResult budgetResult(const BudgetSamples& samples,
                                                  double p,
                                                  const std::vector<int>& parameter_of_unknown,
                                                  int parameters);

/// Mean, standard uncertainty and the probabilistically symmetric coverage interval of
/// probability p of `samples` (JCGM 101 §7.7).
[[nodiscard]] metrology::MonteCarloResult summariseSamples(const Eigen::RowVectorXd& samples,
                                                           double p);

}  // namespace pkm::calibration::detail
