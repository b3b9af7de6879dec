/// @file
/// @brief The state of a running LinuxCNC as its status channel reports it (docs/linuxcnc.md,
/// "The live machine"): one record of the reader that LinuxcncLink runs, parsed and checked.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace pkm::live {

/// LinuxCNC's task states (its `linuxcnc.STATE_*` values).
enum class TaskState { kEstop = 1, kEstopReset = 2, kOff = 3, kOn = 4 };
/// LinuxCNC's task modes (`linuxcnc.MODE_*`).
enum class TaskMode { kManual = 1, kAuto = 2, kMdi = 3 };
/// LinuxCNC's interpreter states (`linuxcnc.INTERP_*`).
enum class InterpState { kIdle = 1, kReading = 2, kPaused = 3, kWaiting = 4 };

/// One status record. Lengths in the machine's linear unit (the INI's [TRAJ] LINEAR_UNITS),
/// angles in degrees, as LinuxCNC reports them; poses are x, y, z, a, b, c in machine
/// coordinates (no work offsets applied).
struct LinuxcncStatus {
  long long sequence = 0;                  ///< the reader's record number, 1, 2, ...
  double time = 0.0;                       ///< the reader's monotonic clock, s
  std::string ini;                         ///< the INI LinuxCNC was started with (absolute path)
  int kinematics_type = 0;                 ///< 1 identity, 2 forward only, 3 inverse only, 4 both
  double linear_units = 1.0;               ///< machine units per mm (1 for mm, 1/25.4 for inch)
  std::vector<double> joint_actual;        ///< joint feedback positions (strut lengths)
  std::vector<double> joint_commanded;     ///< joint commanded positions
  std::array<double, 6> pose_commanded{};  ///< the trajectory planner's commanded pose
  std::array<double, 6> pose_actual{};     ///< the pose forward kinematics gives of the feedback
  bool estop = true;                       ///< emergency stop active
  bool enabled = false;                    ///< machine on
  std::vector<bool> homed;                 ///< per joint
  TaskMode task_mode = TaskMode::kManual;
  TaskState task_state = TaskState::kEstop;
  int exec_state = 0;  ///< LinuxCNC's `EXEC_*` value (1 error, 2 done, 3.. waiting)
  InterpState interp_state = InterpState::kIdle;
  bool paused = false;
  bool in_position = false;  ///< motion has reached its commanded position
  std::string file;          ///< the loaded program ("" when none)
  /// The interpreter's current line (LinuxCNC's `current_line`; the interpreter reads ahead of
  /// the motion, so this is usually past the executing line).
  int current_line = 0;
  int motion_line = 0;                  ///< the program line of the motion executing now (0: none)
  int read_line = 0;                    ///< the line the interpreter has read up to
  int tool = 0;                         ///< tool in the spindle (0: none)
  std::array<double, 3> tool_offset{};  ///< x, y, z of the active tool length offset
  int g5x_index = 1;                    ///< 1 = G54 ... 9 = G59.3
  std::array<double, 6> g5x_offset{};   ///< the active work offset
  std::array<double, 6> g92_offset{};
  double velocity = 0.0;  ///< current tool speed, machine unit / s

  /// Every joint homed (and at least one joint).
  [[nodiscard]] bool allHomed() const;
  /// A program or MDI command is executing (interpreter not idle).
  [[nodiscard]] bool busy() const;
  /// LinuxCNC may be commanded to move: out of E-stop, on, homed and idle.
  [[nodiscard]] bool readyToMove() const;
};

/// What one line of the reader says.
struct ReaderLine {
  enum class Kind { kStatus, kError, kFatal };
  Kind kind = Kind::kError;
  LinuxcncStatus status;  ///< when kind is kStatus
  std::string message;    ///< when kind is kError (LinuxCNC not running) or kFatal (reader ended)
};

/// Parses one JSON line of the reader (src/live/linuxcnc_bridge.py). A status record must carry
/// every field with its type and 1..16 joints; a joint or pose value that is null (LinuxCNC
/// reported a non-finite number) is an error. Throws pkm::IoError "reader line: message" for
/// malformed lines.
[[nodiscard]] ReaderLine parseReaderLine(std::string_view line);

/// Why LinuxCNC must not be sent motion in state `s` ("" when it may: readyToMove): "LinuxCNC is
/// in E-stop", "the machine is off", "not every joint is homed" or "LinuxCNC is running a program
/// or command".
[[nodiscard]] std::string motionRefusal(const LinuxcncStatus& s);

}  // namespace pkm::live
