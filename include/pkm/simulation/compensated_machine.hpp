/// @file
/// @brief A virtual machine behind a compensating controller: every command passes through a
/// compensation (axis tables, base-frame rotation, G-code correction ...) before the true machine
/// moves, while the nominal pose stays that of the command the user gave. Re-measuring a campaign
/// on it shows what the compensation achieves (docs/campaign.md).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/simulation/virtual_machine.hpp"

namespace pkm::simulation {

/// What a controller does to a command before the axes move. May keep state (the approach
/// direction of each axis, for bidirectional tables); reset() forgets it.
class CommandCompensation {
 public:
  virtual ~CommandCompensation() = default;
  /// The command sent to the axes for the user's `command` (same size and units).
  [[nodiscard]] virtual Eigen::VectorXd apply(const Eigen::VectorXd& command) = 0;
  /// Forgets the motion history; the default does nothing.
  virtual void reset() {}

 protected:
  CommandCompensation() = default;
  CommandCompensation(const CommandCompensation&) = default;
  CommandCompensation& operator=(const CommandCompensation&) = default;
};

/// `machine` with `compensation` in its controller: moveTo(c) = machine.moveTo(compensation(c)),
/// nominalPose(c) = machine.nominalPose(c).
class CompensatedMachine final : public VirtualMachine {
 public:
  /// Throws pkm::InvalidArgument when either pointer is null.
  CompensatedMachine(std::shared_ptr<VirtualMachine> machine,
                     std::shared_ptr<CommandCompensation> compensation);
  [[nodiscard]] std::vector<std::string> axisNames() const override;
  [[nodiscard]] std::vector<bool> angularAxes() const override;
  [[nodiscard]] geometry::RigidTransform nominalPose(const Eigen::VectorXd& command) const override;
  /// Throws as the inner machine, and pkm::InvalidArgument when the compensation changes the
  /// command's size or makes it non-finite.
  geometry::RigidTransform moveTo(const Eigen::VectorXd& command) override;
  /// Resets the compensation and the inner machine.
  void reset(std::uint64_t noise_seed) override;

 private:
  std::shared_ptr<VirtualMachine> machine_;
  std::shared_ptr<CommandCompensation> compensation_;
};

/// A chain of compensations applied in order (first the first).
class CompensationChain final : public CommandCompensation {
 public:
  /// Appends `c` (ignored when null).
  void add(std::shared_ptr<CommandCompensation> c);
  [[nodiscard]] Eigen::VectorXd apply(const Eigen::VectorXd& command) override;
  void reset() override;
  /// Number of compensations.
  [[nodiscard]] std::size_t size() const { return chain_.size(); }

 private:
  std::vector<std::shared_ptr<CommandCompensation>> chain_;
};

}  // namespace pkm::simulation
