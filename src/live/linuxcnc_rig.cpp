// The running LinuxCNC as a constrained-motion rig (linuxcnc_rig.hpp).
#include "linuxcnc_rig.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::live::detail {
namespace {

/// LinuxCNC's pose and the calibrated FK of its joints agree within this, mm and degrees.
constexpr double kAppliedTolerance = 1e-6;
/// After a move LinuxCNC's commanded pose is the command within this, mm and degrees (the MDI
/// line's 9 decimals).
constexpr double kArrivedTolerance = 1e-6;
/// The laser run approaches its start from this far before it, mm.
constexpr double kLaserOvershootMm = 5.0;

void settle(double seconds) { std::this_thread::sleep_for(std::chrono::duration<double>(seconds)); }

double halValue(LinuxcncCommander& cnc, const std::string& pin) {
  return cnc.halValues({pin}).at(0);
}

}  // namespace

LinuxcncStatus moveAndCheck(LinuxcncCommander& cnc, const Eigen::VectorXd& command) {
  const LinuxcncStatus st = cnc.mdi(moveLine(command));
  const std::array<double, 6> want{command[0],
                                   command[1],
                                   command[2],
                                   radToDeg(command[3]),
                                   radToDeg(command[4]),
                                   radToDeg(command[5])};
  for (std::size_t k = 0; k < 6; ++k)
    if (!(std::abs(st.pose_commanded[k] - want[k]) <= kArrivedTolerance))
      throw IoError(
          fmt::format("LinuxCNC: after the move to {} = {:.6f} it commands {} = {:.6f}: stopped",
                      "XYZABC"[k],
                      want[k],
                      "XYZABC"[k],
                      st.pose_commanded[k]));
  return st;
}

std::string moveLine(const Eigen::VectorXd& c) {
  return fmt::format("G53 G0 X{:.9f} Y{:.9f} Z{:.9f} A{:.9f} B{:.9f} C{:.9f}",
                     c[0],
                     c[1],
                     c[2],
                     radToDeg(c[3]),
                     radToDeg(c[4]),
                     radToDeg(c[5]));
}

LinuxcncGaugeRig::LinuxcncGaugeRig(LinuxcncCommander& cnc,
                                   std::array<std::string, 3> pins,
                                   double settle_s,
                                   int samples,
                                   const workflow::RunControl& control)
    : cnc_(cnc),
      pins_(std::move(pins)),
      settle_s_(settle_s),
      samples_(samples),
      control_(control) {}

kinematics::StrutVector LinuxcncGaugeRig::moveTo(const Eigen::VectorXd& command) {
  control_.checkCancelled();
  const LinuxcncStatus st = moveAndCheck(cnc_, command);
  if (st.joint_commanded.size() != kinematics::kStruts)
    throw IoError(
        fmt::format("LinuxCNC reports {} joints, a hexapod has 6", st.joint_commanded.size()));
  kinematics::StrutVector q;
  for (int i = 0; i < kinematics::kStruts; ++i)
    q[i] = st.joint_commanded[static_cast<std::size_t>(i)];
  return q;
}

Eigen::Vector3d LinuxcncGaugeRig::raw() {
  settle(settle_s_);
  const std::vector<double> v = cnc_.halValues({pins_[0], pins_[1], pins_[2]}, samples_);
  return {v[0], v[1], v[2]};
}

void LinuxcncGaugeRig::zeroGauges() { tare_ = raw(); }

Eigen::Vector3d LinuxcncGaugeRig::readGauges() { return raw() - tare_; }

double laserXError(LinuxcncCommander& cnc,
                   const std::string& pin,
                   const Eigen::VectorXd& reference,
                   double length,
                   double settle_s,
                   const workflow::RunControl& control) {
  Eigen::VectorXd start = reference, end = reference;
  start[0] -= length / 2;
  end[0] += length / 2;
  Eigen::VectorXd before = start;
  before[0] -= kLaserOvershootMm;
  for (const Eigen::VectorXd* c : {&before, &start}) {
    control.checkCancelled();
    (void)moveAndCheck(cnc, *c);
  }
  settle(settle_s);
  const double at_start = halValue(cnc, pin);
  control.checkCancelled();
  (void)moveAndCheck(cnc, end);
  settle(settle_s);
  return (halValue(cnc, pin) - at_start) - length;
}

void applyPkmhexkinsGeometry(LinuxcncCommander& cnc, const io::HexapodMachine& machine) {
  if (const std::string why = motionRefusal(cnc.status()); !why.empty())
    throw IoError("LinuxCNC: the calibration cannot be applied: " + why);
  std::vector<std::pair<std::string, std::string>> pins;
  std::istringstream lines(io::writePkmhexkinsSetp(machine));
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string setp, pin, value;
    if (words >> setp >> pin >> value && setp == "setp") pins.emplace_back(pin, value);
  }
  (void)cnc.machineOn(false);  // the struts hold still; nothing moves while the pins change
  // On hold, so that pkmhexkins checks and takes the new geometry as one, never a mix.
  cnc.setPin("pkmhexkins.hold", "1");
  for (const auto& [pin, value] : pins) cnc.setPin(pin, value);
  cnc.setPin("pkmhexkins.hold", "0");
  LinuxcncStatus st = cnc.machineOn(true);
  settle(0.2);
  st = cnc.status();
  const std::vector<double> flags = cnc.halValues({"pkmhexkins.geometry-ok", "pkmhexkins.fault"});
  if (flags[0] != 1.0 || flags[1] != 0.0)
    throw IoError("LinuxCNC: pkmhexkins refused the calibrated geometry (see LinuxCNC's log)");
  kinematics::HexapodData data(machine.model);
  kinematics::StrutVector q;
  for (int i = 0; i < kinematics::kStruts; ++i)
    q[i] = st.joint_actual.at(static_cast<std::size_t>(i));
  const kinematics::PoseRpy seed{
      Eigen::Vector3d(st.pose_actual[0], st.pose_actual[1], st.pose_actual[2]),
      Eigen::Vector3d(
          degToRad(st.pose_actual[3]), degToRad(st.pose_actual[4]), degToRad(st.pose_actual[5]))};
  if (!kinematics::forwardKinematics(machine.model, data, q, seed, machine.fk).ok())
    throw IoError("LinuxCNC: the calibrated forward kinematics of its joints does not converge");
  const std::array<double, 6> want{data.pose.position.x(),
                                   data.pose.position.y(),
                                   data.pose.position.z(),
                                   radToDeg(data.pose.rpy.x()),
                                   radToDeg(data.pose.rpy.y()),
                                   radToDeg(data.pose.rpy.z())};
  for (std::size_t k = 0; k < 6; ++k)
    if (std::abs(want[k] - st.pose_actual[k]) > kAppliedTolerance)
      throw IoError(fmt::format(
          "LinuxCNC: after the calibrated geometry was set, its pose {} is {}, the calibrated "
          "machine's {}: the geometry was not taken",
          "XYZABC"[k],
          st.pose_actual[k],
          want[k]));
}

}  // namespace pkm::live::detail
