// A helper program of pkm::live run with pipes on its standard streams (the LinuxCNC reader and
// commander, src/live/linuxcnc_bridge.py): start, and stop by closing its input, then SIGTERM,
// then SIGKILL. Internal to src/live.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>
#include <vector>

namespace pkm::live::detail {

/// A started child: its pid, the write end of its standard input and the read end of its output
/// and error.
struct ChildProcess {
  pid_t pid = -1;
  int to_child = -1;
  int from_child = -1;
};

/// Starts `args` (args[0] an absolute path). `what` names it in messages. Throws pkm::IoError when
/// the pipes cannot be made or the program cannot be started.
[[nodiscard]] ChildProcess startChild(const std::vector<std::string>& args,
                                      const std::string& what);

/// Writes all of `bytes` to the child's input; false when the child has closed it (EPIPE). A
/// SIGPIPE this raises is blocked in this thread and consumed, so an ended child cannot end pkm.
[[nodiscard]] bool writeToChild(const ChildProcess& child, const std::string& bytes);

/// Closes the child's input and waits `grace` for it to end, then SIGTERM and another `grace`,
/// then SIGKILL; reaps it. Leaves from_child open (a reading thread may still use it).
void stopChild(ChildProcess& child, std::chrono::milliseconds grace);

}  // namespace pkm::live::detail
