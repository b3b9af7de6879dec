/// @file
/// @brief Internal: one calibration observation's residuals and Jacobians under a parameter vector
/// and an optional measurement frame, shared by the solver, the identification Jacobian and the
/// residual statistics (hexapod_least_squares.cpp, hexapod_residuals.cpp).
#pragma once

#include <Eigen/Core>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/geometry/rigid_fit.hpp"

namespace pkm::calibration::detail {

/// The measurement frame world_T_measurement = (exp([δω]x)·R₀, t₀ + δt) with δ = (δt, δω) the
/// estimated correction of the initial frame (R₀, t₀).
struct FrameEstimate {
  geometry::RigidTransform initial = geometry::RigidTransform::Identity();
  Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
  [[nodiscard]] geometry::RigidTransform current() const;
};

/// Which observation: kind and index (set and station for gauge stations).
struct ObservationRef {
  enum class Kind { kPose, kPoint, kGauge, kDistance } kind = Kind::kPose;
  std::size_t index = 0;  ///< pose, point or station index
  std::size_t set = 0;    ///< constrained set (kGauge)
  [[nodiscard]] Eigen::Index rows() const {
    return kind == Kind::kPose ? 6 : kind == Kind::kDistance ? 1 : 3;
  }
};

/// Every observation of `data`, in the order poses, points, gauge stations, distances.
[[nodiscard]] std::vector<ObservationRef> observations(const HexapodCalibrationData& data);

/// The residuals of `ref` (rows() values into r) under `model` and `frame` (nullptr: the pose and
/// point measurements are in world). J_theta (rows × 42) and J_frame (rows × 6, when frame) receive
/// the derivatives when non-null. With `backlash` (per strut, length unit) the strut lengths of a
/// pose or point observation are its readings − approach·backlash/2 (the hysteresis of
/// HexapodVirtualMachine: a strut that last moved in + stops b/2 short), and J_backlash (rows × 6)
/// receives the derivatives. False when an FK does not converge.
bool evaluate(const kinematics::HexapodModel& model,
              kinematics::HexapodData& work,
              const HexapodCalibrationData& data,
              const ObservationRef& ref,
              const FrameEstimate* frame,
              double* r,
              Eigen::MatrixXd* J_theta,
              Eigen::MatrixXd* J_frame,
              const kinematics::StrutVector* backlash = nullptr,
              Eigen::MatrixXd* J_backlash = nullptr);

/// The approach directions of `ref` (zero for gauge stations).
[[nodiscard]] kinematics::StrutVector approachOf(const HexapodCalibrationData& data,
                                                 const ObservationRef& ref);

/// `data` with every measurement replaced by what `model` predicts for its readings: poses and
/// points by FK from the measurement (mapped into `frame` when given), gauge readings by the
/// model's gauge heights relative to the reference (reference readings 0). Observations whose FK
/// fails keep their measurement.
[[nodiscard]] HexapodCalibrationData predictedData(
    const kinematics::HexapodModel& model,
    const HexapodCalibrationData& data,
    const std::optional<geometry::RigidTransform>& frame);

}  // namespace pkm::calibration::detail
