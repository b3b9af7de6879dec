/// @file
/// @brief The hybrid machine of seed 000 (Exechon PKM on X2 over a table on Y2) as a virtual
/// machine: the kinematic error chain of pkm/kinematics/hybrid_chain.hpp with known errors.
#pragma once

#include "pkm/kinematics/hybrid_errors.hpp"
#include "pkm/kinematics/hybrid_model.hpp"
#include "pkm/simulation/virtual_machine.hpp"

namespace pkm::simulation {

/// A hybrid machine with injected geometric errors (PDGE tables of X2 and Y2, the PKM grid, the
/// four squareness errors). Command (x2, y2, xp, yp, zp), mm; poses are w_T_t (tool in the work
/// frame, hybridActualPose). Stateless.
class HybridVirtualMachine final : public VirtualMachine {
 public:
  /// Throws pkm::InvalidArgument when the model or errors do not validate or the model's unit is
  /// not mm (measurement files are in mm).
  HybridVirtualMachine(kinematics::HybridMachineModel model, kinematics::GeometricErrors errors);
  /// {"x2", "y2", "xp", "yp", "zp"}.
  [[nodiscard]] std::vector<std::string> axisNames() const override;
  /// hybridNominalPose.
  [[nodiscard]] Eigen::Isometry3d nominalPose(const Eigen::VectorXd& command) const override;
  /// hybridActualPose with the errors evaluated at the command.
  Eigen::Isometry3d moveTo(const Eigen::VectorXd& command) override;
  /// The model.
  [[nodiscard]] const kinematics::HybridMachineModel& model() const { return model_; }
  /// The injected errors (the truth).
  [[nodiscard]] const kinematics::GeometricErrors& errors() const { return errors_; }

 private:
  kinematics::HybridMachineModel model_;
  kinematics::GeometricErrors errors_;
};

}  // namespace pkm::simulation
