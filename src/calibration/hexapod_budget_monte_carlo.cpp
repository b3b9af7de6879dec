// GUM Supplement 1 propagation of a hexapod calibration's budgets: the calibration re-fitted on
// perturbed observations with the adaptive stopping rule of JCGM 101:2008 §7.9
// (calibration/hexapod_budget.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <thread>

#include "detail/hexapod_errors.hpp"
#include "detail/noise_stream.hpp"
#include "pkm/calibration/hexapod_budget.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::calibration {
namespace {

/// Uniform variates in (0, 1) from the same 64-bit stream as the trial's normals.
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

/// The unknowns of one trial's estimate, in the budgets' order (free parameters, frame, backlash).
Eigen::VectorXd unknownsOf(const HexapodCalibrationSummary& s,
                           const HexapodCalibrationSummary& fit,
                           Eigen::Index n) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  Eigen::Index v = 0;
  for (const int k : fit.free_indices) x(v++) = s.parameters(k);
  if (fit.measurement_frame && s.measurement_frame) {
    x.segment<3>(v) = s.measurement_frame->translation() - fit.measurement_frame->translation();
    x.segment<3>(v + 3) = geometry::so3Log(s.measurement_frame->linear() *
                                           fit.measurement_frame->linear().transpose());
    v += 6;
  }
  if (fit.backlash && s.backlash) x.segment<6>(v) = *s.backlash;
  return x;
}

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

metrology::MonteCarloResult summarise(const Eigen::RowVectorXd& samples, double p) {
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

}  // namespace

bool BudgetMonteCarloOptions::isValid(std::string* why) const {
  const auto fail = [&](std::string reason) {
    if (why) *why = std::move(reason);
    return false;
  };
  if (batch < 10) return fail(fmt::format("Monte Carlo: batch must be >= 10, got {}", batch));
  if (max_trials < 2 * batch)
    return fail(fmt::format("Monte Carlo: max_trials must be >= 2 x batch, got {}", max_trials));
  if (significant_digits < 1 || significant_digits > 3)
    return fail("Monte Carlo: significant_digits must be 1, 2 or 3");
  if (threads < 0) return fail("Monte Carlo: threads must be >= 0");
  if (!(coverage_probability > 0.0 && coverage_probability < 1.0))
    return fail("Monte Carlo: coverage_probability must be in (0, 1)");
  return true;
}

BudgetMonteCarloResult hexapodBudgetMonteCarlo(const kinematics::HexapodModel& initial,
                                               const HexapodCalibrationData& data,
                                               const HexapodCalibrationSummary& fit,
                                               const HexapodCalibrationOptions& calibration,
                                               const metrology::UncertaintySources& sources,
                                               const HexapodParameterUncertainty& linear,
                                               const BudgetMonteCarloOptions& options) {
  std::string why;
  PKM_CHECK(options.isValid(&why), "{}", why);
  PKM_CHECK(sources.isValid(&why), "{}", why);
  const auto t0 = std::chrono::steady_clock::now();
  const kinematics::HexapodModel estimate = withHexapodParameters(initial, fit.parameters);
  const HexapodCalibrationData base = detail::predictedData(estimate, data, fit.measurement_frame);
  std::vector<detail::CoordinateSource> inputs =
      detail::hexapodCoordinateSources(data, sources, initial.unit);
  if (linear.linear.fit_sigma > 0.0) {
    detail::CoordinateSource typeA;
    typeA.contributor.distribution = metrology::Distribution::kNormal;
    typeA.coordinates = detail::residualCoordinates(data, linear.linear.fit_sigma);
    inputs.push_back(std::move(typeA));
  }
  const auto n = static_cast<Eigen::Index>(linear.linear.budgets.size());
  std::vector<bool> uncertain;
  for (const metrology::UncertaintyBudget& b : linear.linear.budgets)
    uncertain.push_back(b.combinedStandardUncertainty() > 0.0);

  const int max_trials = options.max_trials;
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(n, max_trials);
  std::vector<char> ok(static_cast<std::size_t>(max_trials), 0);
  const auto trial = [&](int k) {
    detail::GaussianStream normal(detail::trialSeed(options.seed, k));
    UniformStream uniform(detail::trialSeed(options.seed ^ 0x5DEECE66DULL, k));
    HexapodCalibrationData d = base;
    for (const detail::CoordinateSource& s : inputs)
      for (const detail::MeasuredCoordinate& c : s.coordinates)
        detail::perturbMeasurement(
            d, c, detail::drawError(s.contributor.distribution, c.u, uniform, normal));
    try {
      x.col(k) = unknownsOf(calibrateHexapod(initial, d, calibration), fit, n);
      ok[static_cast<std::size_t>(k)] = 1;
    } catch (const InvalidArgument&) {
      // A failed re-fit: counted below, its column dropped.
    }
  };
  unsigned threads = options.threads > 0 ? static_cast<unsigned>(options.threads)
                                         : std::max(1u, std::thread::hardware_concurrency());
  BudgetMonteCarloResult out;
  int done = 0;
  while (done < max_trials) {
    const int end = std::min(max_trials, done + options.batch);
    std::atomic<int> next{done};
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < std::min<unsigned>(threads, static_cast<unsigned>(end - done)); ++t)
      pool.emplace_back([&] {
        for (int k = next++; k < end; k = next++) trial(k);
      });
    for (std::thread& t : pool) t.join();
    done = end;
    ++out.batches;
    if (options.progress) options.progress(done, max_trials);
    // Failed trials are rare; the batch criterion is evaluated on the trials that succeeded.
    std::vector<Eigen::Index> good;
    for (int k = 0; k < done; ++k)
      if (ok[static_cast<std::size_t>(k)]) good.push_back(k);
    Eigen::MatrixXd g(n, static_cast<Eigen::Index>(good.size()));
    for (std::size_t i = 0; i < good.size(); ++i)
      g.col(static_cast<Eigen::Index>(i)) = x.col(good[i]);
    const int h = static_cast<int>(good.size()) / options.batch;
    if (stabilised(g, options.batch, h, uncertain, options.significant_digits)) {
      out.stabilised = true;
      x = g;
      break;
    }
    if (done >= max_trials) x = g;
  }
  out.trials = static_cast<int>(x.cols());
  out.failures = done - out.trials;
  for (Eigen::Index k = 0; k < n; ++k)
    out.unknowns.push_back(summarise(x.row(k), options.coverage_probability));
  out.covariance = Eigen::MatrixXd::Zero(kHexapodParameters, kHexapodParameters);
  if (out.trials > 1) {
    const Eigen::MatrixXd c = x.colwise() - x.rowwise().mean();
    const Eigen::MatrixXd cov = c * c.transpose() / (out.trials - 1.0);
    for (std::size_t a = 0; a < fit.free_indices.size(); ++a)
      for (std::size_t b = 0; b < fit.free_indices.size(); ++b)
        out.covariance(fit.free_indices[a], fit.free_indices[b]) =
            cov(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace pkm::calibration
