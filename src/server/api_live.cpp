// GET /api/live, POST /api/live/connect and /api/live/disconnect (docs/web.md): the LinuxCNC
// running on this host, followed read-only through live::LinuxcncLink and checked on its machine.
#include <fmt/format.h>

#include "api_state.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/hexapod_machine.hpp"

namespace pkm::server::detail {
namespace {

const char* modeName(live::TaskMode m) {
  switch (m) {
    case live::TaskMode::kManual:
      return "manual";
    case live::TaskMode::kAuto:
      return "auto";
    case live::TaskMode::kMdi:
      return "mdi";
  }
  return "manual";
}

const char* interpName(live::InterpState i) {
  switch (i) {
    case live::InterpState::kIdle:
      return "idle";
    case live::InterpState::kReading:
      return "reading";
    case live::InterpState::kPaused:
      return "paused";
    case live::InterpState::kWaiting:
      return "waiting";
  }
  return "idle";
}

template <typename Range>
Json numbers(const Range& values) {
  Json out = Json::array();
  for (const double v : values) out.push_back(finiteOrNull(v));
  return out;
}

Json statusJson(const live::LinuxcncStatus& st) {
  Json homed = Json::array();
  for (const bool h : st.homed) homed.push_back(h);
  return {{"sequence", st.sequence},
          {"ini", st.ini},
          {"joints_actual", numbers(st.joint_actual)},
          {"joints_commanded", numbers(st.joint_commanded)},
          {"pose_commanded", numbers(st.pose_commanded)},
          {"pose_actual", numbers(st.pose_actual)},
          {"estop", st.estop},
          {"enabled", st.enabled},
          {"homed", homed},
          {"mode", modeName(st.task_mode)},
          {"interpreter", interpName(st.interp_state)},
          {"paused", st.paused},
          {"in_position", st.in_position},
          {"file", st.file},
          {"executing_line", st.motion_line},
          {"interpreter_line", st.current_line},
          {"read_line", st.read_line},
          {"tool", st.tool},
          {"tool_offset", numbers(st.tool_offset)},
          {"g5x_index", st.g5x_index},
          {"g5x_offset", numbers(st.g5x_offset)},
          {"g92_offset", numbers(st.g92_offset)},
          {"velocity", st.velocity}};
}

/// The followed machine, read once per INI; `error` says why there is none.
std::shared_ptr<const live::LiveMachine> machineOf(Api::State& s,
                                                   const live::LinkSnapshot& snap,
                                                   std::string& error) {
  const std::string ini = !s.options.linuxcnc_ini.empty() ? s.options.linuxcnc_ini
                          : snap.status                   ? snap.status->ini
                                                          : std::string();
  if (ini.empty()) return nullptr;
  std::lock_guard lock(s.live_mutex);
  if (s.live_machine_ini != ini) {
    s.live_machine_ini = ini;
    s.live_machine.reset();
    s.live_machine_error.clear();
    try {
      s.live_machine = std::make_shared<const live::LiveMachine>(live::liveMachine(ini));
    } catch (const IoError& e) {
      s.live_machine_error = e.what();
    }
  }
  error = s.live_machine_error;
  return s.live_machine;
}

}  // namespace

std::string followedIni(Api::State& s) {
  std::shared_ptr<live::LinuxcncLink> link;
  {
    std::lock_guard lock(s.live_mutex);
    link = s.link;
  }
  if (!link)
    throw HttpError(409, "not following LinuxCNC: press Connect, or start `pkm serve --linuxcnc`");
  if (!s.options.linuxcnc_ini.empty()) return s.options.linuxcnc_ini;
  const live::LinkSnapshot snap = link->snapshot();
  if (!snap.status || snap.status->ini.empty())
    throw HttpError(409,
                    fmt::format("LinuxCNC does not answer ({}): start it, then try again",
                                snap.reason.empty() ? "no status yet" : snap.reason));
  return snap.status->ini;
}

Response liveProgram(Api::State& s) {
  std::shared_ptr<live::LinuxcncLink> link;
  {
    std::lock_guard lock(s.live_mutex);
    link = s.link;
  }
  const live::LinkSnapshot snap = link ? link->snapshot() : live::LinkSnapshot{};
  if (!snap.status || snap.status->file.empty())
    throw HttpError(404, "LinuxCNC has no program loaded (or is not followed)");
  // The path is LinuxCNC's, not the request's: the program it runs, read as a program file.
  const std::string& file = snap.status->file;
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) throw HttpError(404, fmt::format("{}: LinuxCNC's program cannot be read here", file));
  if (size > s.options.max_body)
    throw HttpError(
        413, fmt::format("{}: {} bytes, above the limit of {}", file, size, s.options.max_body));
  return json({{"file", file}, {"text", io::readTextFile(file, s.options.max_body)}});
}

Response liveConnect(Api::State& s) {
  {
    std::lock_guard lock(s.live_mutex);
    if (!s.link) s.link = std::make_shared<live::LinuxcncLink>(s.options.live);
  }
  return liveStatus(s);
}

Response liveDisconnect(Api::State& s) {
  std::shared_ptr<live::LinuxcncLink> link;
  {
    std::lock_guard lock(s.live_mutex);
    link.swap(s.link);
  }
  link.reset();  // stops the reader (outside the lock: it may take a second)
  return json({{"following", false}});
}

Response liveStatus(Api::State& s) {
  std::shared_ptr<live::LinuxcncLink> link;
  {
    std::lock_guard lock(s.live_mutex);
    link = s.link;
  }
  if (!link)
    return json(
        {{"following", false},
         {"connected", false},
         {"state", "disconnected"},
         {"reason", "not following LinuxCNC: press Connect, or start `pkm serve --linuxcnc`"}});
  const live::LinkSnapshot snap = link->snapshot();
  std::string machine_error;
  const std::shared_ptr<const live::LiveMachine> machine = machineOf(s, snap, machine_error);
  Json out = {{"following", true},
              {"connected", snap.connected},
              {"reason", snap.reason},
              {"records", snap.records},
              {"age_s", snap.age_s}};
  if (machine)
    out["machine"] = {{"name", machine->name},
                      {"ini", machine->ini},
                      {"hal", machine->hal},
                      {"units", machine->units()}};
  else if (!machine_error.empty())
    out["machine_error"] = machine_error;
  live::LiveFrame frame;
  if (machine) {
    try {
      frame = live::liveFrame(snap, *machine);
    } catch (const std::exception& e) {
      out["machine_error"] = e.what();
      frame.link = snap;
    }
  }
  out["state"] = live::liveState(snap);
  if (snap.status) out["status"] = statusJson(*snap.status);
  if (frame.pose_check) {
    out["check"] = poseRowJson(*frame.pose_check);
    out["joint_disagreement"] = finiteOrNull(frame.joint_disagreement);
  }
  return json(out);
}

}  // namespace pkm::server::detail
