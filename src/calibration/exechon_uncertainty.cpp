#include "pkm/calibration/exechon_uncertainty.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "detail/exechon_predicted.hpp"
#include "detail/noise_stream.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/exechon_data.hpp"

namespace pkm::calibration {
namespace {

using kinematics::ExechonModel;

/// One trial's result.
struct Trial {
  ExechonParameterVector parameters;
  std::optional<geometry::RigidTransform> frame;
};

/// `base` with Gaussian noise on every point and direction.
ExechonCalibrationData noisy(const ExechonCalibrationData& base,
                             const ExechonMonteCarloOptions& o,
                             detail::GaussianStream& n) {
  ExechonCalibrationData d = base;
  for (ExechonObservation& p : d.observations) {
    for (int i = 0; i < 3; ++i) p.point(i) += o.position_sigma * n();
    if (p.direction) {
      const Eigen::Vector3d w(
          o.direction_sigma * n(), o.direction_sigma * n(), o.direction_sigma * n());
      p.direction = (geometry::so3Exp(w) * *p.direction).normalized();
    }
  }
  return d;
}

/// Runs `trial(k)` for k in [0, total) on `threads` workers, reporting progress from this thread.
template <class F>
void runTrials(int total, int threads_option, const std::function<void(int, int)>& progress, F f) {
  std::atomic<int> next{0}, done{0};
  const auto worker = [&] {
    for (int k = next++; k < total; k = next++) {
      f(k);
      ++done;
    }
  };
  unsigned threads = threads_option > 0 ? static_cast<unsigned>(threads_option)
                                        : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min<unsigned>(threads, static_cast<unsigned>(total));
  std::vector<std::thread> pool;
  for (unsigned i = 0; i < threads; ++i) pool.emplace_back(worker);
  int reported = -1;
  while (done.load() < total) {
    if (progress && done.load() != reported) {
      reported = done.load();
      progress(reported, total);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (std::thread& t : pool) t.join();
  if (progress) progress(total, total);
}

/// Sample standard deviation (n − 1) of the columns' entries, per row.
Eigen::VectorXd sampleStd(const Eigen::MatrixXd& samples) {
  const Eigen::VectorXd mean = samples.rowwise().mean();
  if (samples.cols() < 2) return Eigen::VectorXd::Zero(samples.rows());
  return ((samples.colwise() - mean).cwiseAbs2().rowwise().sum() /
          static_cast<double>(samples.cols() - 1))
      .cwiseSqrt();
}

/// Calibrates `initial` on options.trials noisy copies of `base` (trial k's noise from the stream
/// trialSeed(options.seed, k)) on options.threads workers. Element k: trial k's estimate, nullopt
/// when its calibration threw pkm::InvalidArgument; the non-converged are counted into
/// `not_converged`.
std::vector<std::optional<Trial>> runExechonTrials(const ExechonModel& initial,
                                                   const ExechonCalibrationData& base,
                                                   const ExechonCalibrationOptions& calibration,
                                                   const ExechonMonteCarloOptions& options,
                                                   std::atomic<int>& not_converged) {
  const int total = options.trials;
  std::vector<std::optional<Trial>> results(static_cast<std::size_t>(total));
  runTrials(total, options.threads, options.progress, [&](int k) {
    detail::GaussianStream n(detail::trialSeed(options.seed, k));
    const ExechonCalibrationData trial = noisy(base, options, n);
    try {
      const ExechonCalibrationSummary s = calibrateExechon(initial, trial, calibration);
      results[static_cast<std::size_t>(k)] = Trial{s.parameters, s.measurement_frame};
      if (!s.converged) ++not_converged;
    } catch (const InvalidArgument&) {
      // Counted as a failure below.
    }
  });
  return results;
}

/// Stores in `out` the mean and sample standard deviation of the parameters over the successful
/// trials `ok` (out.trials of them), and the standard deviation of their frames' deviation from
/// `frame` (translation, model length unit; rotation vector, rad; zero without frames).
void summariseExechonTrials(const std::vector<Trial>& ok,
                            const std::optional<geometry::RigidTransform>& frame,
                            ExechonMonteCarloSummary& out) {
  Eigen::MatrixXd theta(kExechonParameters, out.trials), delta(6, out.trials);
  for (int k = 0; k < out.trials; ++k) {
    const Trial& t = ok[static_cast<std::size_t>(k)];
    theta.col(k) = t.parameters;
    delta.col(k).setZero();
    if (frame && t.frame) {
      delta.col(k).head<3>() = t.frame->translation() - frame->translation();
      delta.col(k).tail<3>() = geometry::so3Log(t.frame->linear() * frame->linear().transpose());
    }
  }
  out.mean = theta.rowwise().mean();
  out.standard_deviation = sampleStd(theta);
  out.frame_standard_deviation = sampleStd(delta);
}

/// The workspace configurations where the estimate's FK converges: their joints, the FK solution
/// (the trials' FK seed) and the estimate's tool point (world, model length unit).
struct ExechonWorkspaceFk {
  std::vector<kinematics::ExechonJoints> joints;
  std::vector<kinematics::ExechonConfiguration> seeds;
  std::vector<Eigen::Vector3d> nominal;
};

/// The FK of `estimate` at every configuration of `workspace` (from its home), failures left out.
ExechonWorkspaceFk estimateWorkspaceFk(const ExechonModel& estimate,
                                       const std::vector<kinematics::ExechonJoints>& workspace,
                                       const kinematics::FkOptions& fk) {
  ExechonWorkspaceFk ws;
  kinematics::ExechonData work(estimate);
  for (const kinematics::ExechonJoints& q : workspace)
    if (kinematics::toolForwardKinematics(estimate, work, q, estimate.home, fk).ok()) {
      ws.joints.push_back(q);
      ws.seeds.push_back(kinematics::configurationOf(work));
      ws.nominal.push_back(work.world_p_tool);
    }
  return ws;
}

/// Stores in `out` the tool-point spread of the trials `ok` over the workspace `ws`: each trial
/// model's (parameters about `estimate`, base `reference`) tool points, rigidly aligned to the
/// estimate's when `align` and at least 3 converge, against the estimate's (out.tcp), and the
/// per-configuration σ = √trace(Cov) of the trial points (out.tool_sigma); model length unit.
void exechonToolSpread(const std::vector<Trial>& ok,
                       const ExechonModel& estimate,
                       const geometry::RigidTransform& reference,
                       const ExechonWorkspaceFk& ws,
                       bool align,
                       const kinematics::FkOptions& fk,
                       ExechonMonteCarloSummary& out) {
  const std::vector<kinematics::ExechonJoints>& joints = ws.joints;
  const std::vector<kinematics::ExechonConfiguration>& seeds = ws.seeds;
  const std::vector<Eigen::Vector3d>& nominal = ws.nominal;
  // points[c]: the trial tool points at configuration c (FK failures left out).
  std::vector<std::vector<Eigen::Vector3d>> points(joints.size());
  std::vector<double> deviations;
  for (const Trial& t : ok) {
    const ExechonModel m = withExechonParameters(estimate, t.parameters, reference);
    kinematics::ExechonData tw(m);
    std::vector<std::size_t> index;
    std::vector<Eigen::Vector3d> est, got;
    for (std::size_t c = 0; c < joints.size(); ++c)
      if (kinematics::toolForwardKinematics(m, tw, joints[c], seeds[c], fk).ok()) {
        index.push_back(c);
        est.push_back(nominal[c]);
        got.push_back(tw.world_p_tool);
      }
    geometry::RigidTransform a = geometry::RigidTransform::Identity();
    if (align && got.size() >= 3) a = geometry::fitRigidTransform(est, got);
    for (std::size_t i = 0; i < got.size(); ++i) {
      const Eigen::Vector3d p = a.linear() * got[i] + a.translation();
      deviations.push_back((p - est[i]).norm());
      points[index[i]].push_back(p);
    }
  }
  out.tcp = tcpErrorStatistics(std::move(deviations));
  std::vector<double> sigmas;
  for (const auto& ps : points) {
    if (ps.size() < 2) continue;
    Eigen::MatrixXd s(3, static_cast<Eigen::Index>(ps.size()));
    for (std::size_t i = 0; i < ps.size(); ++i) s.col(static_cast<Eigen::Index>(i)) = ps[i];
    sigmas.push_back(sampleStd(s).norm());  // √(σx² + σy² + σz²) = √trace(Cov)
  }
  out.tool_sigma = tcpErrorStatistics(std::move(sigmas));
}

}  // namespace

ExechonCalibrationData detail::predictedExechonData(
    const ExechonModel& estimate,
    const ExechonCalibrationData& data,
    const std::optional<geometry::RigidTransform>& frame,
    const kinematics::FkOptions& fk) {
  ExechonCalibrationData out = data;
  out.observations.clear();
  kinematics::ExechonData work(estimate);
  for (const ExechonObservation& o : data.observations) {
    if (!kinematics::toolForwardKinematics(estimate, work, o.joints, estimate.home, fk).ok())
      continue;
    ExechonObservation p = o;
    const Eigen::Vector3d world = work.world_p_tool + work.world_R_tool * data.target_offset;
    p.point = frame ? Eigen::Vector3d(frame->linear().transpose() * (world - frame->translation()))
                    : world;
    if (o.direction)
      p.direction = frame ? Eigen::Vector3d(frame->linear().transpose() * work.world_u_tool)
                          : work.world_u_tool;
    out.observations.push_back(std::move(p));
  }
  return out;
}

void ExechonMonteCarloOptions::validate() const {
  PKM_CHECK(trials >= 2, "Monte Carlo: trials must be >= 2, got {}", trials);
  PKM_CHECK(threads >= 0, "Monte Carlo: threads must be >= 0, got {}", threads);
  PKM_CHECK(std::isfinite(position_sigma) && position_sigma > 0.0,
            "Monte Carlo: position_sigma must be finite and > 0, got {}",
            position_sigma);
  PKM_CHECK(std::isfinite(direction_sigma) && direction_sigma >= 0.0,
            "Monte Carlo: direction_sigma must be finite and >= 0, got {}",
            direction_sigma);
}

ExechonMonteCarloSummary monteCarloExechon(const ExechonModel& initial,
                                           const ExechonCalibrationData& data,
                                           const ExechonModel& estimate,
                                           const std::optional<geometry::RigidTransform>& frame,
                                           const std::vector<kinematics::ExechonJoints>& workspace,
                                           const ExechonCalibrationOptions& calibration,
                                           const ExechonMonteCarloOptions& options) {
  options.validate();
  calibration.validate();
  PKM_CHECK(frame.has_value() == data.measurement_frame.has_value(),
            "Monte Carlo: the estimated measurement frame must be given exactly when the data "
            "have a measurement frame");
  const auto t0 = std::chrono::steady_clock::now();
  const ExechonCalibrationData base =
      detail::predictedExechonData(estimate, data, frame, calibration.fk);
  const int total = options.trials;
  std::atomic<int> not_converged{0};
  const std::vector<std::optional<Trial>> results =
      runExechonTrials(initial, base, calibration, options, not_converged);

  ExechonMonteCarloSummary out;
  std::vector<Trial> ok;
  for (const auto& r : results)
    if (r) ok.push_back(*r);
  out.trials = static_cast<int>(ok.size());
  out.failures = total - out.trials;
  out.not_converged = not_converged.load();
  if (!ok.empty()) {
    summariseExechonTrials(ok, frame, out);

    // The tool point at each workspace configuration under the estimate (its FK solution seeds the
    // trials' FK) and under every trial model.
    const geometry::RigidTransform reference = initial.world_T_zoppi;
    const ExechonWorkspaceFk ws = estimateWorkspaceFk(estimate, workspace, calibration.fk);
    out.configurations = static_cast<int>(ws.joints.size());
    bool align = false;
    for (int k = kExechonBaseParameter; k < kExechonParameters; ++k)
      align = align || calibration.free[static_cast<std::size_t>(k)];
    align = align && frame.has_value();
    exechonToolSpread(ok, estimate, reference, ws, align, calibration.fk, out);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace pkm::calibration
