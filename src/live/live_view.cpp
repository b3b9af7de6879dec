// A running LinuxCNC's status checked on its machine (pkm/live/live_view.hpp).
#include "pkm/live/live_view.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "pkm/core/units.hpp"
#include "pkm/io/linuxcnc_machine.hpp"

namespace pkm::live {

std::string liveState(const LinkSnapshot& s) {
  if (!s.connected || !s.status) return "disconnected";
  const LinuxcncStatus& st = *s.status;
  if (st.estop || st.task_state == TaskState::kEstop) return "estop";
  if (!st.enabled || st.task_state != TaskState::kOn) return "off";
  if (!st.allHomed()) return "not homed";
  if (st.paused || st.interp_state == InterpState::kPaused) return "paused";
  if (st.busy()) return "running";
  return "idle";
}

std::string LiveMachine::units() const { return std::string(toString(machine.model.unit)); }

LiveMachine liveMachine(const std::string& ini) {
  io::LinuxcncHexapod read = io::readLinuxcncHexapod(ini);
  LiveMachine m;
  m.ini = ini;
  m.hal = read.file;
  m.name = std::filesystem::path(read.file).filename().string();
  m.machine = std::move(read.machine);
  return m;
}

LiveFrame liveFrame(const LinkSnapshot& snapshot, const LiveMachine& machine) {
  LiveFrame f;
  f.link = snapshot;
  f.state = liveState(snapshot);
  if (!snapshot.status) {
    f.joint_disagreement = std::numeric_limits<double>::quiet_NaN();
    return f;
  }
  kinematics::HexapodData data(machine.machine.model);
  f.pose_check =
      workflow::checkHexapodPose(machine.machine.model, data, snapshot.status->pose_actual);
  const std::vector<double>& lcnc = snapshot.status->joint_actual;
  const std::vector<double>& pkm = f.pose_check->joints;
  if (pkm.size() != lcnc.size() || pkm.empty()) {
    f.joint_disagreement = std::numeric_limits<double>::quiet_NaN();
  } else {
    double d = 0.0;
    for (std::size_t i = 0; i < pkm.size(); ++i) d = std::max(d, std::abs(pkm[i] - lcnc[i]));
    f.joint_disagreement = d;
  }
  return f;
}

}  // namespace pkm::live
