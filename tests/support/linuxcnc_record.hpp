// A status record as LinuxCNC's reader writes it (src/live/linuxcnc_bridge.py), for the tests of
// pkm::live and the server's live routes: a homed, idle hexapod at `pose` with `joints`.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pkm::test {

/// A complete, valid record; tests change fields of it and dump() it.
inline nlohmann::json linuxcncRecord(long long seq,
                                     const std::array<double, 6>& pose = {0, 0, 20, 0, 0, 0},
                                     const std::vector<double>& joints = {1, 2, 3, 4, 5, 6},
                                     const std::string& ini = "/nowhere/hexapod.ini") {
  const std::vector<bool> homed(joints.size(), true);
  return {{"seq", seq},
          {"t", 100.0 + 0.04 * static_cast<double>(seq)},
          {"ini", ini},
          {"kinematics_type", 4},
          {"linear_units", 1.0 / 25.4},
          {"joints", joints.size()},
          {"joint_actual", joints},
          {"joint_commanded", joints},
          {"pose_commanded", pose},
          {"pose_actual", pose},
          {"estop", false},
          {"enabled", true},
          {"homed", homed},
          {"task_mode", 3},
          {"task_state", 4},
          {"exec_state", 2},
          {"interp_state", 1},
          {"paused", false},
          {"inpos", true},
          {"file", ""},
          {"current_line", 0},
          {"motion_line", 0},
          {"read_line", 0},
          {"tool", 0},
          {"tool_offset", {0, 0, 0}},
          {"g5x_index", 1},
          {"g5x_offset", {0, 0, 0, 0, 0, 0}},
          {"g92_offset", {0, 0, 0, 0, 0, 0}},
          {"velocity", 0.0}};
}

}  // namespace pkm::test
