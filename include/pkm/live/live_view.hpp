/// @file
/// @brief What a front end draws of a running LinuxCNC (docs/linuxcnc.md, "The live machine"):
/// the machine the configuration defines, and every status record checked on it by pkm
/// (strut readings, stroke and cone margins, closest pair, condition number).
#pragma once

#include <optional>
#include <string>

#include "pkm/io/hexapod_machine.hpp"
#include "pkm/live/linuxcnc_link.hpp"
#include "pkm/workflow/pose_checks.hpp"

namespace pkm::live {

/// The machine a LinuxCNC configuration computes with, as files pkm reads.
struct LiveMachine {
  std::string ini;   ///< the configuration's INI
  std::string hal;   ///< the file its geometry is read from: genhexkins HAL or pkmhexkins params
  std::string name;  ///< the machine's name for display (the HAL file's)
  io::HexapodMachine machine;  ///< the machine, read once (the HAL file with the INI)
  /// "mm" or "inch": the machine's unit ([TRAJ] LINEAR_UNITS).
  [[nodiscard]] std::string units() const;
};

/// The machine of the configuration `ini`, read once (io::readLinuxcncHexapod): pkmhexkins'
/// parameter file, or the HAL file among its [HAL] HALFILE entries that sets genhexkins pins, with
/// the INI. Throws pkm::IoError naming the INI when it has neither, or naming the file and line of
/// a malformed entry.
[[nodiscard]] LiveMachine liveMachine(const std::string& ini);

/// One status record checked on the machine.
struct LiveFrame {
  LinkSnapshot link;  ///< connection state and the record
  /// Where the machine is: the record's actual pose (LinuxCNC's forward kinematics of its joint
  /// feedback) checked by workflow::checkPoses (machine unit, degrees); empty without a record.
  /// The actual pose and joints of one record belong together; the commanded pose and joints do
  /// not while the machine moves (LinuxCNC samples them apart: 1e-2 in seen at 0.5 in/s).
  std::optional<workflow::PoseCheckRow> pose_check;
  /// The largest difference between LinuxCNC's joint feedback and pkm's inverse kinematics of the
  /// actual pose, machine unit (NaN without a record or a solution): what LinuxCNC computes with
  /// against what pkm draws.
  double joint_disagreement = 0.0;
  /// The state in one word for a status line: "disconnected", "estop", "off", "not homed",
  /// "running", "paused", "idle".
  std::string state;
};

/// The state of `snapshot` in one word (LiveFrame::state).
[[nodiscard]] std::string liveState(const LinkSnapshot& snapshot);

/// `snapshot` checked on `machine` (no file is read).
[[nodiscard]] LiveFrame liveFrame(const LinkSnapshot& snapshot, const LiveMachine& machine);

}  // namespace pkm::live
