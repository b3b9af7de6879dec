// One line of the LinuxCNC reader, parsed and checked (pkm/live/linuxcnc_status.hpp).
#include "pkm/live/linuxcnc_status.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "pkm/core/error.hpp"

namespace pkm::live {
namespace {

using Json = nlohmann::json;

[[noreturn]] void fail(const std::string& message) { throw IoError("reader line: " + message); }

const Json& field(const Json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end()) fail(fmt::format("no \"{}\"", key));
  return *it;
}

double number(const Json& j, const char* key) {
  const Json& v = field(j, key);
  if (!v.is_number()) fail(fmt::format("\"{}\" is not a number", key));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(fmt::format("\"{}\" is not finite", key));
  return d;
}

long long integer(const Json& j, const char* key) {
  const Json& v = field(j, key);
  if (!v.is_number_integer()) fail(fmt::format("\"{}\" is not an integer", key));
  return v.get<long long>();
}

int smallInt(const Json& j, const char* key) {
  const long long v = integer(j, key);
  if (v < -1'000'000'000LL || v > 1'000'000'000LL) fail(fmt::format("\"{}\" out of range", key));
  return static_cast<int>(v);
}

bool flag(const Json& j, const char* key) {
  const Json& v = field(j, key);
  if (!v.is_boolean()) fail(fmt::format("\"{}\" is not true or false", key));
  return v.get<bool>();
}

std::string text(const Json& j, const char* key) {
  const Json& v = field(j, key);
  if (!v.is_string()) fail(fmt::format("\"{}\" is not a string", key));
  return v.get<std::string>();
}

std::vector<double> numbers(const Json& j, const char* key, std::size_t count) {
  const Json& v = field(j, key);
  if (!v.is_array() || v.size() != count)
    fail(fmt::format("\"{}\" is not an array of {} numbers", key, count));
  std::vector<double> out;
  for (std::size_t i = 0; i < count; ++i) {
    if (!v[i].is_number())
      fail(fmt::format(
          "\"{}\"[{}] is not a finite number (LinuxCNC reported NaN or infinity)", key, i));
    out.push_back(v[i].get<double>());
  }
  return out;
}

template <std::size_t N>
std::array<double, N> fixed(const Json& j, const char* key) {
  const std::vector<double> v = numbers(j, key, N);
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = v[i];
  return out;
}

template <typename E>
E enumerated(const Json& j, const char* key, int lo, int hi) {
  const int v = smallInt(j, key);
  if (v < lo || v > hi) fail(fmt::format("\"{}\" {} is not one of {}..{}", key, v, lo, hi));
  return static_cast<E>(v);
}

LinuxcncStatus parseStatus(const Json& j) {
  LinuxcncStatus s;
  s.sequence = integer(j, "seq");
  s.time = number(j, "t");
  s.ini = text(j, "ini");
  s.kinematics_type = smallInt(j, "kinematics_type");
  s.linear_units = number(j, "linear_units");
  const long long joints = integer(j, "joints");
  if (joints < 1 || joints > 16) fail(fmt::format("\"joints\" {} is not 1..16", joints));
  const auto n = static_cast<std::size_t>(joints);
  s.joint_actual = numbers(j, "joint_actual", n);
  s.joint_commanded = numbers(j, "joint_commanded", n);
  s.pose_commanded = fixed<6>(j, "pose_commanded");
  s.pose_actual = fixed<6>(j, "pose_actual");
  s.estop = flag(j, "estop");
  s.enabled = flag(j, "enabled");
  const Json& homed = field(j, "homed");
  if (!homed.is_array() || homed.size() != n) fail("\"homed\" is not one flag per joint");
  for (const Json& h : homed) {
    if (!h.is_boolean()) fail("\"homed\" is not one flag per joint");
    s.homed.push_back(h.get<bool>());
  }
  s.task_mode = enumerated<TaskMode>(j, "task_mode", 1, 3);
  s.task_state = enumerated<TaskState>(j, "task_state", 1, 4);
  s.exec_state = smallInt(j, "exec_state");
  s.interp_state = enumerated<InterpState>(j, "interp_state", 1, 4);
  s.paused = flag(j, "paused");
  s.in_position = flag(j, "inpos");
  s.file = text(j, "file");
  s.current_line = smallInt(j, "current_line");
  s.motion_line = smallInt(j, "motion_line");
  s.read_line = smallInt(j, "read_line");
  s.tool = smallInt(j, "tool");
  s.tool_offset = fixed<3>(j, "tool_offset");
  s.g5x_index = smallInt(j, "g5x_index");
  s.g5x_offset = fixed<6>(j, "g5x_offset");
  s.g92_offset = fixed<6>(j, "g92_offset");
  s.velocity = number(j, "velocity");
  return s;
}

}  // namespace

bool LinuxcncStatus::allHomed() const {
  if (homed.empty()) return false;
  for (const bool h : homed)
    if (!h) return false;
  return true;
}

bool LinuxcncStatus::busy() const { return interp_state != InterpState::kIdle; }

bool LinuxcncStatus::readyToMove() const {
  return !estop && enabled && task_state == TaskState::kOn && allHomed() && !busy();
}

std::string motionRefusal(const LinuxcncStatus& s) {
  if (s.estop || s.task_state == TaskState::kEstop) return "LinuxCNC is in E-stop";
  if (!s.enabled || s.task_state != TaskState::kOn) return "the machine is off";
  if (!s.allHomed()) return "not every joint is homed";
  if (s.busy()) return "LinuxCNC is running a program or command";
  return "";
}

ReaderLine parseReaderLine(std::string_view line) {
  const Json j = Json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object())
    fail(fmt::format("not a JSON object: '{}'", line.substr(0, 200)));
  ReaderLine out;
  if (j.contains("fatal")) {
    out.kind = ReaderLine::Kind::kFatal;
    out.message = text(j, "fatal");
  } else if (j.contains("error")) {
    out.kind = ReaderLine::Kind::kError;
    out.message = text(j, "error");
  } else {
    out.kind = ReaderLine::Kind::kStatus;
    out.status = parseStatus(j);
  }
  return out;
}

}  // namespace pkm::live
