#include "pkm/simulation/hybrid_virtual_machine.hpp"

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"

namespace pkm::simulation {

namespace {
kinematics::HybridCommand toCommand(const Eigen::VectorXd& c) {
  checkCommand(c, 5);
  kinematics::HybridCommand command;
  command.x2 = c[0];
  command.y2 = c[1];
  command.pkm = c.tail<3>();
  return command;
}
}  // namespace

HybridVirtualMachine::HybridVirtualMachine(kinematics::HybridMachineModel model,
                                           kinematics::GeometricErrors errors)
    : model_(std::move(model)), errors_(std::move(errors)) {
  model_.validate();
  errors_.validate();
  PKM_CHECK(model_.unit == LengthUnit::kMillimetre,
            "machine '{}': simulated measurements need a machine in mm",
            model_.name);
}

std::vector<std::string> HybridVirtualMachine::axisNames() const {
  return {"x2", "y2", "xp", "yp", "zp"};
}

Eigen::Isometry3d HybridVirtualMachine::nominalPose(const Eigen::VectorXd& command) const {
  return kinematics::hybridNominalPose(model_, toCommand(command));
}

Eigen::Isometry3d HybridVirtualMachine::moveTo(const Eigen::VectorXd& command) {
  return kinematics::hybridActualPose(model_, errors_, toCommand(command));
}

}  // namespace pkm::simulation
