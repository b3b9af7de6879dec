#include "pkm/simulation/hybrid_virtual_machine.hpp"

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"
#include "pkm/simulation/compliance.hpp"

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
    : model_(std::move(model)),
      errors_(std::move(errors)),
      squareness_(errors_.squareness),
      tripod_(std::move(tripod)) {
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
  geometry::RigidTransform pose = kinematics::hybridActualPose(model_, errors_, c);
  if (tripod_) pose = pose * tripod_->errorMotion(c.pkm);  // P_T_t = Trans(q)·E(e_P(p))·E_tripod
  if (sag_x2_.kind != AxisSag::Kind::kNone) {
    const Eigen::Vector3d pivot =
        c.x2 * Eigen::Vector3d::UnitX() - c.y2 * Eigen::Vector3d::UnitY() - model_.Y2_p_work;
    pose = sagCarryingTool(
        pose, axisDeflection(sag_x2_, c.x2), sag_x2_.sense * Eigen::Vector3d::UnitX(), pivot);
  }
  if (sag_y2_.kind != AxisSag::Kind::kNone)
    pose = sagCarryingWork(pose,
                           axisDeflection(sag_y2_, c.y2),
                           sag_y2_.sense * Eigen::Vector3d::UnitY(),
                           -model_.Y2_p_work);
  return pose;
}

void HybridVirtualMachine::setTripodCompliance(const std::optional<ExechonCompliance>& compliance) {
  if (tripod_) tripod_->setCompliance(compliance);
}

void HybridVirtualMachine::setSag(const AxisSag& x2, const AxisSag& y2) {
  std::string why;
  PKM_CHECK(x2.isValid(&why), "X2 sag: {}", why);
  PKM_CHECK(y2.isValid(&why), "Y2 sag: {}", why);
  sag_x2_ = x2;
  sag_y2_ = y2;
}

void HybridVirtualMachine::setTripodLegLeadErrors(const ExechonLegLeadErrors& lead) {
  if (tripod_) tripod_->setLegLeadErrors(lead);
}

void HybridVirtualMachine::setPkmTilt(const Eigen::Vector3d& omega) {
  PKM_CHECK(omega.allFinite(), "PKM tilt must be finite");
  tilt_ = omega;
  errors_.squareness = squareness_;
  errors_.squareness.sx_p += omega.x();
  errors_.squareness.sy_p -= omega.y();
  errors_.squareness.sz_p += omega.z();
}

}  // namespace pkm::simulation
