/// @file
/// @brief Tripod parameter errors of the hybrid machine's Exechon PKM (the MXT700S parallelism
/// paper's "the PKM is an Exechon", beyond its Cartesian error grid): the controller solves the
/// NOMINAL Exechon tool IK for the commanded PKM point with a vertical tool, the true (perturbed)
/// tripod reaches its FK for those leg and wrist readings, and the difference is a PKM error motion
/// at the TCP.
///
/// Definition (pkm's; the PKM frames of docs/conventions.md "Hybrid machine"): with the PKM command
/// p (the tool point in the Exechon model's world frame, whose axes are P's) and the tool direction
/// u = −z,
///   (legs, C, A) = toolIK_nominal(p, u),   T_nom = toolFK_nominal(legs, C, A) = [R_nom, p_nom],
///   T_true = toolFK_true(legs, C, A) = [R_true, p_true],
/// the error motion of the hybrid tool frame t (P's axes, origin at the TCP) is
///   E_tripod = [R_true·R_nomᵀ, p_true − p_nom],
/// i.e. T_nom⁻¹·T_true (the error in the nominal Exechon tool frame) re-expressed in t's axes:
/// t_true = t_nom·E_tripod. The chain composes it after the PKM grid: P_T_t = Trans(P_p_tcp0 + p) ·
/// E(e_P(p)) · E_tripod.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/simulation/unmodelled_geometry.hpp"

namespace pkm::simulation {

/// Errors of the true tripod and wrist: each value is added to the nominal model's parameter of the
/// same name (ExechonTripodGeometry, ExechonLeg::length_offset, ExechonWrist). Lengths in the model
/// length unit (mm), angles in rad. The branch signs are not errors.
struct ExechonTripodErrors {
  double dA = 0.0;    ///< error of dA (base joint P1A on jb)
  double dB = 0.0;    ///< error of dB (base joint P1B on ib)
  double dC = 0.0;    ///< error of dC (base joint P1C on jb)
  double l12A = 0.0;  ///< error of l12A (leg A's U-joint axis offset)
  double l12C = 0.0;  ///< error of l12C
  double l12B = 0.0;  ///< error of l12B (leg B's base S-joint: R1 to R2)
  double l23B = 0.0;  ///< error of l23B (leg B's base S-joint: R2 to the leg axis)
  double pA = 0.0;    ///< error of pA (platform joint P4A)
  double pB = 0.0;    ///< error of pB (platform joint P5B)
  double pC = 0.0;    ///< error of pC (platform joint P4C)
  double hA = 0.0;    ///< error of hA
  double hC = 0.0;    ///< error of hC
  double hx = 0.0;    ///< error of hx (wrist point S in the platform frame)
  double hz = 0.0;    ///< error of hz
  /// Errors of the legs' length offsets (A, B, C): the true geometric length is reading +
  /// length_offset + this, so a positive value makes the leg longer than the controller assumes.
  Eigen::Vector3d length_offset = Eigen::Vector3d::Zero();
  double c0 = 0.0;           ///< error of the wrist C zero offset, rad
  double a0 = 0.0;           ///< error of the wrist A zero offset, rad
  double tool_length = 0.0;  ///< error of the tool length

  /// True when every value is exactly 0.
  [[nodiscard]] bool isZero() const;
  /// Throws pkm::InvalidArgument naming the field when a value is not finite.
  void validate() const;
};

/// The nominal model with `errors` added (the true machine). Throws pkm::InvalidArgument when the
/// errors or the resulting model do not validate (ExechonModel::validate).
[[nodiscard]] kinematics::ExechonModel perturbedExechon(const kinematics::ExechonModel& nominal,
                                                        const ExechonTripodErrors& errors);

/// The Exechon PKM of a hybrid machine with tripod errors: the nominal model the controller uses,
/// the true one, and the tripod FK settings.
class HybridTripod {
 public:
  /// Throws pkm::InvalidArgument when `nominal` or the perturbed model do not validate, the errors
  /// are not finite or `fk` is invalid.
  HybridTripod(kinematics::ExechonModel nominal,
               const ExechonTripodErrors& errors,
               kinematics::FkOptions fk = {});
  /// E_tripod at the PKM command `p` (file comment; mm, rad, P's axes). Tool direction −z, tool IK
  /// in the model's branch with the wrist nearest home; the true FK is seeded with the nominal
  /// solution. Throws pkm::InvalidArgument for a non-finite p, or when the nominal IK or the true
  /// FK fails there (p outside the PKM's reach).
  [[nodiscard]] geometry::RigidTransform errorMotion(const Eigen::Vector3d& p) const;
  /// The controller's (nominal) model.
  [[nodiscard]] const kinematics::ExechonModel& nominal() const { return nominal_; }
  /// The true (perturbed) model.
  [[nodiscard]] const kinematics::ExechonModel& actual() const { return actual_; }
  /// The injected errors.
  [[nodiscard]] const ExechonTripodErrors& errors() const { return errors_; }
  /// The tripod FK settings.
  [[nodiscard]] const kinematics::FkOptions& fkOptions() const { return fk_; }
  /// Gravity compliance and joint clearance of the true tripod's legs (compliance.hpp): errorMotion
  /// then takes the true FK at exechonDeflectedJoints of the commanded readings. std::nullopt
  /// (the default) switches it off. Throws pkm::InvalidArgument for an invalid compliance.
  void setCompliance(std::optional<ExechonCompliance> compliance);
  /// The compliance in effect.
  [[nodiscard]] const std::optional<ExechonCompliance>& compliance() const { return compliance_; }
  /// The legs' ball-screw lead errors, beyond the tripod model (unmodelled_geometry.hpp): the true
  /// FK takes each leg at its reading r plus e(r). All zero (the default) leaves the tripod as it
  /// was. Throws pkm::InvalidArgument when an error does not validate.
  void setLegLeadErrors(const ExechonLegLeadErrors& lead);
  /// The legs' lead errors.
  [[nodiscard]] const ExechonLegLeadErrors& legLeadErrors() const { return lead_; }

 private:
  kinematics::ExechonModel nominal_;
  kinematics::ExechonModel actual_;
  ExechonTripodErrors errors_;
  kinematics::FkOptions fk_;
  std::optional<ExechonCompliance> compliance_;
  ExechonLegLeadErrors lead_{};
};

}  // namespace pkm::simulation
