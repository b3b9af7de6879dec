#include "pkm/simulation/compensated_machine.hpp"

#include <fmt/ranges.h>

#include <utility>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"

namespace pkm::simulation {

CompensatedMachine::CompensatedMachine(std::shared_ptr<VirtualMachine> machine,
                                       std::shared_ptr<CommandCompensation> compensation)
    : machine_(std::move(machine)), compensation_(std::move(compensation)) {
  PKM_CHECK(machine_ != nullptr, "a compensated machine needs a machine");
  PKM_CHECK(compensation_ != nullptr, "a compensated machine needs a compensation");
}

std::vector<std::string> CompensatedMachine::axisNames() const { return machine_->axisNames(); }

std::vector<bool> CompensatedMachine::angularAxes() const { return machine_->angularAxes(); }

geometry::RigidTransform CompensatedMachine::nominalPose(const Eigen::VectorXd& command) const {
  return machine_->nominalPose(command);
}

geometry::RigidTransform CompensatedMachine::moveTo(const Eigen::VectorXd& command) {
  checkCommand(command, static_cast<Eigen::Index>(machine_->axisNames().size()));
  const Eigen::VectorXd sent = compensation_->apply(command);
  PKM_CHECK(sent.size() == command.size() && sent.allFinite(),
            "the compensation gave an unusable command for ({})",
            fmt::join(command, ", "));
  return machine_->moveTo(sent);
}

void CompensatedMachine::reset(std::uint64_t noise_seed) {
  compensation_->reset();
  machine_->reset(noise_seed);
}

void CompensationChain::add(std::shared_ptr<CommandCompensation> c) {
  if (c) chain_.push_back(std::move(c));
}

Eigen::VectorXd CompensationChain::apply(const Eigen::VectorXd& command) {
  Eigen::VectorXd c = command;
  for (const auto& step : chain_) c = step->apply(c);
  return c;
}

void CompensationChain::reset() {
  for (const auto& step : chain_) step->reset();
}

}  // namespace pkm::simulation
