/// @file
/// @brief Identification of the Exechon kinematic parameters (exechon_parameters.hpp) from tool
/// point (and optionally tool direction) measurements by Levenberg–Marquardt (Ceres, private) on
/// forward-kinematic residuals, with an optional measurement frame, identifiability, explicit
/// holding of unidentifiable directions, covariance and the worst observations listed by source
/// (docs/calibration.md, "Exechon").
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "pkm/calibration/acceptance.hpp"
#include "pkm/calibration/exechon_parameters.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/identifiability.hpp"
#include "pkm/geometry/rigid_fit.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::calibration {

/// One measurement: the machine axes the controller reported and the measured target.
struct ExechonObservation {
  kinematics::ExechonJoints joints;                 ///< leg readings (length unit), C, A (rad)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< measured target, measurement frame
  /// Measured unit tool direction (measurement frame), when the instrument gives one.
  std::optional<Eigen::Vector3d> direction;
  std::string source;  ///< where it came from ("FILE:LINE"), for diagnostics; may be empty
};

/// The data of one identification.
struct ExechonCalibrationData {
  std::vector<ExechonObservation> observations;
  /// The measured target in the tool frame (SMR offset), model length unit; known, not estimated.
  Eigen::Vector3d target_offset = Eigen::Vector3d::Zero();
  /// As HexapodCalibrationData::measurement_frame: when set, the measurements are in an instrument
  /// frame whose placement world_T_measurement is estimated with the parameters from this start.
  std::optional<geometry::RigidTransform> measurement_frame;
  /// 3 equations per observation, 3 more with a direction.
  [[nodiscard]] std::size_t equations() const;
};

/// Settings of calibrateExechon.
struct ExechonCalibrationOptions {
  ExechonParameterMask free = allExechonParametersFree();
  int max_iterations = 100;  ///< LM iterations, ≥ 1
  /// Stopping rules of the solve (HexapodCalibrationOptions' of the same names).
  double function_tolerance = 1e-10;   ///< relative cost change of a step
  double gradient_tolerance = 1e-14;   ///< Ceres max-norm gradient
  double parameter_tolerance = 1e-12;  ///< Ceres relative step
  RobustLoss loss = RobustLoss::kNone;
  double loss_scale = 0.0;         ///< model length unit; > 0 when loss ≠ kNone
  double measurement_sigma = 0.0;  ///< residual σ for the covariance; 0 estimates it
  /// Weight of a direction residual, length unit per radian (1000: 1 µrad counts as 1 µm).
  double direction_weight = 1000.0;
  IdentifiabilityOptions identifiability;
  kinematics::FkOptions fk;  ///< the tripod FK inside each residual
  int worst_count = 5;       ///< how many worst observations the summary lists, ≥ 0
  /// Plausibility limit of a parameter change, relative (calibration::implausibleChanges).
  double max_plausible_change = kPlausibleChangeFraction;
  /// Throws pkm::InvalidArgument naming the field when a setting is unusable.
  void validate() const;
};

/// An observation with a large residual after the fit.
struct WorstObservation {
  std::size_t index = 0;  ///< into data.observations
  std::string source;     ///< its source ("FILE:LINE"), or "observation N"
  double residual = 0.0;  ///< |r| of its point residual after the fit, model length unit
};

/// What calibrateExechon did.
struct ExechonCalibrationSummary {
  bool converged = false;
  std::string termination;
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0, seconds = 0.0;
  ResidualStatistics before, after;  ///< on the fitted data
  ExechonParameterVector initial = ExechonParameterVector::Zero();
  ExechonParameterVector parameters = ExechonParameterVector::Zero();  ///< the estimate
  Identifiability identifiability;  ///< of the free unknowns (parameters, then frame) at the start
  std::vector<int> free_indices;    ///< unknown index of each identifiability column (26+: frame)
  double sigma = 0.0;
  Eigen::MatrixXd covariance;  ///< (26 + 6·frame)² (zero rows/columns for fixed unknowns)
  ExechonParameterVector standard_deviation = ExechonParameterVector::Zero();
  std::optional<geometry::RigidTransform> measurement_frame;  ///< the estimate, when estimated
  Eigen::Matrix<double, 6, 1> frame_standard_deviation = Eigen::Matrix<double, 6, 1>::Zero();
  std::vector<WorstObservation> worst;  ///< largest residuals after the fit, largest first
  /// The parameters that moved by more than ExechonCalibrationOptions::max_plausible_change ×
  /// the machine's characteristic length (lengths) or kPlausibleAngleChange (angles), largest first
  /// (calibration::implausibleChanges): the signature of a unit mistake, a wrong frame or a wrong
  /// machine file. Empty when none.
  std::vector<ParameterChange> large_changes;
  /// A fit whose residual RMS exceeds 2 % of the machine size: the model does not explain the
  /// data. Empty when none.
  std::vector<std::string> warnings;
};

/// The tool-frame target of `model` for `joints` (tool FK seeded with `seed`, then the target
/// offset); std::nullopt when the FK does not converge.
[[nodiscard]] std::optional<Eigen::Vector3d> exechonTarget(
    const kinematics::ExechonModel& model,
    const kinematics::ExechonJoints& joints,
    const Eigen::Vector3d& target_offset,
    const kinematics::ExechonConfiguration& seed,
    const kinematics::FkOptions& fk = {});

/// ∂p/∂θ of the tool-frame target p at `joints` with respect to the 26 parameters (central
/// differences through the tool FK seeded with `seed`: 1e-3 length unit, 1e-6 rad; the base
/// placement relative to model.world_T_zoppi). The rows of one point observation in the
/// identification Jacobian. std::nullopt when an FK does not converge.
using ExechonTargetJacobian = Eigen::Matrix<double, 3, kExechonParameters>;
[[nodiscard]] std::optional<ExechonTargetJacobian> exechonTargetJacobian(
    const kinematics::ExechonModel& model,
    const kinematics::ExechonJoints& joints,
    const Eigen::Vector3d& target_offset,
    const kinematics::ExechonConfiguration& seed,
    const kinematics::FkOptions& fk = {});

/// The linearised uncertainty of the target position at `joints` left by the calibration:
/// √trace(J·Σ·Jᵀ) with J = ∂p/∂θ (central differences through the tool FK) and Σ the 26 × 26
/// parameter block of ExechonCalibrationSummary::covariance (model length unit). nullopt when the
/// FK does not converge. Throws pkm::InvalidArgument when Σ is smaller than 26 × 26.
[[nodiscard]] std::optional<double> exechonTargetUncertainty(
    const kinematics::ExechonModel& estimated,
    const Eigen::MatrixXd& covariance,
    const kinematics::ExechonJoints& joints,
    const Eigen::Vector3d& target_offset,
    const kinematics::ExechonConfiguration& seed,
    const kinematics::FkOptions& fk = {});

/// A starting world_T_measurement: the rigid fit of the measured points to the targets `model`
/// predicts. Throws pkm::InvalidArgument when fewer than 3 observations have a converging FK.
[[nodiscard]] geometry::RigidTransform initialExechonMeasurementFrame(
    const kinematics::ExechonModel& model,
    const ExechonCalibrationData& data,
    const kinematics::FkOptions& fk = {});

/// Residual statistics of the point residuals (world − predicted, model length unit) under `model`
/// with the measurements in `frame` (default data.measurement_frame; world when neither).
[[nodiscard]] ResidualStatistics exechonResidualStatistics(
    const kinematics::ExechonModel& model,
    const ExechonCalibrationData& data,
    const std::optional<geometry::RigidTransform>& frame = std::nullopt,
    const kinematics::FkOptions& fk = {});

/// Estimates the free parameters of `initial` (base placement relative to initial.world_T_zoppi)
/// and, with data.measurement_frame, the frame. Throws pkm::InvalidArgument for invalid options, a
/// non-finite observation or a non-unit direction (naming its source), no free parameter, fewer
/// equations than unknowns, or an initial model under which fewer than half of the observations
/// have a converging FK (a unit or model mistake).
[[nodiscard]] ExechonCalibrationSummary calibrateExechon(
    const kinematics::ExechonModel& initial,
    const ExechonCalibrationData& data,
    const ExechonCalibrationOptions& options = {});

}  // namespace pkm::calibration
