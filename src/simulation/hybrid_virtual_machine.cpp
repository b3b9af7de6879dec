#include "pkm/simulation/hybrid_virtual_machine.hpp"

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
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
                                           kinematics::GeometricErrors errors,
                                           std::optional<HybridTripod> tripod)
    : model_(std::move(model)), errors_(std::move(errors)), tripod_(std::move(tripod)) {
  model_.validate();
  errors_.validate();
  PKM_CHECK(model_.unit == LengthUnit::kMillimetre,
            "machine '{}': simulated measurements need a machine in mm",
            model_.name);
}

std::vector<std::string> HybridVirtualMachine::axisNames() const {
  return {"x2", "y2", "xp", "yp", "zp"};
}

geometry::RigidTransform HybridVirtualMachine::nominalPose(const Eigen::VectorXd& command) const {
  return kinematics::hybridNominalPose(model_, toCommand(command));
}

geometry::RigidTransform HybridVirtualMachine::moveTo(const Eigen::VectorXd& command) {
  const kinematics::HybridCommand c = toCommand(command);
  const geometry::RigidTransform pose = kinematics::hybridActualPose(model_, errors_, c);
  if (!tripod_) return pose;
  return pose * tripod_->errorMotion(c.pkm);  // P_T_t = Trans(q) · E(e_P(p)) · E_tripod
}

void HybridVirtualMachine::setTripodLegLeadErrors(const ExechonLegLeadErrors& lead) {
  if (tripod_) tripod_->setLegLeadErrors(lead);
}

}  // namespace pkm::simulation
