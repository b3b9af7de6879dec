// The running LinuxCNC as the rig of a constrained-motion measurement, its laser's x-move
// measurement and a calibrated geometry applied to its pkmhexkins pins (internal to src/live;
// live_calibration.hpp documents the routine).
#pragma once

#include <array>
#include <string>

#include "pkm/io/hexapod_machine.hpp"
#include "pkm/live/linuxcnc_commander.hpp"
#include "pkm/simulation/dial_gauges.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::live::detail {

/// The MDI line of a command (x y z in mm, a b c in rad): a rapid move in machine coordinates
/// (G53: work offsets do not apply), 9 decimals.
[[nodiscard]] std::string moveLine(const Eigen::VectorXd& command);

/// Moves to `command` (moveLine) and checks that LinuxCNC then commands that pose (1e-6 mm and
/// degrees): a move that ended elsewhere (an MDI that was not executed, an offset) stops the
/// routine. Returns LinuxCNC's state. Throws pkm::IoError.
LinuxcncStatus moveAndCheck(LinuxcncCommander& cnc, const Eigen::VectorXd& command);

/// LinuxCNC as the rig: moves by MDI, the gauges from HAL pins, each reading the mean of
/// `samples` reads (zeroed in software: the readings at zeroGauges are subtracted). Cancellation
/// is checked before each move.
class LinuxcncGaugeRig final : public simulation::ConstrainedMotionRig {
 public:
  LinuxcncGaugeRig(LinuxcncCommander& cnc,
                   std::array<std::string, 3> pins,
                   double settle_s,
                   int samples,
                   const workflow::RunControl& control);
  kinematics::StrutVector moveTo(const Eigen::VectorXd& command) override;
  void zeroGauges() override;
  Eigen::Vector3d readGauges() override;

 private:
  Eigen::Vector3d raw();
  LinuxcncCommander& cnc_;
  std::array<std::string, 3> pins_;
  double settle_s_;
  int samples_;
  const workflow::RunControl& control_;
  Eigen::Vector3d tare_ = Eigen::Vector3d::Zero();
};

/// The error of an x move of `length` centred on `reference` (mm, rad) as a laser on HAL pin `pin`
/// reads it: (reading at the end − at the start) − length, mm, both ends approached from −x (the
/// start from 5 mm before it).
[[nodiscard]] double laserXError(LinuxcncCommander& cnc,
                                 const std::string& pin,
                                 const Eigen::VectorXd& reference,
                                 double length,
                                 double settle_s,
                                 const workflow::RunControl& control);

/// Gives the running pkmhexkins the geometry of `machine`: machine off (LinuxCNC must be idle),
/// `pkmhexkins.hold` set, every `pkmhexkins.*` geometry pin set, hold released (the geometry is
/// checked and taken as one), machine on; then checks that pkmhexkins took it
/// (geometry-ok, no fault) and that LinuxCNC's pose is the calibrated forward kinematics of its
/// joints. The struts do not move: only the pose LinuxCNC computes from them changes. Throws
/// pkm::IoError saying what failed.
void applyPkmhexkinsGeometry(LinuxcncCommander& cnc, const io::HexapodMachine& machine);

}  // namespace pkm::live::detail
