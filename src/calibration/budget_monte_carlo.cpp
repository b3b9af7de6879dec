// The adaptive Monte Carlo procedure of the calibration budgets (detail/budget_monte_carlo.hpp).
#include "detail/budget_monte_carlo.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace pkm::calibration::detail {
namespace {

/// Sample standard deviation of each row of `x` (columns first..last−1).
Eigen::VectorXd rowStd(const Eigen::MatrixXd& x, Eigen::Index first, Eigen::Index last) {
  const Eigen::MatrixXd b = x.middleCols(first, last - first);
  const Eigen::VectorXd mean = b.rowwise().mean();
  return ((b.colwise() - mean).rowwise().squaredNorm() / static_cast<double>(b.cols() - 1))
      .cwiseSqrt();
}

/// JCGM 101 §7.9.2: δ = ½·10^l with u = c·10^l, c an n_dig-digit integer.
double numericalTolerance(double u, int digits) {
  const double l = std::floor(std::log10(u)) - (digits - 1);
  return 0.5 * std::pow(10.0, l);
}

/// §7.9.4 on the standard uncertainties: for every unknown with u > 0, 2·s(u_batch)/√h ≤ δ.
bool stabilised(
    const Eigen::MatrixXd& x, int batch, int h, const std::vector<bool>& uncertain, int digits) {
  if (h < 2) return false;
  const Eigen::VectorXd u_all = rowStd(x, 0, static_cast<Eigen::Index>(batch) * h);
  Eigen::MatrixXd u_batches(x.rows(), h);
  for (int r = 0; r < h; ++r)
    u_batches.col(r) =
        rowStd(x, static_cast<Eigen::Index>(r) * batch, static_cast<Eigen::Index>(r + 1) * batch);
  const Eigen::VectorXd s_u = rowStd(u_batches, 0, h) / std::sqrt(static_cast<double>(h));
  for (Eigen::Index k = 0; k < x.rows(); ++k) {
    if (!uncertain[static_cast<std::size_t>(k)] || !(u_all(k) > 0.0)) continue;
    if (2.0 * s_u(k) > numericalTolerance(u_all(k), digits)) return false;
  }
  return true;
}

}  // namespace

BudgetSamples runBudgetMonteCarlo(Eigen::Index unknowns,
                                  const std::vector<bool>& uncertain,
                                  const BudgetMonteCarloOptions& options,
                                  const BudgetTrial& trial) {
  const int max_trials = options.max_trials;
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(unknowns, max_trials);
  std::vector<char> ok(static_cast<std::size_t>(max_trials), 0);
  const auto run = [&](int k) {
    GaussianStream normal(trialSeed(options.seed, k));
    UniformStream uniform(trialSeed(options.seed ^ 0x5DEECE66DULL, k));
    if (const std::optional<Eigen::VectorXd> u = trial(k, normal, uniform)) {
      x.col(k) = *u;
      ok[static_cast<std::size_t>(k)] = 1;
    }
  };
  const unsigned threads = options.threads > 0 ? static_cast<unsigned>(options.threads)
                                               : std::max(1u, std::thread::hardware_concurrency());
  BudgetSamples out;
  int done = 0;
  while (done < max_trials) {
    const int end = std::min(max_trials, done + options.batch);
    std::atomic<int> next{done};
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < std::min<unsigned>(threads, static_cast<unsigned>(end - done)); ++t)
      pool.emplace_back([&] {
        for (int k = next++; k < end; k = next++) run(k);
      });
    for (std::thread& t : pool) t.join();
    done = end;
    ++out.batches;
    if (options.progress) options.progress(done, max_trials);
    // Failed trials are rare; the batch criterion is evaluated on the trials that succeeded.
    std::vector<Eigen::Index> good;
    for (int k = 0; k < done; ++k)
      if (ok[static_cast<std::size_t>(k)]) good.push_back(k);
    Eigen::MatrixXd g(unknowns, static_cast<Eigen::Index>(good.size()));
    for (std::size_t i = 0; i < good.size(); ++i)
      g.col(static_cast<Eigen::Index>(i)) = x.col(good[i]);
    const int h = static_cast<int>(good.size()) / options.batch;
    if (stabilised(g, options.batch, h, uncertain, options.significant_digits)) {
      out.stabilised = true;
      out.x = std::move(g);
      break;
    }
    if (done >= max_trials) out.x = std::move(g);
  }
  out.failures = done - static_cast<int>(out.x.cols());
  return out;
}

BudgetMonteCarloResult budgetResult(const BudgetSamples& samples,
                                    double p,
                                    const std::vector<int>& parameter_of_unknown,
                                    int parameters) {
  const Eigen::MatrixXd& x = samples.x;
  BudgetMonteCarloResult out;
  out.batches = samples.batches;
  out.stabilised = samples.stabilised;
  out.trials = static_cast<int>(x.cols());
  out.failures = samples.failures;
  for (Eigen::Index k = 0; k < x.rows(); ++k) out.unknowns.push_back(summariseSamples(x.row(k), p));
  out.covariance = Eigen::MatrixXd::Zero(parameters, parameters);
  if (out.trials < 2) return out;
  const Eigen::MatrixXd c = x.colwise() - x.rowwise().mean();
  const Eigen::MatrixXd cov = c * c.transpose() / (out.trials - 1.0);
  const auto n =
      std::min<std::size_t>(parameter_of_unknown.size(), static_cast<std::size_t>(x.rows()));
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const int ka = parameter_of_unknown[a];
      const int kb = parameter_of_unknown[b];
      if (ka >= 0 && kb >= 0)
        out.covariance(ka, kb) = cov(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
    }
  return out;
}

metrology::MonteCarloResult summariseSamples(const Eigen::RowVectorXd& samples, double p) {
  metrology::MonteCarloResult r;
  r.trials = static_cast<std::size_t>(samples.size());
  r.mean = samples.mean();
  r.standard_uncertainty = samples.size() > 1
                               ? std::sqrt((samples.array() - r.mean).square().sum() /
                                           (static_cast<double>(samples.size()) - 1.0))
                               : 0.0;
  std::vector<double> sorted(samples.data(), samples.data() + samples.size());
  std::sort(sorted.begin(), sorted.end());
  const auto at = [&](double q) {
    const auto i =
        static_cast<std::size_t>(std::llround(q * static_cast<double>(sorted.size() - 1)));
    return sorted[std::min(i, sorted.size() - 1)];
  };
  r.low = at(0.5 * (1.0 - p));
  r.high = at(0.5 * (1.0 + p));
  return r;
}

}  // namespace pkm::calibration::detail
