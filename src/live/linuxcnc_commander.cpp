// The command channel to a running LinuxCNC (pkm/live/linuxcnc_commander.hpp).
#include "pkm/live/linuxcnc_commander.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <mutex>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "pkm/core/error.hpp"
#include "pkm/live/linuxcnc_link.hpp"

namespace pkm::live {

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

/// The longest answer line; a longer one ends the channel instead of growing without bound.
constexpr std::size_t kMaxAnswer = 1u << 16;
/// How much longer than a move an answer may take (LinuxCNC's mode changes, the abort).
constexpr double kAnswerMarginS = 30.0;

/// A message of the commander, said to come from LinuxCNC once.
std::string fromLinuxcnc(const std::string& text) {
  return text.starts_with("LinuxCNC") ? text : "LinuxCNC: " + text;
}

}  // namespace

struct LinuxcncCommander::State {
  CommanderOptions options;
  detail::ChildProcess child;
  std::mutex write_mutex;  // abort() may write from another thread
  mutable std::mutex log_mutex;
  std::vector<std::string> log;
  std::string pending;  // bytes read after the last answer line
  long long next_id = 1;

  void send(const Json& request);
  std::string readLine(Clock::time_point until);
  Json ask(Json request);
  std::string lastWords();
};

void CommanderOptions::validate() const {
  if (!(move_timeout_s > 0.0) || !std::isfinite(move_timeout_s))
    throw InvalidArgument("the move timeout must be a positive number of seconds");
  if (command.empty() && python.empty()) throw InvalidArgument("no Python to run the commander");
}

void LinuxcncCommander::State::send(const Json& request) {
  const std::string line = request.dump();
  {
    std::lock_guard lock(log_mutex);
    log.push_back(line);
  }
  if (options.on_sent) options.on_sent(line);
  std::lock_guard lock(write_mutex);
  if (!detail::writeToChild(child, line + "\n"))
    throw IoError("LinuxCNC: the commander has ended (its input is closed)");
}

std::string LinuxcncCommander::State::readLine(Clock::time_point until) {
  char buffer[4096];
  while (true) {
    if (const std::size_t nl = pending.find('\n'); nl != std::string::npos) {
      std::string line = pending.substr(0, nl);
      pending.erase(0, nl + 1);
      return line;
    }
    if (pending.size() > kMaxAnswer)
      throw IoError("LinuxCNC: the commander wrote a line over 64 KiB");
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
    if (left.count() <= 0) throw IoError("LinuxCNC: no answer from the commander in time");
    pollfd p{child.from_child, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t got = ::read(child.from_child, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) throw IoError("LinuxCNC: the commander ended unexpectedly");
    pending.append(buffer, static_cast<std::size_t>(got));
  }
}

std::string LinuxcncCommander::State::lastWords() {
  const auto until = Clock::now() + std::chrono::milliseconds(500);
  try {
    while (true) {
      const Json j = Json::parse(readLine(until), nullptr, /*allow_exceptions=*/false);
      if (j.is_object() && j.contains("fatal") && j["fatal"].is_string()) return j["fatal"];
    }
  } catch (const IoError&) {  // its output ended or took too long
  }
  return "";
}

Json LinuxcncCommander::State::ask(Json request) {
  const long long id = next_id++;
  request["id"] = id;
  try {
    send(request);
  } catch (const IoError&) {  // it has ended: say why when it said so before it went
    if (const std::string why = lastWords(); !why.empty()) throw IoError(fromLinuxcnc(why));
    throw;
  }
  const auto until =
      Clock::now() + std::chrono::duration<double>(options.move_timeout_s + kAnswerMarginS);
  while (true) {
    const std::string line = readLine(std::chrono::time_point_cast<Clock::duration>(until));
    if (!line.starts_with("{")) continue;  // a message of LinuxCNC's module, not an answer
    const Json j = Json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded() || !j.is_object())
      throw IoError(fmt::format("LinuxCNC: the commander wrote '{}'", line.substr(0, 200)));
    if (j.contains("fatal")) throw IoError(fromLinuxcnc(j["fatal"].get<std::string>()));
    if (!j.contains("id") || !j["id"].is_number_integer() || j["id"].get<long long>() != id)
      continue;  // the answer to an abort sent between requests
    if (!j.value("ok", false))
      throw IoError(fromLinuxcnc(j.value("error", std::string("the request failed"))));
    return j;
  }
}

namespace {

LinuxcncStatus statusOf(const Json& answer) {
  if (!answer.contains("status")) throw IoError("LinuxCNC: the commander's answer has no status");
  Json record = answer["status"];
  record["seq"] = 1;
  ReaderLine r = parseReaderLine(record.dump());
  if (r.kind != ReaderLine::Kind::kStatus) throw IoError("LinuxCNC: " + r.message);
  return r.status;
}

}  // namespace

LinuxcncCommander::LinuxcncCommander(CommanderOptions options) : state_(std::make_shared<State>()) {
  options.validate();
  state_->options = std::move(options);
  std::vector<std::string> args = state_->options.command;
  if (args.empty()) args = {state_->options.python, "-u", "-c", readerProgram(), "command"};
  state_->child = detail::startChild(args, "LinuxCNC commander");
  try {
    (void)status();
  } catch (...) {
    detail::stopChild(state_->child, std::chrono::milliseconds(1000));
    ::close(state_->child.from_child);
    throw;
  }
}

LinuxcncCommander::~LinuxcncCommander() {
  // The commander aborts its motion when its input ends; give it time to tell LinuxCNC.
  detail::stopChild(state_->child, std::chrono::milliseconds(3000));
  ::close(state_->child.from_child);
}

LinuxcncStatus LinuxcncCommander::status() { return statusOf(state_->ask({{"op", "status"}})); }

LinuxcncStatus LinuxcncCommander::mdi(const std::string& line) {
  if (line.find_first_of("\r\n") != std::string::npos)
    throw InvalidArgument("an MDI command is one line");
  return statusOf(
      state_->ask({{"op", "mdi"}, {"line", line}, {"timeout", state_->options.move_timeout_s}}));
}

std::vector<double> LinuxcncCommander::halValues(const std::vector<std::string>& pins,
                                                 int samples,
                                                 double interval_s) {
  Json request = {{"op", "hal_get"}, {"pins", pins}};
  if (samples > 1) request.update({{"samples", samples}, {"interval", interval_s}});
  const Json answer = state_->ask(request);
  std::vector<double> out;
  for (const Json& v : answer.value("values", Json::array())) {
    if (v.is_boolean())
      out.push_back(v.get<bool>() ? 1.0 : 0.0);
    else if (v.is_number())
      out.push_back(v.get<double>());
    else
      throw IoError("LinuxCNC: a HAL value that is not a number");
  }
  if (out.size() != pins.size()) throw IoError("LinuxCNC: the HAL answer has the wrong count");
  return out;
}

void LinuxcncCommander::setPin(const std::string& pin, const std::string& value) {
  (void)state_->ask({{"op", "hal_set"}, {"pin", pin}, {"value", value}});
}

LinuxcncStatus LinuxcncCommander::machineOn(bool on) {
  return statusOf(state_->ask({{"op", "machine"}, {"on", on}}));
}

void LinuxcncCommander::abort() { state_->send({{"op", "abort"}, {"id", 0}}); }

std::vector<std::string> LinuxcncCommander::log() const {
  std::lock_guard lock(state_->log_mutex);
  return state_->log;
}

}  // namespace pkm::live
