/// @file
/// @brief Identification of the 42 hexapod kinematic parameters from full-pose and point
/// observations by Levenberg–Marquardt (Ceres, private to this module), with identifiability,
/// explicit handling of unidentifiable directions and parameter covariance (docs/calibration.md).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pkm/calibration/acceptance.hpp"
#include "pkm/calibration/constrained_motion.hpp"
#include "pkm/calibration/distance_measurements.hpp"
#include "pkm/calibration/hexapod_measurements.hpp"
#include "pkm/calibration/hexapod_parameters.hpp"
#include "pkm/calibration/identifiability.hpp"
#include "pkm/geometry/rigid_fit.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::calibration {

/// Robust loss applied to each observation's residual block.
enum class RobustLoss { kNone, kHuber, kCauchy };

/// The data of one identification: any mix of full-pose and point observations.
struct HexapodCalibrationData {
  std::vector<PoseObservation> poses;    ///< IK residuals, 6 equations each
  std::vector<PointObservation> points;  ///< FK point residuals, 3 equations each
  /// Constrained-motion (dial gauge) sets: 3 plane-contact equations per station.
  std::vector<ConstrainedMotionData> constrained;
  /// Distances (ball bar on a known pivot, interferometer along a line): 1 equation each; not
  /// affected by the measurement frame (a fixed end is in world).
  std::vector<DistanceObservation> distances;
  /// When set, the pose and point measurements are expressed in an instrument frame (a laser
  /// tracker's) and world_T_measurement is estimated with the parameters, starting from this value
  /// (initialMeasurementFrame gives one). The rigid motion of the base frame (6 directions) is then
  /// unidentifiable and held at the initial base joints (docs/calibration.md, "Frames").
  std::optional<geometry::RigidTransform> measurement_frame;
  /// Number of scalar equations.
  [[nodiscard]] std::size_t equations() const;
};

/// Settings of calibrateHexapod.
struct HexapodCalibrationOptions {
  HexapodParameterMask free = allHexapodParametersFree();  ///< parameters to estimate
  int max_iterations = 100;                                ///< LM iterations, ≥ 1
  /// Converged when a step (accepted, or rejected at LM damping ≤ the scaled diagonal) changes
  /// ½Σr² by at most this × ½Σr². Reachable on noisy data, where a step at the minimum changes
  /// the cost only by the rounding of the residuals (~1e-12 of it); a Gauss–Newton step that
  /// lowers the cost by a fraction t moves the estimate by about √(t·m) of its standard deviations
  /// (m residuals: 3e-4 for t = 1e-10, m = 1000) (docs/calibration.md, "Solver").
  double function_tolerance = 1e-10;
  double gradient_tolerance = 1e-14;   ///< Ceres max-norm gradient
  double parameter_tolerance = 1e-12;  ///< Ceres relative step
  RobustLoss loss = RobustLoss::kNone;
  double loss_scale = 0.0;  ///< model length unit; > 0 when loss ≠ kNone
  /// Standard deviation of one residual (model length unit) for the covariance; 0 estimates it
  /// from the final residuals as √(Σr² / (m − rank)).
  double measurement_sigma = 0.0;
  IdentifiabilityOptions identifiability;
  /// Also estimate a per-strut backlash b_i (length unit): a strut's length is its reading −
  /// approach_i·b_i/2 (PoseObservation::approach; observations with approach 0 carry no term).
  bool estimate_backlash = false;
  /// Tikhonov (maximum a posteriori) regularisation toward the initial geometry: when > 0, every
  /// free parameter gets the prior residual (σ_r/σ_θ)·(θ_k − θ₀_k), σ_θ this value (model length
  /// unit: how far the true geometry may plausibly lie from the machine file) and σ_r =
  /// measurement_sigma, which must then be > 0 (Tikhonov & Arsenin 1977, "Solutions of ill-posed
  /// problems"; Hollerbach, Khalil & Gautier, "Model identification", Springer Handbook of
  /// Robotics 2008). For data that see some combinations only weakly (dial gauges:
  /// docs/calibration.md, "Weakly identified directions"). The covariance then includes the
  /// prior. 0: no prior.
  double parameter_prior_sigma = 0.0;
  /// The uncertainty budgets' statement of the machine file's geometry, the prior's centre, as an
  /// input quantity (hexapodParameterUncertainty): one standard deviation per parameter, model
  /// length unit. 0: parameter_prior_sigma. A prior may regularise more strongly than the
  /// assembly tolerance (a ridge estimate: lower variance, some bias); the budgets then carry that
  /// bias at the tolerance stated here (docs/calibration.md, "Uncertainty budgets"). Needs
  /// parameter_prior_sigma > 0 when > 0.
  double prior_uncertainty = 0.0;
  /// Throws pkm::InvalidArgument naming the field when a setting is unusable.
  void validate() const;
};

/// Residual statistics of a data set under one parameter vector, model length unit.
struct ResidualStatistics {
  int equations = 0;    ///< residuals counted
  double rms = 0.0;     ///< root mean square
  double max = 0.0;     ///< largest magnitude
  int fk_failures = 0;  ///< point observations whose FK did not converge (not counted)
};

/// What calibrateHexapod did.
struct HexapodCalibrationSummary {
  bool converged = false;     ///< a stopping rule was met (not the iteration limit, not failure)
  std::string termination;    ///< the stopping rule's message (Ceres' or the function tolerance's)
  int iterations = 0;         ///< LM iterations taken
  double initial_cost = 0.0;  ///< ½Σr² before
  double final_cost = 0.0;    ///< ½Σr² after
  double seconds = 0.0;       ///< wall time of the solve, s
  ResidualStatistics before;  ///< on the fitted data, initial parameters
  ResidualStatistics after;   ///< on the fitted data, estimated parameters
  HexapodParameterVector initial = HexapodParameterVector::Zero();
  HexapodParameterVector parameters = HexapodParameterVector::Zero();  ///< the estimate
  /// Identifiability of the free parameters at the initial values (columns = free parameters in
  /// index order). Unidentifiable directions are held at their initial value by a prior residual
  /// n·(θ − θ₀) per null-space vector n, so they never drift silently.
  Identifiability identifiability;
  std::vector<int> free_indices;  ///< parameter index of each identifiability column
  double sigma = 0.0;             ///< the residual σ used for the covariance
  /// 42 × 42 covariance of the estimate (σ²·(JᵀJ)⁺ on the identifiable subspace; zero rows and
  /// columns for fixed parameters).
  Eigen::MatrixXd covariance;
  /// √diag(covariance), model length unit.
  HexapodParameterVector standard_deviation = HexapodParameterVector::Zero();
  /// The estimated world_T_measurement when the data has a measurement frame.
  std::optional<geometry::RigidTransform> measurement_frame;
  /// Standard deviations of the frame correction (δt mm, δω rad; world axes).
  Eigen::Matrix<double, 6, 1> frame_standard_deviation = Eigen::Matrix<double, 6, 1>::Zero();
  /// The estimated per-strut backlash (length unit) with estimate_backlash, and its σ.
  std::optional<kinematics::StrutVector> backlash;
  kinematics::StrutVector backlash_standard_deviation = kinematics::StrutVector::Zero();
  /// The parameters that moved by more than kPlausibleChangeFraction × the machine's
  /// characteristic length, largest first (calibration::implausibleChanges): the signature of a
  /// unit mistake, a tracker frame taken as the world or a wrong machine file. Empty when none.
  std::vector<ParameterChange> large_changes;
};

/// Names of the six backlash unknowns in identifiability reports: backlash0 … backlash5.
[[nodiscard]] const std::vector<std::string>& backlashNames();

/// Approach directions from the order of measurement: for each observation the sign of the change
/// of each strut reading since the previous observation (+1 longer, −1 shorter; unchanged: the
/// previous direction); the first observation gets `first` (0: unknown). Precondition: `readings`
/// in the order the machine moved through them.
[[nodiscard]] std::vector<kinematics::StrutVector> approachFromSequence(
    const std::vector<kinematics::StrutVector>& readings, double first = 0.0);

/// Names of the six measurement-frame unknowns as used in identifiability reports: frame.x,
/// frame.y, frame.z (translation) and frame.rx, frame.ry, frame.rz (world-axis rotation vector).
[[nodiscard]] const std::vector<std::string>& measurementFrameNames();

/// A starting world_T_measurement: the rigid fit (geometry::fitRigidTransform) of the measured
/// positions of the pose and point observations to the positions FK of `model` gives for their
/// readings. Throws pkm::InvalidArgument when fewer than 3 observations have a converging FK or
/// they are collinear.
[[nodiscard]] geometry::RigidTransform initialMeasurementFrame(
    const kinematics::HexapodModel& model, const HexapodCalibrationData& data);

/// Estimates the free parameters of `initial` so that the observations fit (least squares of the
/// IK residuals of poses, the FK residuals of points and the plane-contact residuals of gauge
/// stations; hexapod_measurements.hpp, constrained_motion.hpp). Throws
/// pkm::InvalidArgument when options are invalid, no parameter is free, an observation is not
/// finite, or there are fewer equations than free parameters (the message gives both counts).
[[nodiscard]] HexapodCalibrationSummary calibrateHexapod(
    const kinematics::HexapodModel& initial,
    const HexapodCalibrationData& data,
    const HexapodCalibrationOptions& options = {});

/// The residual statistics of `data` under `model`, with pose and point measurements taken in
/// `frame` (default: data.measurement_frame; world when neither is set) (FK from the measured point
/// with the home orientation for points, from the command for gauge stations).
[[nodiscard]] ResidualStatistics residualStatistics(
    const kinematics::HexapodModel& model,
    const HexapodCalibrationData& data,
    const std::optional<geometry::RigidTransform>& frame = std::nullopt,
    const std::optional<kinematics::StrutVector>& backlash = std::nullopt);

/// The size of each observation's residual after a fit, model length unit: the Euclidean norm of
/// its residual block (6 IK residuals of a pose, 3 FK residuals of a point, 3 plane contacts of a
/// gauge station) under `model` and `frame` (default data.measurement_frame), in the order poses,
/// points, then the stations of each constrained set; −1 where the FK does not converge. For
/// outlier diagnostics (the CLI names the worst by file and line).
[[nodiscard]] std::vector<double> observationResidualNorms(
    const kinematics::HexapodModel& model,
    const HexapodCalibrationData& data,
    const std::optional<geometry::RigidTransform>& frame = std::nullopt,
    const std::optional<kinematics::StrutVector>& backlash = std::nullopt);

/// The stacked identification Jacobian of `data` at `model`'s parameters: 6 rows per pose, 3 per
/// point, 3 per gauge station, 1 per distance (rows whose FK fails are zero); 42 columns, plus 6
/// for the measurement frame (measurementFrameNames) when data.measurement_frame is set.
[[nodiscard]] Eigen::MatrixXd identificationJacobian(const kinematics::HexapodModel& model,
                                                     const HexapodCalibrationData& data);

}  // namespace pkm::calibration
