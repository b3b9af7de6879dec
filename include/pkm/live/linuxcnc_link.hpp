/// @file
/// @brief A read-only connection to the LinuxCNC running on this host (docs/linuxcnc.md, "The
/// live machine"): a child process polls LinuxCNC's status channel through its `linuxcnc` Python
/// module and streams the records; the link keeps the latest. It sends LinuxCNC no command.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pkm/live/linuxcnc_status.hpp"

namespace pkm::live {

/// How the link reads.
struct LinkOptions {
  /// The Python that has LinuxCNC's module (Debian's, not the first python3 on PATH).
  std::string python = "/usr/bin/python3";
  /// The reader program and its arguments; empty: `python -u -c <embedded reader> PERIOD`. Tests
  /// put a stand-in here.
  std::vector<std::string> command;
  double rate_hz = 25.0;  ///< status records per second, 1..200
  /// No record for this long and the link reports itself disconnected, s (> 0).
  double stale_after_s = 1.0;
  /// Throws pkm::InvalidArgument for a rate outside 1..200 Hz or a non-positive stale time.
  void validate() const;
};

/// What the link knows now.
struct LinkSnapshot {
  /// A status record younger than stale_after_s arrived and LinuxCNC's last answer was not an
  /// error.
  bool connected = false;
  /// Why not connected ("" when connected): the reader's error (LinuxCNC not running), its fatal
  /// message (no `linuxcnc` module), that it ended, or that records stopped arriving.
  std::string reason;
  std::optional<LinuxcncStatus> status;  ///< the latest record (also when no longer connected)
  double age_s = 0.0;                    ///< seconds since that record arrived
  long long records = 0;                 ///< records received since the link started
};

/// The connection. Starts its reader at construction and stops it (closing the reader's input,
/// then SIGTERM, then SIGKILL) at destruction. Thread-safe: snapshot() may be called from any
/// thread.
class LinuxcncLink {
 public:
  /// Starts the reader. Throws pkm::InvalidArgument as LinkOptions::validate and pkm::IoError
  /// when the reader cannot be started.
  explicit LinuxcncLink(LinkOptions options = {});
  ~LinuxcncLink();
  LinuxcncLink(const LinuxcncLink&) = delete;
  LinuxcncLink& operator=(const LinuxcncLink&) = delete;

  /// The latest state.
  [[nodiscard]] LinkSnapshot snapshot() const;

  /// Waits until a status record with sequence > `after` arrives, the reader ends, or `timeout`
  /// passes; returns snapshot().
  [[nodiscard]] LinkSnapshot waitForRecord(long long after,
                                           std::chrono::milliseconds timeout) const;

  struct State;  ///< the implementation's

 private:
  std::shared_ptr<State> state_;
};

/// The embedded reader program (src/live/linuxcnc_bridge.py).
[[nodiscard]] const std::string& readerProgram();

}  // namespace pkm::live
