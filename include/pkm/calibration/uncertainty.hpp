/// @file
/// @brief Uncertainty of a hexapod calibration (docs/calibration.md, "Uncertainty"): Monte Carlo
/// over simulated measurement noise (multi-threaded, with progress), and the TCP error a model
/// leaves over the workspace (mean, 95th percentile, max).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "pkm/calibration/hexapod_calibration.hpp"

namespace pkm::calibration {

/// Statistics of TCP position errors (model length unit).
struct TcpErrorStatistics {
  int samples = 0;    ///< errors counted
  double mean = 0.0;  ///< mean |error|
  double p95 = 0.0;   ///< 95th percentile of |error| (nearest rank)
  double max = 0.0;   ///< largest |error|
};

/// The statistics of `errors` (|error| values). Throws pkm::InvalidArgument for a non-finite value.
[[nodiscard]] TcpErrorStatistics tcpErrorStatistics(std::vector<double> errors);

/// The TCP position error over `poses` of a machine whose true geometry is `truth` when its
/// controller runs `controller`: for each commanded pose X, q = IK_controller(X), and the error is
/// |p(FK_truth(q)) − p(X)|. Poses whose FK does not converge are skipped (not counted).
[[nodiscard]] TcpErrorStatistics tcpErrorOverWorkspace(
    const kinematics::HexapodModel& controller,
    const kinematics::HexapodModel& truth,
    const std::vector<kinematics::PoseRpy>& poses);

/// Settings of monteCarloHexapod.
struct MonteCarloOptions {
  int trials = 100;        ///< simulated repetitions of the measurement, ≥ 2
  int threads = 0;         ///< worker threads; 0: std::thread::hardware_concurrency()
  std::uint64_t seed = 1;  ///< seed of the simulated noise (results do not depend on threads)
  double position_sigma =
      0.0;  ///< noise of measured positions, model unit (> 0 unless points/poses are absent)
  double orientation_sigma = 0.0;  ///< noise of measured orientations, rad (≥ 0)
  double gauge_sigma = 0.0;        ///< noise of gauge readings, model unit (≥ 0)
  /// Called from the calling thread with (finished, total) while the trials run; may be empty.
  std::function<void(int, int)> progress;
  /// Throws pkm::InvalidArgument naming the field when a setting is unusable.
  void validate() const;
};

/// What monteCarloHexapod found.
struct MonteCarloSummary {
  int trials = 0;         ///< trials with an estimate
  int failures = 0;       ///< trials whose calibration threw (no estimate)
  int not_converged = 0;  ///< trials that stopped at the iteration limit (counted in trials)
  HexapodParameterVector mean = HexapodParameterVector::Zero();  ///< mean estimate
  HexapodParameterVector standard_deviation = HexapodParameterVector::Zero();
  /// The TCP error over the workspace poses of the re-estimated models against `estimate`
  /// (pooled over trials and poses): the calibration's uncertainty expressed at the tool. With a
  /// measurement frame, each trial is first aligned rigidly (the world's rigid motion is not
  /// observable from tracker data).
  TcpErrorStatistics tcp;
  double seconds = 0.0;  ///< wall time
};

/// Monte Carlo uncertainty of calibrateHexapod: the measurements of `data` are replaced by what
/// `estimate` (with `frame`, the estimated measurement frame, if any) predicts for their readings
/// plus Gaussian noise of the given sigmas, the calibration is repeated from `initial` for each
/// trial, and the spread of the estimates and of the TCP position over `workspace` is reported.
/// Trial k draws from its own stream (seed, k), so results do not depend on the thread count.
/// Throws pkm::InvalidArgument for invalid options or data (as calibrateHexapod).
[[nodiscard]] MonteCarloSummary monteCarloHexapod(
    const kinematics::HexapodModel& initial,
    const HexapodCalibrationData& data,
    const kinematics::HexapodModel& estimate,
    const std::optional<geometry::RigidTransform>& frame,
    const std::vector<kinematics::PoseRpy>& workspace,
    const HexapodCalibrationOptions& calibration,
    const MonteCarloOptions& options);

}  // namespace pkm::calibration
