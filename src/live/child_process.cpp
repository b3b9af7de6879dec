// A helper program with pipes on its standard streams (child_process.hpp).
#include "child_process.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <thread>

#include "pkm/core/error.hpp"

extern char** environ;

namespace pkm::live::detail {
namespace {

using Clock = std::chrono::steady_clock;

/// Starts `args` with its standard input reading `in` and its output and error writing `out`.
pid_t spawn(const std::vector<std::string>& args, int in, int out, const std::string& what) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in, 0);
  posix_spawn_file_actions_adddup2(&actions, out, 1);
  posix_spawn_file_actions_adddup2(&actions, out, 2);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0)
    throw IoError(fmt::format("cannot start the {} {}: {}", what, args[0], std::strerror(rc)));
  return pid;
}

/// Waits up to `limit` for `pid` to end.
bool reaped(pid_t pid, std::chrono::milliseconds limit) {
  const auto until = Clock::now() + limit;
  do {
    if (::waitpid(pid, nullptr, WNOHANG) == pid) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  } while (Clock::now() < until);
  return false;
}

}  // namespace

ChildProcess startChild(const std::vector<std::string>& args, const std::string& what) {
  if (args.empty()) throw IoError(fmt::format("no program to run as the {}", what));
  int in[2], out[2];
  if (::pipe2(in, O_CLOEXEC) != 0)
    throw IoError(fmt::format("cannot make a pipe for the {}", what));
  if (::pipe2(out, O_CLOEXEC) != 0) {
    ::close(in[0]);
    ::close(in[1]);
    throw IoError(fmt::format("cannot make a pipe for the {}", what));
  }
  ChildProcess child;
  try {
    child.pid = spawn(args, in[0], out[1], what);
  } catch (...) {
    for (const int fd : {in[0], in[1], out[0], out[1]}) ::close(fd);
    throw;
  }
  ::close(in[0]);
  ::close(out[1]);
  child.to_child = in[1];
  child.from_child = out[0];
  return child;
}

bool writeToChild(const ChildProcess& child, const std::string& bytes) {
  sigset_t pipe_signal, pending, old;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  sigpending(&pending);
  const bool was_pending = sigismember(&pending, SIGPIPE) == 1;
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &old);
  bool ok = true;
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(child.to_child, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ok = false;
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  if (!ok && !was_pending) {  // consume the SIGPIPE this write raised
    sigpending(&pending);
    if (sigismember(&pending, SIGPIPE) == 1) {
      const timespec now{0, 0};
      (void)sigtimedwait(&pipe_signal, nullptr, &now);
    }
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return ok;
}

void stopChild(ChildProcess& child, std::chrono::milliseconds grace) {
  if (child.to_child >= 0) ::close(child.to_child);  // the child sees its input end and exits
  child.to_child = -1;
  if (child.pid <= 0) return;
  if (!reaped(child.pid, grace)) {
    ::kill(child.pid, SIGTERM);
    if (!reaped(child.pid, grace)) {
      ::kill(child.pid, SIGKILL);
      ::waitpid(child.pid, nullptr, 0);
    }
  }
  child.pid = -1;
}

}  // namespace pkm::live::detail
