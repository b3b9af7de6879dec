/// @file
/// @brief A laser tracker measuring an Exechon PKM (stand-alone or the PKM of a hybrid machine):
/// the controller solves the NOMINAL tool IK for each commanded tool pose, the true (perturbed)
/// tripod and wrist reach their FK for those leg and wrist readings, and the tracker reads an SMR
/// on the tool in its own frame (the data of an Exechon kinematic calibration; docs/formats.md,
/// "Exechon tracker files").
#pragma once

#include <string>
#include <vector>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/simulation/laser_tracker.hpp"
#include "pkm/simulation/random.hpp"
#include "pkm/simulation/unmodelled_geometry.hpp"

namespace pkm::simulation {

/// The set-up of a tracker measurement on an Exechon. Frames: "world" is the Exechon model's world
/// frame (the PKM frame P of a hybrid machine).
struct ExechonTrackerSetup {
  std::string name = "exechon-tracker";  ///< names the random stream and the file
  int count = 0;                         ///< random tool poses, ≥ 1
  /// The box of commanded tool points, world frame, mm (min ≤ max per axis).
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d box_max = Eigen::Vector3d::Zero();
  /// The mean commanded tool direction (world; normalised by pkm) and the largest tilt from it,
  /// rad (directions uniform over the spherical cap; 0: always `direction`).
  Eigen::Vector3d direction = -Eigen::Vector3d::UnitZ();
  double max_tilt = 0.0;
  /// SMR centre in the tool frame (platform_R_tool axes, origin at the tool point), mm.
  Eigen::Vector3d smr_offset = Eigen::Vector3d::Zero();
  /// The tracker's placement world_T_tracker (rigid; part of the truth).
  geometry::RigidTransform world_T_tracker = geometry::RigidTransform::Identity();
  TrackerNoise noise;  ///< the instrument noise
  /// Throws pkm::InvalidArgument for an empty name, count < 1, a non-finite or inverted box, a zero
  /// direction, a tilt outside [0, π/2], a non-finite offset, invalid noise or a placement that is
  /// not rigid.
  void validate() const;
};

/// One reading.
struct ExechonTrackerReading {
  kinematics::ExechonToolPose command;  ///< commanded tool point and direction, world
  kinematics::ExechonJoints joints;     ///< what the controller commanded (nominal IK)
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();  ///< SMR in the tracker frame, with noise
  Eigen::Vector3d truth = Eigen::Vector3d::Zero();     ///< SMR in the tracker frame, exact
};

/// Runs the measurement: draws `count` commands (uniform tool point in the box, direction uniform
/// in the cap) that the NOMINAL model reaches within every limit (checkToolPose; rejected draws are
/// redrawn, at most 200·count draws in all), moves the TRUE model there by tool FK from the
/// commanded readings (seeded with the nominal configuration) and reads the SMR with the tracker
/// noise (range, azimuth, elevation from `rng`). With `leg_lead` the true legs travel their
/// readings plus the screws' lead errors (withLeadErrors; the readings recorded are the commanded
/// ones); with a `compliance`, the true model then reaches its FK at exechonDeflectedJoints of
/// those (gravity and joint clearance, compliance.hpp). Throws pkm::InvalidArgument for an invalid
/// set-up or models, too few reachable commands, or a true FK that does not converge.
[[nodiscard]] std::vector<ExechonTrackerReading> simulateExechonTracker(
    const kinematics::ExechonModel& nominal,
    const kinematics::ExechonModel& actual,
    const kinematics::FkOptions& fk,
    const ExechonTrackerSetup& setup,
    RandomStream& rng,
    const ExechonCompliance* compliance = nullptr,
    const ExechonLegLeadErrors& leg_lead = {});

}  // namespace pkm::simulation
