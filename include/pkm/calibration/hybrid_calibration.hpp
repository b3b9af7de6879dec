/// @file
/// @brief Identification of the four squareness errors of a hybrid machine (MXT700S parallelism
/// paper, §2.2: szX2, sxP, syP, szP) from tool positions measured over all five axes, with the PDGE
/// of X2, Y2 and the PKM taken as known (measured by laser beforehand, as in the MXT700S
/// parallelism paper) and, optionally, the PKM's calibrated tripod (docs/calibration.md, "Hybrid
/// machine").
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"
#include "pkm/kinematics/hybrid_errors.hpp"
#include "pkm/kinematics/hybrid_model.hpp"

namespace pkm::calibration {

/// The PKM's error motion E_tripod(p) at a PKM command p (P frame), or nullopt where it cannot be
/// evaluated; an empty function means none.
using TripodMotion = std::function<std::optional<geometry::RigidTransform>(const Eigen::Vector3d&)>;

/// One measurement: the five commanded axes and the measured target.
struct HybridObservation {
  kinematics::HybridCommand command;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< measured target, measurement frame
  std::string source;                               ///< "FILE:LINE", for diagnostics
};

/// The data of one identification.
struct HybridCalibrationData {
  std::vector<HybridObservation> observations;
  /// The target in the tool frame t (P's axes at the TCP), model length unit; known.
  Eigen::Vector3d target_offset = Eigen::Vector3d::Zero();
  /// When set, the measurements are in an instrument frame whose placement in the work frame is
  /// estimated from this start (as ExechonCalibrationData::measurement_frame).
  std::optional<geometry::RigidTransform> measurement_frame;
};

/// Settings of calibrateHybridSquareness.
struct HybridCalibrationOptions {
  std::array<bool, 4> free{true, true, true, true};  ///< szX2, sxP, syP, szP
  int max_iterations = 100;
  /// Stopping rules of the solve (HexapodCalibrationOptions' of the same names).
  double function_tolerance = 1e-10;   ///< relative cost change of a step
  double gradient_tolerance = 1e-14;   ///< Ceres max-norm gradient
  double parameter_tolerance = 1e-12;  ///< Ceres relative step
  RobustLoss loss = RobustLoss::kNone;
  double loss_scale = 0.0;
  double measurement_sigma = 0.0;  ///< 0: estimated from the residuals
  IdentifiabilityOptions identifiability;
  int worst_count = 5;
  /// Throws pkm::InvalidArgument naming the field when a setting is unusable.
  void validate() const;
};

/// What calibrateHybridSquareness did.
struct HybridCalibrationSummary {
  bool converged = false;
  std::string termination;
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0, seconds = 0.0;
  ResidualStatistics before, after;         ///< target residuals, model length unit
  kinematics::HybridSquareness squareness;  ///< the estimate, rad
  Eigen::Vector4d standard_deviation = Eigen::Vector4d::Zero();  ///< szX2, sxP, syP, szP, rad
  Identifiability identifiability;  ///< of the free unknowns (squareness, then frame)
  std::optional<geometry::RigidTransform> measurement_frame;
  std::vector<WorstObservation> worst;
};

/// Names of the four squareness unknowns: "szX2", "sxP", "syP", "szP".
[[nodiscard]] const std::vector<std::string>& hybridSquarenessNames();

/// The target in the work frame at `command`: hybridActualPose(model, known errors with
/// `squareness`, command) · E_tripod · target_offset, with E_tripod the error motion of `tripod`
/// (the PKM's true tripod against the controller's, simulation::HybridTripod semantics) when given.
/// nullopt when the tripod cannot reach the command.
[[nodiscard]] std::optional<Eigen::Vector3d> hybridTarget(
    const kinematics::HybridMachineModel& model,
    const kinematics::GeometricErrors& known,
    const kinematics::HybridSquareness& squareness,
    const kinematics::HybridCommand& command,
    const Eigen::Vector3d& target_offset,
    const TripodMotion& tripod = {});

/// Estimates the four squareness errors, starting from zero (the known errors' own squareness is
/// ignored), with the PDGE of `known` fixed. `tripod` optionally gives the PKM's error motion
/// E_tripod(p) at a PKM command p (e.g. a calibrated Exechon against the controller's nominal one).
/// Throws pkm::InvalidArgument for invalid options, a non-finite observation (naming its source),
/// no free unknown or fewer equations than unknowns.
[[nodiscard]] HybridCalibrationSummary calibrateHybridSquareness(
    const kinematics::HybridMachineModel& model,
    const kinematics::GeometricErrors& known,
    const HybridCalibrationData& data,
    const HybridCalibrationOptions& options = {},
    const TripodMotion& tripod = {});

}  // namespace pkm::calibration
