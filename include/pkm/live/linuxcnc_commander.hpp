/// @file
/// @brief A command channel to the LinuxCNC running on this host (docs/linuxcnc.md, "Automated
/// calibration by constrained motion"): a child process sends MDI lines through LinuxCNC's own
/// `linuxcnc` Python module and reads and sets HAL pins; each request is answered before the next
/// is sent. Safety: the child refuses motion unless LinuxCNC is out of E-stop, on, homed and idle,
/// and aborts any motion it started when this object is destroyed, its process ends or abort() is
/// called. Every line sent is logged.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pkm/live/linuxcnc_status.hpp"

namespace pkm::live {

/// How the commander runs.
struct CommanderOptions {
  /// The Python that has LinuxCNC's module (Debian's, not the first python3 on PATH).
  std::string python = "/usr/bin/python3";
  /// The commander program and its arguments; empty: `python -u -c <embedded bridge> command`.
  /// Tests put a stand-in here.
  std::vector<std::string> command;
  double move_timeout_s = 120.0;  ///< longest MDI move; then it is aborted (> 0)
  /// Called with every line sent to LinuxCNC, as sent (the command log).
  std::function<void(const std::string&)> on_sent;
  /// Throws pkm::InvalidArgument for a non-positive timeout or no program.
  void validate() const;
};

/// The command channel. Thread-safe for abort() only (from another thread while a request waits);
/// the other calls come from one thread.
class LinuxcncCommander {
 public:
  /// Starts the commander; throws pkm::IoError when it cannot start or LinuxCNC does not answer
  /// (not running: the message says so).
  explicit LinuxcncCommander(CommanderOptions options = {});
  /// Closes the commander's input: it aborts any motion it started and ends.
  ~LinuxcncCommander();
  LinuxcncCommander(const LinuxcncCommander&) = delete;
  LinuxcncCommander& operator=(const LinuxcncCommander&) = delete;

  /// LinuxCNC's state now.
  [[nodiscard]] LinuxcncStatus status();
  /// Sends one MDI line and waits until its motion has ended; the state then. Throws
  /// pkm::IoError "LinuxCNC: refused: ..." when LinuxCNC is in E-stop, off, not homed or busy,
  /// and "LinuxCNC: ..." for LinuxCNC's own error, a move longer than the timeout or an abort.
  LinuxcncStatus mdi(const std::string& line);
  /// The values of HAL pins (float, bit as 0/1, integers), in order: each the mean of `samples`
  /// reads `interval_s` apart (a gauge interface's dither). Throws pkm::IoError naming a pin that
  /// does not exist.
  [[nodiscard]] std::vector<double> halValues(const std::vector<std::string>& pins,
                                              int samples = 1,
                                              double interval_s = 0.002);
  /// Sets an unconnected HAL input pin or a parameter (`halcmd setp`).
  void setPin(const std::string& pin, const std::string& value);
  /// Machine on or off (off is refused while it moves); the state then.
  LinuxcncStatus machineOn(bool on);
  /// Stops any motion now (LinuxCNC's abort); does not wait for the answer.
  void abort();
  /// Every line sent so far.
  [[nodiscard]] std::vector<std::string> log() const;

  struct State;  ///< the implementation's

 private:
  std::shared_ptr<State> state_;
};

}  // namespace pkm::live
