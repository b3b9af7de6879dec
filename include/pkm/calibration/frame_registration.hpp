/// @file
/// @brief The registration of a measuring instrument's frame (a laser tracker's) to the machine's
/// world frame from reference points whose world coordinates are known — fiducial nests on the
/// table, which define the frame a part program uses — and the calibration data moved into world
/// by it (docs/calibration.md, "Frames").
#pragma once

#include <Eigen/Core>
#include <vector>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/geometry/rigid_transform.hpp"

namespace pkm::calibration {

/// A fitted world_T_measurement with its quality and uncertainty.
struct FrameRegistration {
  geometry::RigidTransform world_T_measurement = geometry::RigidTransform::Identity();
  int references = 0;  ///< reference points fitted
  /// |world_k − world_T_measurement·measured_k| per reference, length unit.
  std::vector<double> residuals;
  double rms = 0.0;  ///< RMS of `residuals`
  double max = 0.0;  ///< largest of `residuals`
  /// The per-coordinate standard deviation of a reference used for the covariance: the larger of
  /// the residual estimate √(Σ|r|²/(3n − 6)) (when 3n > 6) and the stated σ.
  double sigma = 0.0;
  /// 6 × 6 covariance of the registration error (δt length unit, δω rad; world axes, left
  /// perturbation as measurement frames elsewhere: T' = (I + [δω]×)·T + δt): σ²·(AᵀA)⁻¹ with
  /// A_k = [I, −[p_k]×] at the registered reference p_k (Gauss–Markov).
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  /// The standard uncertainty (length unit) of the registration at world point p along its worst
  /// direction: √λ_max(A·Σ·Aᵀ), A = [I, −[p]×].
  [[nodiscard]] double uncertaintyAt(const Eigen::Vector3d& p) const;
};

/// Fits world_T_measurement to the pairs (world_k, measured_k) (geometry::fitRigidTransform:
/// Kabsch 1976, Umeyama 1991 without scale) with its residuals and covariance; `stated_sigma`
/// (≥ 0, length unit) is the instrument's per-coordinate σ, a floor for the covariance when
/// few references leave the residual estimate unreliable. Throws pkm::InvalidArgument for
/// different sizes, fewer than 3 references, non-finite values, or references on one line.
[[nodiscard]] FrameRegistration registerMeasurementFrame(
    const std::vector<Eigen::Vector3d>& world,
    const std::vector<Eigen::Vector3d>& measured,
    double stated_sigma = 0.0);

/// Moves the pose and point measurements of `data` from the measurement frame into world:
/// pose ← world_T_measurement·pose, point ← world_T_measurement·point; clears
/// data.measurement_frame (the data are then world-frame data, every parameter identifiable from
/// full poses). Gauge stations and distances do not depend on the frame.
void expressInWorld(HexapodCalibrationData& data,
                    const geometry::RigidTransform& world_T_measurement);

}  // namespace pkm::calibration
