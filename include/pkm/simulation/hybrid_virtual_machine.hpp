/// @file
/// @brief The hybrid machine of the MXT700S parallelism paper (Exechon PKM on X2 over a table on
/// Y2) as a virtual machine: the kinematic error chain of pkm/kinematics/hybrid_chain.hpp with
/// known errors, and optionally the tripod parameter errors of its Exechon PKM
/// (hybrid_tripod_errors.hpp).
#pragma once

#include <optional>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/hybrid_errors.hpp"
#include "pkm/kinematics/hybrid_model.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/simulation/hybrid_tripod_errors.hpp"
#include "pkm/simulation/virtual_machine.hpp"

namespace pkm::simulation {

/// A hybrid machine with injected geometric errors (PDGE tables of X2 and Y2, the PKM grid, the
/// four squareness errors) and, optionally, tripod parameter errors of the Exechon PKM. Command
/// (x2, y2, xp, yp, zp), mm; poses are w_T_t (tool in the work frame, hybridActualPose, times
/// E_tripod when a tripod is given). Stateless.
class HybridVirtualMachine final : public VirtualMachine {
 public:
  /// Throws pkm::InvalidArgument when the model or errors do not validate or the model's unit is
  /// not mm (measurement files are in mm).
  /// With a `tripod`, moveTo also applies its E_tripod at the PKM command (after the PKM grid:
  /// w_T_t = hybridActualPose · E_tripod); without one, moveTo is hybridActualPose exactly.
  HybridVirtualMachine(kinematics::HybridMachineModel model,
                       kinematics::GeometricErrors errors,
                       std::optional<HybridTripod> tripod = std::nullopt);
  /// {"x2", "y2", "xp", "yp", "zp"}.
  [[nodiscard]] std::vector<std::string> axisNames() const override;
  /// hybridNominalPose.
  [[nodiscard]] geometry::RigidTransform nominalPose(const Eigen::VectorXd& command) const override;
  /// hybridActualPose with the errors evaluated at the command, times the tripod's error motion
  /// when there is one (which throws pkm::InvalidArgument where the PKM cannot reach the command).
  geometry::RigidTransform moveTo(const Eigen::VectorXd& command) override;
  /// The model.
  [[nodiscard]] const kinematics::HybridMachineModel& model() const { return model_; }
  /// The injected errors (the truth).
  [[nodiscard]] const kinematics::GeometricErrors& errors() const { return errors_; }
  /// The Exechon PKM with its tripod errors, when given.
  [[nodiscard]] const std::optional<HybridTripod>& tripod() const { return tripod_; }
  /// Gravity sag of the extending axes (environment.hpp AxisSag, compliance.hpp), applied after
  /// the chain (and the tripod) in the work frame: X2 carries the tool, so w_T_t →
  /// sagCarryingTool(w_T_t, axisDeflection(x2, x2), sense·x̂, the X2 carriage's nominal origin
  /// x2·x̂ − y2·ŷ − Y2_p_work); Y2 carries the table and the work, so w_T_t →
  /// sagCarryingWork(w_T_t, axisDeflection(y2, y2), sense·ŷ, the Y2 carriage's origin
  /// −Y2_p_work). Both kNone (the default) switch it off. Throws pkm::InvalidArgument for an
  /// invalid sag.
  void setSag(const AxisSag& x2, const AxisSag& y2);
  /// Gravity compliance of the tripod's legs (HybridTripod::setCompliance); nothing without a
  /// tripod.
  void setTripodCompliance(const std::optional<ExechonCompliance>& compliance);
  /// The sag of X2 and of Y2 in effect.
  [[nodiscard]] const AxisSag& sagX2() const { return sag_x2_; }
  [[nodiscard]] const AxisSag& sagY2() const { return sag_y2_; }
  /// The tripod's leg lead errors (HybridTripod::setLegLeadErrors); ignored without a tripod.
  /// Throws pkm::InvalidArgument when an error does not validate.
  void setTripodLegLeadErrors(const ExechonLegLeadErrors& lead);
  /// Thermal tilt of the PKM relative to its extending axes (environment.hpp,
  /// ThermalEnvironment::warmup_tilt_rad): the PKM frame P turns by exp([ω]×) on top of its
  /// squareness, i.e. sxP, syP, szP change by ω_x, −ω_y, ω_z (squarenessRotationP), so the PKM's
  /// own motions change direction while X2 and Y2 do not. ω in rad; zero (the default) switches it
  /// off. Throws pkm::InvalidArgument for a non-finite ω.
  void setPkmTilt(const Eigen::Vector3d& omega);
  /// The tilt in effect, rad.
  [[nodiscard]] const Eigen::Vector3d& pkmTilt() const { return tilt_; }

 private:
  kinematics::HybridMachineModel model_;
  kinematics::GeometricErrors errors_;
  kinematics::HybridSquareness squareness_;  ///< errors_'s own squareness (before any tilt)
  Eigen::Vector3d tilt_ = Eigen::Vector3d::Zero();
  std::optional<HybridTripod> tripod_;
  AxisSag sag_x2_;
  AxisSag sag_y2_;
};

}  // namespace pkm::simulation
