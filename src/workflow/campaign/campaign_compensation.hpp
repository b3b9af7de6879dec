/// @file
/// @brief The controller compensations the campaign applies to its virtual machines
/// (simulation::CommandCompensation): LinuxCNC axis tables with LinuxCNC's interpolation and
/// direction law, and the hybrid machine's squareness compensation (docs/campaign.md).
#pragma once

#include <map>

#include "campaign_steps.hpp"
#include "pkm/compensation/hybrid_squareness.hpp"
#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/simulation/compensated_machine.hpp"

namespace pkm::workflow::campaign {

/// LinuxCNC COMP_FILE tables on some axes of a command: the motor position of axis i is
/// applyLinuxcncComp(table_i, command_i, direction_i), the direction the sign of the last change
/// of command_i (+1 after reset).
class AxisTableController final : public simulation::CommandCompensation {
 public:
  explicit AxisTableController(Eigen::Index axes)
      : last_(Eigen::VectorXd::Zero(axes)), dir_(axes, 1) {}
  /// Puts `file` on axis `axis` (0-based).
  void set(int axis, compensation::LinuxcncCompFile file) { tables_[axis] = std::move(file); }
  [[nodiscard]] Eigen::VectorXd apply(const Eigen::VectorXd& command) override {
    Eigen::VectorXd out = command;
    for (const auto& [axis, file] : tables_) {
      const auto a = static_cast<std::size_t>(axis);
      if (moved_ && command[axis] != last_[axis]) dir_[a] = command[axis] > last_[axis] ? 1 : -1;
      out[axis] = compensation::applyLinuxcncComp(file, command[axis], dir_[a]);
    }
    last_ = command;
    moved_ = true;
    return out;
  }
  void reset() override {
    moved_ = false;
    std::fill(dir_.begin(), dir_.end(), 1);
  }

 private:
  std::map<int, compensation::LinuxcncCompFile> tables_;
  Eigen::VectorXd last_;
  std::vector<int> dir_;
  bool moved_ = false;
};

/// The axis tables of the positioning runs: for each (measurement, axis index) the ISO 230-2
/// result over the axis position (line start + s · direction) as compensation/<axis>.comp (LinuxCNC
/// COMP_FILE type 1) and compensation/<axis>.eec.spf (SINUMERIK EEC, resampled to equidistant
/// points), recorded for the result store and put on `controller`. Throws pkm::IoError naming the
/// step when a measurement is missing, and as the table writers.
void writeAxisTables(const StepContext& ctx,
                     StepOutcome& out,
                     const LineData& data,
                     const std::vector<std::pair<std::string, int>>& tables,
                     const std::vector<std::string>& axis_names,
                     AxisTableController& controller);

/// The hybrid machine's squareness compensation on a command (x2, y2, xp, yp, zp): the PKM part
/// becomes A·p + b₀ + x2·b₁ (compensation::compensatedCommand).
class HybridSquarenessController final : public simulation::CommandCompensation {
 public:
  explicit HybridSquarenessController(compensation::HybridSquarenessCompensation c)
      : c_(std::move(c)) {}
  [[nodiscard]] Eigen::VectorXd apply(const Eigen::VectorXd& command) override {
    kinematics::HybridCommand h{command[0], command[1], command.tail<3>()};
    const kinematics::HybridCommand k = compensation::compensatedCommand(c_, h);
    Eigen::VectorXd out(5);
    out << k.x2, k.y2, k.pkm;
    return out;
  }

 private:
  compensation::HybridSquarenessCompensation c_;
};

}  // namespace pkm::workflow::campaign
