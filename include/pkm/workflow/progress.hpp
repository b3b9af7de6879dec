/// @file
/// @brief Progress reports and cancellation for long workflows (campaigns, Monte Carlo, pose
/// planning, large G-code runs). A workflow never prints: it calls the front end's Progress
/// callback, which the CLI turns into its progress lines and a server into its own events.
#pragma once

#include <atomic>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pkm::workflow {

/// One progress report.
struct ProgressEvent {
  std::string stage;      ///< what is running, e.g. a campaign step's id ("" for the whole job)
  std::size_t index = 0;  ///< 1-based number of the stage (0 when the job has no stages)
  std::size_t count = 0;  ///< number of stages (0 when unknown)
  double elapsed = 0.0;   ///< seconds since the job started
  std::string message;    ///< one line, no newline
};

/// Receives progress reports; called on the workflow's own thread, in order. May be empty.
using Progress = std::function<void(const ProgressEvent&)>;

/// Thrown by a workflow that saw its CancellationToken set. Files written before are complete
/// (every output is published atomically); the result is lost.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

/// Set by a front end (another thread, a signal handler) to stop a running workflow at its next
/// check point. Lock-free; a token may be reused after reset().
class CancellationToken {
 public:
  void cancel() noexcept { cancelled_.store(true, std::memory_order_relaxed); }
  void reset() noexcept { cancelled_.store(false, std::memory_order_relaxed); }
  [[nodiscard]] bool cancelled() const noexcept {
    return cancelled_.load(std::memory_order_relaxed);
  }
  /// Throws Cancelled when cancel() was called.
  void check() const {
    if (cancelled()) throw Cancelled();
  }

 private:
  std::atomic<bool> cancelled_{false};
};

/// Receives a notice: something the user should know about the input (a value the reader
/// assumed, metadata it ignored, what a file held), one line without a prefix. May be empty.
using Notice = std::function<void(const std::string&)>;

/// What every workflow takes besides its request: where to report and what to watch.
struct RunControl {
  Progress progress;                          ///< may be empty
  Notice notice;                              ///< may be empty
  const CancellationToken* cancel = nullptr;  ///< may be null: never cancelled
  /// Reports `event` when there is a callback.
  void report(const ProgressEvent& event) const {
    if (progress) progress(event);
  }
  /// Passes each of `notices` on, in order, when there is a callback.
  void note(const std::vector<std::string>& notices) const {
    if (notice)
      for (const std::string& n : notices) notice(n);
  }
  /// Throws Cancelled when the token is set.
  void checkCancelled() const {
    if (cancel != nullptr) cancel->check();
  }
};

}  // namespace pkm::workflow
