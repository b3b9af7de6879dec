// A running LinuxCNC's status checked on its machine (pkm/live/live_view.hpp).
#include "pkm/live/live_view.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "pkm/core/units.hpp"
#include "pkm/io/linuxcnc_patch.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/named_text.hpp"

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
  const io::NamedText text = io::readNamedText(ini);
  const io::NamedText hal = io::genhexkinsHalFile(text);
  LiveMachine m;
  m.ini = ini;
  m.hal = hal.name;
  m.name = std::filesystem::path(hal.name).filename().string();
  io::HalReadOptions options;
  options.ini_path = ini;
  m.machine = io::loadHexapodMachine(m.hal, options);
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
