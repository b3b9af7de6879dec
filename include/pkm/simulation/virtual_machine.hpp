/// @file
/// @brief VirtualMachine: the interface the simulated instruments measure through. A virtual
/// ("true") machine is a nominal model plus injected errors; for an axis command it gives the
/// nominal and the actual pose of the tool in the work frame.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "pkm/geometry/rigid_transform.hpp"

namespace pkm::simulation {

/// A machine whose true errors are known. Commands are vectors of axis positions (model length unit
/// for linear axes), in the order of axisNames(). Poses are work_T_tool: the tool frame in the work
/// frame (the frame the workpiece and the fixed parts of an instrument are attached to), length
/// unit mm. moveTo may keep state (the approach direction, for backlash), so a machine is not
/// thread-safe; the instruments call reset(seed) before each measurement.
class VirtualMachine {
 public:
  virtual ~VirtualMachine() = default;
  /// The axis names, e.g. {"x", "y", "z"} or {"x2", "y2", "xp", "yp", "zp"}.
  [[nodiscard]] virtual std::vector<std::string> axisNames() const = 0;
  /// Which axes are angles (radians here, degrees in scenario files); the default: none.
  [[nodiscard]] virtual std::vector<bool> angularAxes() const {
    return std::vector<bool>(axisNames().size(), false);
  }
  /// The nominal work_T_tool at `command` (no errors). Throws pkm::InvalidArgument when the
  /// command has the wrong size or is not finite.
  [[nodiscard]] virtual geometry::RigidTransform nominalPose(
      const Eigen::VectorXd& command) const = 0;
  /// Moves to `command` and returns the actual work_T_tool there (with every injected error).
  /// Throws as nominalPose.
  virtual geometry::RigidTransform moveTo(const Eigen::VectorXd& command) = 0;
  /// Forgets the motion history (the machine is as just switched on) and seeds the machine's own
  /// random effects (repeatability) with `noise_seed`. The default does nothing.
  virtual void reset(std::uint64_t noise_seed) { (void)noise_seed; }

 protected:
  /// Only derived classes construct, copy and assign (no slicing through the interface).
  VirtualMachine() = default;
  VirtualMachine(const VirtualMachine&) = default;
  VirtualMachine& operator=(const VirtualMachine&) = default;
};

/// Throws pkm::InvalidArgument unless `command` has `axes` finite entries.
void checkCommand(const Eigen::VectorXd& command, Eigen::Index axes);

}  // namespace pkm::simulation
