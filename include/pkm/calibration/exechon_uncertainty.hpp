/// @file
/// @brief Monte Carlo uncertainty of an Exechon calibration (docs/calibration.md, "Uncertainty"):
/// the calibration repeated on simulated tracker noise (multi-threaded, with progress), the spread
/// of the parameters and of the predicted tool point over workspace configurations.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/calibration/uncertainty.hpp"

namespace pkm::calibration {

/// Settings of monteCarloExechon.
struct ExechonMonteCarloOptions {
  int trials = 100;             ///< simulated repetitions of the measurement, ≥ 2
  int threads = 0;              ///< worker threads; 0: std::thread::hardware_concurrency()
  std::uint64_t seed = 1;       ///< seed of the simulated noise (results do not depend on threads)
  double position_sigma = 0.0;  ///< noise per coordinate of a measured point, model unit, > 0
  double direction_sigma = 0.0;  ///< noise of a measured tool direction (rotation vector), rad, ≥ 0
  /// Called from the calling thread with (finished, total) while the trials run; may be empty.
  std::function<void(int, int)> progress;
  /// Throws pkm::InvalidArgument naming the field when a setting is unusable.
  void validate() const;
};

/// What monteCarloExechon found.
struct ExechonMonteCarloSummary {
  int trials = 0;         ///< trials with an estimate
  int failures = 0;       ///< trials whose calibration threw (no estimate)
  int not_converged = 0;  ///< trials that stopped at the iteration limit (counted in trials)
  ExechonParameterVector mean = ExechonParameterVector::Zero();                ///< mean estimate
  ExechonParameterVector standard_deviation = ExechonParameterVector::Zero();  ///< sample std
  /// Sample std of the estimated measurement frame (δt model unit, δω rad, left perturbation of
  /// the estimate's frame); zero without a frame.
  Eigen::Matrix<double, 6, 1> frame_standard_deviation = Eigen::Matrix<double, 6, 1>::Zero();
  /// |p(θ_k, q) − p(θ̂, q)| pooled over trials k and workspace configurations q: the tool-point
  /// deviation of each re-estimated model from the estimate (as MonteCarloSummary::tcp).
  TcpErrorStatistics tcp;
  /// Per configuration q, the 3-D spread √trace(Cov_k p(θ_k, q)) of the re-estimated tool points:
  /// the Monte Carlo counterpart of exechonTargetUncertainty (statistics over configurations).
  TcpErrorStatistics tool_sigma;
  int configurations = 0;  ///< workspace configurations whose FK converged for the estimate
  double seconds = 0.0;    ///< wall time
};

/// Monte Carlo uncertainty of calibrateExechon: every observation of `data` is replaced by the
/// target that `estimate` (with `frame`, the estimated world_T_measurement, if any) predicts for
/// its joints plus Gaussian noise (σ_p per coordinate on points; directions rotated by a random
/// rotation vector of σ_d per component), the calibration is repeated from `initial` with the
/// starting frame data.measurement_frame, and the spread of the estimates and of the tool point
/// (target offset zero, FK seeded from the estimate's solution) over `workspace` is reported.
/// Observations whose FK fails under `estimate` are left out of every trial. When a frame is
/// estimated and a base-placement parameter is free, the world is fixed only up to a rigid motion,
/// so each trial's tool points are first aligned rigidly to the estimate's. Trial k draws from its
/// own stream (seed, k), so results do not depend on the thread count. Throws
/// pkm::InvalidArgument for invalid options or data (as calibrateExechon), or a `frame` given
/// without data.measurement_frame (or the reverse).
[[nodiscard]] ExechonMonteCarloSummary monteCarloExechon(
    const kinematics::ExechonModel& initial,
    const ExechonCalibrationData& data,
    const kinematics::ExechonModel& estimate,
    const std::optional<geometry::RigidTransform>& frame,
    const std::vector<kinematics::ExechonJoints>& workspace,
    const ExechonCalibrationOptions& calibration,
    const ExechonMonteCarloOptions& options);

}  // namespace pkm::calibration
