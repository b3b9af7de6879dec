// The true hexapod behind a controller's joint commands and its sensors
// (pkm/simulation/machine_in_loop.hpp).
#include "pkm/simulation/machine_in_loop.hpp"

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::simulation {
namespace {

/// A change of a strut reading larger than this between two commands is a jump, not a servo
/// step (1 mm in 1 ms is 60 m/min), mm.
constexpr double kJump = 1.0;

}  // namespace

void LoopSensors::validate() const {
  const Eigen::Vector3d a = gauge_points[1] - gauge_points[0];
  const Eigen::Vector3d b = gauge_points[2] - gauge_points[0];
  PKM_CHECK(a.cross(b).norm() > 1e-9 * (1.0 + a.norm() * b.norm()),
            "the three gauge tips are collinear");
  PKM_CHECK(table_normal.norm() > 0 && std::isfinite(table_normal.norm()),
            "the table normal is zero");
  PKM_CHECK(laser_direction.norm() > 0 && std::isfinite(laser_direction.norm()),
            "the laser direction is zero");
}

HexapodMachineInLoop::HexapodMachineInLoop(HexapodVirtualMachine machine, LoopSensors sensors)
    : machine_(std::move(machine)),
      sensors_(std::move(sensors)),
      nominal_data_(machine_.nominal()),
      nominal_pose_(machine_.nominal().home) {
  sensors_.validate();
  sensors_.table_normal.normalize();
  sensors_.laser_direction.normalize();
}

bool HexapodMachineInLoop::command(const kinematics::StrutVector& readings) {
  if (moved_ && readings == last_) return true;
  // A servo loop's step is seeded with the last pose. A jump (a controller's joints before and
  // after homing, joints homed one by one) is solved from the machine's home, and the true
  // machine from the commanded pose, so that neither leaves the home's assembly mode.
  const bool jump = !moved_ || (readings - last_).cwiseAbs().maxCoeff() > kJump;
  const kinematics::PoseRpy& seed = jump ? machine_.nominal().home : nominal_pose_;
  const kinematics::FkSummary fk =
      kinematics::forwardKinematics(machine_.nominal(), nominal_data_, readings, seed);
  if (!fk.ok()) return false;
  Eigen::VectorXd command(6);
  command << nominal_data_.pose.position, nominal_data_.pose.rpy;
  if (jump) machine_.reset(++restarts_);
  try {
    pose_ = machine_.moveTo(command);
  } catch (const InvalidArgument&) {
    return false;
  }
  nominal_pose_ = nominal_data_.pose;
  last_ = readings;
  if (!moved_) zero_pose_ = pose_;
  moved_ = true;
  return true;
}

void HexapodMachineInLoop::zero() { zero_pose_ = pose_; }

std::array<double, 3> HexapodMachineInLoop::gauges() const {
  std::array<double, 3> out{};
  for (std::size_t j = 0; j < 3; ++j) {
    const Eigen::Vector3d& t = sensors_.gauge_points[j];
    const Eigen::Vector3d now = pose_.linear() * t + pose_.translation();
    const Eigen::Vector3d then = zero_pose_.linear() * t + zero_pose_.translation();
    out[j] = sensors_.table_normal.dot(now - then);
  }
  return out;
}

double HexapodMachineInLoop::laser() const {
  return sensors_.laser_direction.dot(pose_.translation() - zero_pose_.translation());
}

}  // namespace pkm::simulation
