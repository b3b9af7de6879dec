/// @file
/// @brief The hybrid machine of seed 000 (Exechon PKM on X2 over a table on Y2) as a virtual
/// machine: the kinematic error chain of pkm/kinematics/hybrid_chain.hpp with known errors, and
/// optionally the tripod parameter errors of its Exechon PKM (hybrid_tripod_errors.hpp).
#pragma once

#include <optional>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/hybrid_errors.hpp"
#include "pkm/kinematics/hybrid_model.hpp"
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
  /// The tripod's leg lead errors (HybridTripod::setLegLeadErrors); ignored without a tripod.
  /// Throws pkm::InvalidArgument when an error does not validate.
  void setTripodLegLeadErrors(const ExechonLegLeadErrors& lead);

 private:
  kinematics::HybridMachineModel model_;
  kinematics::GeometricErrors errors_;
  std::optional<HybridTripod> tripod_;
};

}  // namespace pkm::simulation
