// The reader process and the thread that keeps its latest record (pkm/live/linuxcnc_link.hpp).
#include "pkm/live/linuxcnc_link.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <string_view>
#include <thread>
#include <utility>

#include "child_process.hpp"
#include "pkm/core/error.hpp"

namespace pkm::io::detail {
const std::vector<std::pair<std::string_view, std::string_view>>& embeddedLiveReader();
}  // namespace pkm::io::detail

namespace pkm::live {

using Clock = std::chrono::steady_clock;

/// The longest line the reader may write; longer ones are refused, not buffered without bound.
constexpr std::size_t kMaxLine = 1u << 16;

struct LinuxcncLink::State {
  LinkOptions options;
  detail::ChildProcess child;  // the reader (its input closed: it ends)
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
    pollfd p{child.from_child, POLLIN, 0};
    const int ready = ::poll(&p, 1, 100);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t got = ::read(child.from_child, buffer, sizeof buffer);
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

}  // namespace

LinuxcncLink::LinuxcncLink(LinkOptions options) : state_(std::make_shared<State>()) {
  options.validate();
  state_->options = std::move(options);
  state_->child = detail::startChild(readerCommand(state_->options), "LinuxCNC reader");
  state_->thread = std::thread([s = state_] { s->readLoop(); });
}

LinuxcncLink::~LinuxcncLink() {
  State& s = *state_;
  detail::stopChild(s.child, std::chrono::milliseconds(1000));
  s.stop = true;
  s.thread.join();
  ::close(s.child.from_child);
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
