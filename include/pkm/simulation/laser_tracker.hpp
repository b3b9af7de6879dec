/// @file
/// @brief A laser tracker measuring a hexapod virtual machine: a spherically mounted retroreflector
/// (SMR, point mode) or a 6-DOF probe (pose mode) on the tool, read in the tracker's own frame at
/// a list of commanded poses, with the strut readings the controller commanded there (the data of
/// a kinematic calibration; docs/formats.md, "Laser-tracker files").
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "pkm/simulation/hexapod_workspace.hpp"
#include "pkm/simulation/random.hpp"

namespace pkm::simulation {

/// What the tracker reads.
enum class TrackerMode {
  kPoint,  ///< the position of an SMR (3 values per pose)
  kPose,   ///< the full pose of a 6-DOF probe (6 values per pose)
};

/// "point" or "pose" (scenario files, metadata).
[[nodiscard]] const char* toString(TrackerMode mode);

/// The noise of a tracker reading. A tracker measures a point in spherical coordinates, a range r
/// (interferometer or absolute distance meter) and two encoder angles, azimuth and elevation
/// (ASME B89.4.19 treats it as such a spherical coordinate system); the errors are modelled there:
///   r' = r + N(0, σ_r(r)²),  σ_r(r) = √(range_sigma² + (range_ppm·10⁻⁶·r)²),
///   az' = az + N(0, angle_sigma²),  el' = el + N(0, angle_sigma²),
/// so a point is off by σ_r along the line of sight, angle_sigma·r along the elevation direction
/// and angle_sigma·r·cos(el) along the azimuth direction. A 6-DOF probe's orientation is
/// R' = exp([n]×)·R with n ~ N(0, orientation_sigma²·I) in tracker axes (the left perturbation of
/// docs/conventions.md). All zero: the true reading, exactly, and nothing drawn.
struct TrackerNoise {
  double range_sigma = 0.0;        ///< constant range term, mm
  double range_ppm = 0.0;          ///< range term proportional to r, parts per million
  double angle_sigma = 0.0;        ///< azimuth and elevation encoder noise, rad
  double orientation_sigma = 0.0;  ///< 6-DOF probe orientation noise per axis, rad
  /// A perfect instrument (the perfect-instrument twin of `pkm validate coverage`): point() and
  /// rotation() draw their variates as the noisy tracker does, so the random stream stays aligned
  /// with the measured run, and return the true reading.
  bool perfect = false;
  /// Throws pkm::InvalidArgument when a field is negative or not finite.
  void validate() const;
  /// σ_r at range r (mm).
  [[nodiscard]] double rangeSigma(double range) const;
  /// True when every field is 0.
  [[nodiscard]] bool ideal() const;
  /// The measured point for the true point `p` (tracker frame, mm): normal variates for the range,
  /// then the azimuth, then the elevation from `rng` (none for a term whose σ is 0), or `p`
  /// unchanged when the range and angle terms are all 0. Throws pkm::InvalidArgument when p = 0
  /// and there is noise to apply.
  [[nodiscard]] Eigen::Vector3d point(const Eigen::Vector3d& p, RandomStream& rng) const;
  /// The measured rotation for the true `R`: three normal variates, or `R` unchanged and nothing
  /// drawn when orientation_sigma is 0.
  [[nodiscard]] Eigen::Matrix3d rotation(const Eigen::Matrix3d& R, RandomStream& rng) const;
};

/// Tracker noise from datasheet figures (typical values, k = 2 halved):
/// - "ideal": none.
/// - "laser-tracker": a current tracker's U(k = 2) = 15 µm + 6 µm/m taken as the standard
///   uncertainty 7.5 µm + 3 µm/m: range_sigma 7.5 µm, range_ppm 3, angle_sigma 3 µrad (3 µm/m
///   across the line of sight); a 6-DOF probe's ±0.01° orientation: orientation_sigma 0.005° =
///   87.3 µrad. The constant term is given to the range only, so across the line of sight the
///   model is optimistic at short range.
/// std::nullopt for another name.
[[nodiscard]] std::optional<TrackerNoise> trackerNoise(std::string_view name);
/// The names trackerNoise knows.
[[nodiscard]] std::vector<std::string_view> trackerNoiseNames();

/// Six fiducial nests on the table plane z = 0 of the world frame (mm): a 1000 mm square's
/// corners, its centre and a sixth off the square's edge (the set the campaign's hexapod step
/// reads; hexapod-default's table is its world z = 0 plane, 1200 mm below the base joints).
[[nodiscard]] const std::vector<Eigen::Vector3d>& defaultRegistrationNests();

/// The set-up of a tracker measurement on a hexapod.
struct TrackerSetup {
  std::string name = "laser-tracker";  ///< names the random stream and the file
  TrackerMode mode = TrackerMode::kPose;
  /// Explicit commands (x, y, z, a, b, c; mm, rad), measured first, in order.
  std::vector<Eigen::VectorXd> poses;
  /// Then this many random commands inside the workspace (sampleHexapodWorkspace on the nominal
  /// model, from the measurement's stream), ≥ 0.
  int random_count = 0;
  PoseBox random_box;  ///< where the random commands are drawn (needed when random_count > 0)
  /// The target (SMR centre, or the 6-DOF probe's origin with its axes parallel to the tool
  /// frame's) in the tool frame, mm: tool_T_target = Trans(smr_offset).
  Eigen::Vector3d smr_offset = Eigen::Vector3d::Zero();
  /// The tracker's placement: its frame in the machine's world frame (rigid). Part of the truth;
  /// the readings are in the tracker frame.
  geometry::RigidTransform world_T_tracker = geometry::RigidTransform::Identity();
  TrackerNoise noise;  ///< the instrument noise
  /// Fiducial nests on the machine's table, world frame (mm): their world coordinates define the
  /// frame a part program uses, and the tracker reads them (an SMR in each nest) to register its
  /// placement (simulateTrackerRegistration; docs/calibration.md, "Frames"). Default
  /// defaultRegistrationNests(); empty: no registration.
  std::vector<Eigen::Vector3d> registration_nests = defaultRegistrationNests();
  /// True when the tracker is not placed at the world frame (world_T_tracker is not the identity):
  /// its readings are in its own frame.
  [[nodiscard]] bool placed() const;
  /// Throws pkm::InvalidArgument for an empty name, no poses at all, a command that is not six
  /// finite values, an invalid box or noise, a non-finite offset or nest, or a placement that is
  /// not rigid.
  void validate() const;
};

/// One tracker reading of a fiducial nest.
struct NestReading {
  Eigen::Vector3d world = Eigen::Vector3d::Zero();     ///< the nest's world coordinates, mm
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();  ///< the SMR centre read, tracker frame, mm
};

/// The registration readings of `setup`: each nest of setup.registration_nests read from the
/// tracker's placement, world_T_tracker⁻¹·nest plus the tracker's noise (TrackerNoise::point, in
/// nest order, from `rng`). Throws pkm::InvalidArgument for an invalid set-up or a nest at the
/// tracker's centre.
[[nodiscard]] std::vector<NestReading> simulateTrackerRegistration(const TrackerSetup& setup,
                                                                   RandomStream& rng);

/// One tracker reading.
struct TrackerReading {
  Eigen::VectorXd command;  ///< the commanded pose (mm, rad)
  /// The strut readings the controller commanded for it (nominal IK, encoder counts), mm.
  kinematics::StrutVector lengths = kinematics::StrutVector::Zero();
  /// The measured tracker_T_target; in point mode only its translation is measured (rotation I).
  geometry::RigidTransform measured = geometry::RigidTransform::Identity();
  /// The true tracker_T_target = world_T_tracker⁻¹ · world_T_tool · Trans(smr_offset).
  geometry::RigidTransform truth = geometry::RigidTransform::Identity();
};

/// Runs the measurement: draws the random commands (when random_count > 0), then resets the
/// machine with the next raw draw of `rng`, then for each command (explicit ones first) moves the
/// machine there and reads the target, with noise from `rng` in reading order (point: range,
/// azimuth, elevation; pose: then the three orientation variates). The machine's strut backlash,
/// repeatability and encoder counts act as in HexapodVirtualMachine::moveTo. Throws
/// pkm::InvalidArgument for an invalid set-up, too few random poses in the workspace, a target at
/// the tracker's centre, or a command the true machine cannot reach.
[[nodiscard]] std::vector<TrackerReading> simulateLaserTracker(HexapodVirtualMachine& machine,
                                                               const TrackerSetup& setup,
                                                               RandomStream& rng);

}  // namespace pkm::simulation
