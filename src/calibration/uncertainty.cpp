#include "pkm/calibration/uncertainty.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "detail/noise_stream.hpp"
#include "detail/observations.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::calibration {
namespace {

using Gaussian = detail::GaussianStream;
using detail::trialSeed;

/// `predicted` with Gaussian noise added to every measurement.
HexapodCalibrationData noisy(const HexapodCalibrationData& predicted,
                             const MonteCarloOptions& o,
                             Gaussian& n) {
  HexapodCalibrationData d = predicted;
  for (PoseObservation& p : d.poses) {
    for (int i = 0; i < 3; ++i) p.pose.position(i) += o.position_sigma * n();
    const Eigen::Vector3d w(
        o.orientation_sigma * n(), o.orientation_sigma * n(), o.orientation_sigma * n());
    p.pose.rpy = geometry::rpyFromRotation(
        geometry::so3Exp(w) * geometry::rotationFromRpy(p.pose.rpy), p.pose.rpy);
  }
  for (PointObservation& p : d.points)
    for (int i = 0; i < 3; ++i) p.point(i) += o.position_sigma * n();
  for (ConstrainedMotionData& c : d.constrained)
    for (GaugeStation& s : c.stations)
      for (double& g : s.gauges) g += o.gauge_sigma * n();
  return d;
}

/// Calibrates `initial` on options.trials noisy copies of `predicted` (trial k's noise from the
/// stream trialSeed(options.seed, k)) on options.threads workers, reporting options.progress from
/// this thread. Element k: trial k's parameters, nullopt when its calibration threw
/// pkm::InvalidArgument; the non-converged are counted into `not_converged`.
std::vector<std::optional<HexapodParameterVector>> runHexapodTrials(
    const kinematics::HexapodModel& initial,
    const HexapodCalibrationData& predicted,
    const HexapodCalibrationOptions& calibration,
    const MonteCarloOptions& options,
    std::atomic<int>& not_converged) {
  const int total = options.trials;
  std::vector<std::optional<HexapodParameterVector>> results(static_cast<std::size_t>(total));
  std::atomic<int> next{0}, done{0};
  const auto worker = [&] {
    for (int k = next++; k < total; k = next++) {
      Gaussian n(trialSeed(options.seed, k));
      HexapodCalibrationData trial = noisy(predicted, options, n);
      // trial keeps data.measurement_frame as its starting frame, so its gauge (the base-frame
      // freedoms held by the null-space prior) is fixed exactly as in the original calibration.
      try {
        const HexapodCalibrationSummary s = calibrateHexapod(initial, trial, calibration);
        // An iteration-limited solve still counts (ill-conditioned constrained-motion sets creep
        // along weak directions); it is reported in not_converged.
        results[static_cast<std::size_t>(k)] = s.parameters;
        if (!s.converged) ++not_converged;
      } catch (const InvalidArgument&) {
        // Counted as a failure below.
      }
      ++done;
    }
  };
  unsigned threads = options.threads > 0 ? static_cast<unsigned>(options.threads)
                                         : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min<unsigned>(threads, static_cast<unsigned>(total));
  std::vector<std::thread> pool;
  for (unsigned i = 0; i < threads; ++i) pool.emplace_back(worker);
  int reported = -1;
  while (done.load() < total) {
    if (options.progress && done.load() != reported) {
      reported = done.load();
      options.progress(reported, total);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (std::thread& t : pool) t.join();
  if (options.progress) options.progress(total, total);
  return results;
}

/// The TCP errors (model length unit) of the trials' parameters `ok`: each trial's model as the
/// controller of a machine that is `estimate`, at every pose of `workspace` whose FK converges;
/// with a measurement `frame` each trial's TCP positions are first aligned rigidly to the
/// commanded ones (at least 3 poses).
std::vector<double> hexapodTrialTcpErrors(const std::vector<HexapodParameterVector>& ok,
                                          const kinematics::HexapodModel& estimate,
                                          const std::optional<geometry::RigidTransform>& frame,
                                          const std::vector<kinematics::PoseRpy>& workspace) {
  std::vector<double> errors;
  for (const auto& p : ok) {
    const kinematics::HexapodModel m = withHexapodParameters(estimate, p);
    kinematics::HexapodData c(m), t(estimate);
    std::vector<Eigen::Vector3d> commanded, reached;
    for (const kinematics::PoseRpy& pose : workspace) {
      const kinematics::StrutVector q = kinematics::inverseKinematics(m, c, pose);
      if (!kinematics::forwardKinematics(estimate, t, q, pose).ok()) continue;
      commanded.push_back(pose.position);
      reached.push_back(t.world_p_tcp);
    }
    geometry::RigidTransform align = geometry::RigidTransform::Identity();
    if (frame && commanded.size() >= 3) align = geometry::fitRigidTransform(commanded, reached);
    for (std::size_t k = 0; k < commanded.size(); ++k)
      errors.push_back((align.linear() * reached[k] + align.translation() - commanded[k]).norm());
  }
  return errors;
}

}  // namespace

TcpErrorStatistics tcpErrorStatistics(std::vector<double> errors) {
  TcpErrorStatistics s;
  for (const double e : errors)
    PKM_CHECK(std::isfinite(e), "TCP error statistics: a non-finite error");
  s.samples = static_cast<int>(errors.size());
  if (errors.empty()) return s;
  std::sort(errors.begin(), errors.end());
  double sum = 0.0;
  for (const double e : errors) sum += e;
  s.mean = sum / static_cast<double>(errors.size());
  // Nearest rank: the smallest value with at least 95 % of the values at or below it.
  const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(errors.size())));
  s.p95 = errors[std::max<std::size_t>(rank, 1) - 1];
  s.max = errors.back();
  return s;
}

TcpErrorStatistics tcpErrorOverWorkspace(const kinematics::HexapodModel& controller,
                                         const kinematics::HexapodModel& truth,
                                         const std::vector<kinematics::PoseRpy>& poses) {
  kinematics::HexapodData c(controller), t(truth);
  std::vector<double> errors;
  errors.reserve(poses.size());
  for (const kinematics::PoseRpy& pose : poses) {
    const kinematics::StrutVector q = kinematics::inverseKinematics(controller, c, pose);
    if (!kinematics::forwardKinematics(truth, t, q, pose).ok()) continue;
    errors.push_back((t.world_p_tcp - pose.position).norm());
  }
  return tcpErrorStatistics(std::move(errors));
}

void MonteCarloOptions::validate() const {
  PKM_CHECK(trials >= 2, "Monte Carlo: trials must be >= 2, got {}", trials);
  PKM_CHECK(threads >= 0, "Monte Carlo: threads must be >= 0, got {}", threads);
  PKM_CHECK(std::isfinite(position_sigma) && position_sigma >= 0.0 &&
                std::isfinite(orientation_sigma) && orientation_sigma >= 0.0 &&
                std::isfinite(gauge_sigma) && gauge_sigma >= 0.0,
            "Monte Carlo: the noise sigmas must be finite and >= 0");
}

MonteCarloSummary monteCarloHexapod(const kinematics::HexapodModel& initial,
                                    const HexapodCalibrationData& data,
                                    const kinematics::HexapodModel& estimate,
                                    const std::optional<geometry::RigidTransform>& frame,
                                    const std::vector<kinematics::PoseRpy>& workspace,
                                    const HexapodCalibrationOptions& calibration,
                                    const MonteCarloOptions& options) {
  options.validate();
  calibration.validate();
  const auto t0 = std::chrono::steady_clock::now();
  const HexapodCalibrationData predicted = detail::predictedData(estimate, data, frame);
  const int total = options.trials;
  std::atomic<int> not_converged{0};
  const std::vector<std::optional<HexapodParameterVector>> results =
      runHexapodTrials(initial, predicted, calibration, options, not_converged);

  MonteCarloSummary out;
  std::vector<HexapodParameterVector> ok;
  for (const auto& r : results)
    if (r) ok.push_back(*r);
  out.trials = static_cast<int>(ok.size());
  out.failures = total - out.trials;
  out.not_converged = not_converged.load();
  if (!ok.empty()) {
    for (const auto& p : ok) out.mean += p;
    out.mean /= static_cast<double>(ok.size());
    if (ok.size() > 1) {
      HexapodParameterVector var = HexapodParameterVector::Zero();
      for (const auto& p : ok) var += (p - out.mean).cwiseAbs2();
      out.standard_deviation = (var / static_cast<double>(ok.size() - 1)).cwiseSqrt();
    }
    // The TCP spread: each trial's model as the controller of a machine that is `estimate`. With a
    // measurement frame the data fix the machine only up to a rigid motion of the world (the
    // gauge freedoms), so each trial's TCP positions are first aligned rigidly to the estimate's.
    out.tcp = tcpErrorStatistics(hexapodTrialTcpErrors(ok, estimate, frame, workspace));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace pkm::calibration
