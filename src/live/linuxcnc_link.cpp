// The reader process and the thread that keeps its latest record (pkm/live/linuxcnc_link.hpp).
#include "pkm/live/linuxcnc_link.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <string_view>
#include <thread>
#include <utility>

#include "pkm/core/error.hpp"

extern char** environ;

namespace pkm::io::detail {
const std::vector<std::pair<std::string_view, std::string_view>>& embeddedLiveReader();
}  // namespace pkm::io::detail

namespace pkm::live {

using Clock = std::chrono::steady_clock;

/// The longest line the reader may write; longer ones are refused, not buffered without bound.
constexpr std::size_t kMaxLine = 1u << 16;

struct LinuxcncLink::State {
  LinkOptions options;
  pid_t pid = -1;
  int to_child = -1;    // the reader's standard input (closed: the reader ends)
  int from_child = -1;  // its standard output and error
  std::atomic<bool> stop{false};
  std::thread thread;
  mutable std::mutex mutex;
  mutable std::condition_variable arrived;
  std::optional<LinuxcncStatus> status;
  Clock::time_point received{};
  std::string reason = "waiting for the first record from LinuxCNC";
  bool ended = false;
  long long records = 0;

  void take(std::string_view line);
  void readLoop();
};

void LinkOptions::validate() const {
  if (!(rate_hz >= 1.0 && rate_hz <= 200.0))
    throw InvalidArgument(fmt::format("live rate {} Hz is not within 1..200", rate_hz));
  if (!(stale_after_s > 0.0) || !std::isfinite(stale_after_s))
    throw InvalidArgument("live stale time must be a positive number of seconds");
  if (command.empty() && python.empty()) throw InvalidArgument("no Python to run the reader with");
}

const std::string& readerProgram() {
  static const std::string program = [] {
    for (const auto& [name, text] : io::detail::embeddedLiveReader())
      if (name == "linuxcnc_bridge") return std::string(text);
    return std::string();
  }();
  return program;
}

void LinuxcncLink::State::take(std::string_view line) {
  std::lock_guard lock(mutex);
  try {
    ReaderLine r = parseReaderLine(line);
    if (r.kind == ReaderLine::Kind::kStatus) {
      status = std::move(r.status);
      received = Clock::now();
      reason.clear();
      ++records;
    } else {
      reason = r.message;
      if (r.kind == ReaderLine::Kind::kFatal) ended = true;
    }
  } catch (const IoError& e) {
    reason = e.what();
  }
  arrived.notify_all();
}

void LinuxcncLink::State::readLoop() {
  std::string pending;
  char buffer[4096];
  while (!stop.load()) {
    pollfd p{from_child, POLLIN, 0};
    const int ready = ::poll(&p, 1, 100);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t got = ::read(from_child, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    pending.append(buffer, static_cast<std::size_t>(got));
    std::size_t start = 0;
    for (std::size_t nl; (nl = pending.find('\n', start)) != std::string::npos; start = nl + 1)
      take(std::string_view(pending).substr(start, nl - start));
    pending.erase(0, start);
    if (pending.size() > kMaxLine) {
      take("{\"error\": \"the reader wrote a line longer than 64 KiB\"}");
      pending.clear();
    }
  }
  std::lock_guard lock(mutex);
  if (!stop.load() && !ended) reason = "the LinuxCNC reader ended unexpectedly";
  ended = true;
  arrived.notify_all();
}

namespace {

/// The reader's command line.
std::vector<std::string> readerCommand(const LinkOptions& o) {
  if (!o.command.empty()) return o.command;
  return {o.python, "-u", "-c", readerProgram(), fmt::format("{:.6f}", 1.0 / o.rate_hz)};
}

/// Starts `argv` with its standard input reading `in` and its output and error writing `out`.
pid_t spawn(const std::vector<std::string>& args, int in, int out) {
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
    throw IoError(
        fmt::format("cannot start the LinuxCNC reader {}: {}", args[0], std::strerror(rc)));
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

LinuxcncLink::LinuxcncLink(LinkOptions options) : state_(std::make_shared<State>()) {
  options.validate();
  state_->options = std::move(options);
  int in[2], out[2];
  if (::pipe2(in, O_CLOEXEC) != 0) throw IoError("cannot make a pipe for the LinuxCNC reader");
  if (::pipe2(out, O_CLOEXEC) != 0) {
    ::close(in[0]);
    ::close(in[1]);
    throw IoError("cannot make a pipe for the LinuxCNC reader");
  }
  try {
    state_->pid = spawn(readerCommand(state_->options), in[0], out[1]);
  } catch (...) {
    for (const int fd : {in[0], in[1], out[0], out[1]}) ::close(fd);
    throw;
  }
  ::close(in[0]);
  ::close(out[1]);
  state_->to_child = in[1];
  state_->from_child = out[0];
  state_->thread = std::thread([s = state_] { s->readLoop(); });
}

LinuxcncLink::~LinuxcncLink() {
  State& s = *state_;
  ::close(s.to_child);  // the reader sees its input end and exits
  if (!reaped(s.pid, std::chrono::milliseconds(1000))) {
    ::kill(s.pid, SIGTERM);
    if (!reaped(s.pid, std::chrono::milliseconds(1000))) {
      ::kill(s.pid, SIGKILL);
      ::waitpid(s.pid, nullptr, 0);
    }
  }
  s.stop = true;
  s.thread.join();
  ::close(s.from_child);
}

LinkSnapshot LinuxcncLink::snapshot() const {
  const State& s = *state_;
  std::lock_guard lock(s.mutex);
  LinkSnapshot out;
  out.status = s.status;
  out.records = s.records;
  out.reason = s.reason;
  if (s.status) {
    out.age_s = std::chrono::duration<double>(Clock::now() - s.received).count();
    if (out.reason.empty() && out.age_s > s.options.stale_after_s)
      out.reason = fmt::format("no record from LinuxCNC for {:.1f} s", out.age_s);
  }
  if (s.ended && out.reason.empty()) out.reason = "the LinuxCNC reader ended";
  out.connected = out.reason.empty() && s.status.has_value();
  return out;
}

LinkSnapshot LinuxcncLink::waitForRecord(long long after, std::chrono::milliseconds timeout) const {
  {
    const State& s = *state_;
    std::unique_lock lock(s.mutex);
    s.arrived.wait_for(
        lock, timeout, [&] { return s.ended || (s.status && s.status->sequence > after); });
  }
  return snapshot();
}

}  // namespace pkm::live
