/// @file
/// @brief The physical hexapod behind a controller's joint commands, with the sensors of Lee et
/// al.'s calibration ("Development of a Parallel-Typed CNC Machine", §3-§5): three dial gauges on
/// the platform touching the table, and a laser interferometer along x. A controller in the loop
/// (LinuxCNC through the `pkm-truth` HAL component, docs/linuxcnc.md) sends strut readings; the
/// true machine (assembly errors, encoder resolution, backlash, repeatability) takes them and the
/// sensors read where it really is.
#pragma once

#include <array>
#include <optional>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"

namespace pkm::simulation {

/// Where the sensors are.
struct LoopSensors {
  /// The dial-gauge tips in the tool frame, mm: the triangle of seed 004's calibration scenario
  /// (data/scenarios/seed004-hexapod-calibration.json), 150 mm from the tool point.
  std::array<Eigen::Vector3d, 3> gauge_points{
      Eigen::Vector3d(150, 0, 0), Eigen::Vector3d(-75, 129.9, 0), Eigen::Vector3d(-75, -129.9, 0)};
  /// The table's unit normal, world frame: a gauge reads its tip's displacement along it.
  Eigen::Vector3d table_normal = Eigen::Vector3d::UnitZ();
  /// The laser's beam direction, world frame: it reads the tool point's displacement along it.
  Eigen::Vector3d laser_direction = Eigen::Vector3d::UnitX();
  /// Throws pkm::InvalidArgument for collinear gauge tips or a zero direction.
  void validate() const;
};

/// The true machine and its sensors, driven by strut readings.
class HexapodMachineInLoop {
 public:
  /// Throws pkm::InvalidArgument for invalid sensors.
  HexapodMachineInLoop(HexapodVirtualMachine machine, LoopSensors sensors = {});

  /// The controller commands strut readings `readings` (mm). When they differ from the last
  /// command, the struts move (the true machine's actuation: one repeatability draw per move) and
  /// the platform goes where the true geometry puts it: forward kinematics seeded with the last
  /// pose for a servo step; for a jump (a reading changing by more than 1 mm: before and after
  /// homing) the nominal one from home and the true one from the commanded pose (the true
  /// machine is reset then: its approach directions forgotten), so that neither leaves home's
  /// assembly mode. Returns false, keeping the last pose, when either does not converge.
  bool command(const kinematics::StrutVector& readings);

  /// Zeroes the gauges and the laser at the present pose (as an operator sets the dials to zero).
  void zero();

  /// Gauge readings, mm: n·(tip − tip at zero), positive when a tip moves along the table normal
  /// (0 before the first command).
  [[nodiscard]] std::array<double, 3> gauges() const;
  /// Laser reading, mm: the tool point's displacement along the beam since zero().
  [[nodiscard]] double laser() const;
  /// The true pose world_T_tool (identity before the first command).
  [[nodiscard]] const geometry::RigidTransform& truePose() const { return pose_; }
  /// The pose the controller believes in: the nominal forward kinematics of the last command.
  [[nodiscard]] const kinematics::PoseRpy& commandedPose() const { return nominal_pose_; }
  /// Whether a command has been taken.
  [[nodiscard]] bool moved() const { return moved_; }

 private:
  HexapodVirtualMachine machine_;
  LoopSensors sensors_;
  kinematics::HexapodData nominal_data_;
  kinematics::PoseRpy nominal_pose_;
  kinematics::StrutVector last_ = kinematics::StrutVector::Constant(-1e300);
  geometry::RigidTransform pose_ = geometry::RigidTransform::Identity();
  geometry::RigidTransform zero_pose_ = geometry::RigidTransform::Identity();
  bool moved_ = false;
  std::uint64_t restarts_ = 0;  ///< seeds of the true machine's noise after a restart
};

}  // namespace pkm::simulation
