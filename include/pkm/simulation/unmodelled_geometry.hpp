/// @file
/// @brief Geometry of the true machines that their kinematic models, and so their calibrations,
/// cannot represent (docs/simulation-errors.md, "Geometry the kinematic models cannot
/// represent"): the travel deviation of a ball screw as a nonlinear function of its reading
/// (ISO 3408-3), and a universal joint whose two axes do not intersect, so that the point the
/// strut's line passes through moves with the strut's direction. The hexapod's 42 parameters
/// (point joints, one constant length offset per strut) and the Exechon's parameters have no
/// term for either.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hexapod_model.hpp"
#include "pkm/simulation/geometry_environment.hpp"
#include "pkm/simulation/random.hpp"

namespace pkm::simulation {

/// The travel deviation of one ball screw, mm: the true travel minus the travel its reading r
/// (motor angle × nominal lead) implies,
///   e(r) = progressive·(r − reference) + wave_amplitude·sin(2π·r/wave_length + wave_phase)
///        + periodic_amplitude·sin(2π·r/lead + periodic_phase)
/// (ISO 3408-3: the representative travel's slope error e_p, the variation V_300 about it and
/// the variation within one revolution V_2π). Lengths in mm, phases in rad.
struct ScrewLeadError {
  double progressive = 0.0;         ///< relative slope error (mm per mm)
  double reference = 0.0;           ///< reading where the progressive part is zero, mm
  double wave_amplitude = 0.0;      ///< mm
  double wave_length = 300.0;       ///< mm, > 0
  double wave_phase = 0.0;          ///< rad
  double periodic_amplitude = 0.0;  ///< mm
  double lead = 10.0;               ///< the screw's lead (period of the periodic part), mm, > 0
  double periodic_phase = 0.0;      ///< rad
  /// e(reading), mm.
  [[nodiscard]] double at(double reading) const;
  /// True when every amplitude and the progressive error are 0.
  [[nodiscard]] bool isZero() const;
  /// Throws pkm::InvalidArgument for a non-finite value or a wave length or lead ≤ 0.
  void validate() const;
};

/// A universal joint whose second axis is offset by `offset` from its first, along their common
/// normal. The second axis turns about the first and is perpendicular to the strut, so for a
/// strut direction u the common normal is the part of u perpendicular to the first axis a, and
/// the strut's line passes through the joint centre plus
///   shift(u) = offset·(u − (a·u)·a)/|u − (a·u)·a|
/// instead of through the centre: a point that moves with the strut's direction, unlike the
/// model's fixed joint centre. For u ⊥ a the shift lies along the strut (a length offset); the
/// part no constant parameter absorbs grows with the strut's swing towards a, offset·(1 − cos φ)
/// along the strut and offset·sin φ across it.
struct UJointOffset {
  Eigen::Vector3d first_axis = Eigen::Vector3d::UnitX();  ///< a, unit, the joint body's frame
  double offset = 0.0;                                    ///< signed, mm
  /// shift(u) in the frame of `first_axis`. Precondition: u unit, not parallel to a. Throws
  /// pkm::InvalidArgument when u is (within 1e-9) parallel to a.
  [[nodiscard]] Eigen::Vector3d shift(const Eigen::Vector3d& u) const;
};

/// The hexapod's geometry beyond its 42-parameter model, per strut.
struct HexapodUnmodelledGeometry {
  /// The struts' ball-screw lead errors; the argument is the strut reading (mm).
  std::array<ScrewLeadError, kinematics::kStruts> lead{};
  /// Base joints (world frame; offset 0 for a ball-and-socket joint).
  std::array<UJointOffset, kinematics::kStruts> base_joint{};
  /// Platform joints (platform frame).
  std::array<UJointOffset, kinematics::kStruts> platform_joint{};
  /// True when no lead error and no joint offset is set.
  [[nodiscard]] bool isZero() const;
  /// True when some joint offset is not 0.
  [[nodiscard]] bool hasJointOffsets() const;
  /// Throws pkm::InvalidArgument for an invalid lead error, a non-finite offset or a first axis
  /// that is not a unit vector.
  void validate() const;
};

/// One hexapod's unmodelled geometry drawn from `env` (GeometryEnvironment's distributions): each
/// strut's lead error with its reference at the nominal home reading, the platform joints as
/// U-joints whose first axis is horizontal in the platform frame and perpendicular to the strut at
/// home (the base joints are ball-and-socket, as in Lee et al. ("Development of a Parallel-Typed
/// CNC Machine")). All zero when env is off. Throws pkm::InvalidArgument for an invalid env or a
/// nominal model whose home IK fails.
[[nodiscard]] HexapodUnmodelledGeometry drawHexapodGeometry(const GeometryEnvironment& env,
                                                            const kinematics::HexapodModel& nominal,
                                                            RandomStream& rng);

/// Lead errors of the Exechon's three legs A, B, C (the argument is the leg reading, mm).
using ExechonLegLeadErrors = std::array<ScrewLeadError, 3>;

/// `joints` with each leg reading r replaced by the true travel r + lead[i](r) (wrist unchanged).
[[nodiscard]] kinematics::ExechonJoints withLeadErrors(kinematics::ExechonJoints joints,
                                                       const ExechonLegLeadErrors& lead);

/// Each Exechon leg's lead error drawn from `env`, its reference at the middle of the leg's
/// stroke (0 when the stroke is unbounded). All zero when env is off. Throws pkm::InvalidArgument
/// for an invalid env.
[[nodiscard]] ExechonLegLeadErrors drawLegLeadErrors(const GeometryEnvironment& env,
                                                     const kinematics::ExechonModel& nominal,
                                                     RandomStream& rng);

}  // namespace pkm::simulation
