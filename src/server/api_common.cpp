// Helpers shared by the API's routes (api_state.hpp).
#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <regex>

#include "api_state.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/linuxcnc_samples.hpp"
#include "pkm/io/machine_loader.hpp"

namespace pkm::server {

detail::MachineSpec Api::State::resolveMachine(const std::string& name) {
  for (const char* type : {"hexapod", "exechon"})
    for (const std::string& b : io::builtinMachineNames(type))
      if (b == name) return {name, ""};
  for (const io::LinuxcncSample& sample : io::installedLinuxcncSamples(options.sample_root))
    if (sample.name == name) return {sample.hal.string(), sample.ini.string()};
  if (name == detail::kLiveMachine) {
    const std::lock_guard lock(live_mutex);
    if (live_machine) return {live_machine->hal, live_machine->ini};
    throw detail::HttpError(400,
                            "no LinuxCNC machine: follow a running LinuxCNC first (Connect, or "
                            "`pkm serve --linuxcnc`)");
  }
  const std::lock_guard lock(mutex);
  for (const detail::Upload& u : uploads)
    if (u.name == name) return {u.path.string(), u.ini.string()};
  throw detail::HttpError(400,
                          fmt::format("unknown machine '{}': GET /api/machines lists the machines, "
                                      "POST /api/machines uploads one",
                                      name));
}

std::string Api::State::clean(std::string message) const {
  const std::string prefix = dir.string() + "/";
  for (std::size_t at = message.find(prefix); at != std::string::npos; at = message.find(prefix))
    message.erase(at, prefix.size());
  return message;
}

}  // namespace pkm::server

namespace pkm::server::detail {

JobSlot::JobSlot(Api::State& state,
                 const std::string& name,
                 const workflow::CancellationToken* cancel)
    : state_(state) {
  std::unique_lock lock(state_.jobs_mutex);
  if (state_.jobs_running < state_.options.max_jobs && state_.job_queue.empty()) {
    ++state_.jobs_running;
    return;
  }
  if (state_.job_queue.size() >= state_.options.max_queued)
    throw HttpError(503,
                    fmt::format("{} jobs are running and {} waiting, the most this server holds; "
                                "try again in a few seconds",
                                state_.jobs_running,
                                state_.job_queue.size()));
  const auto mine = state_.job_queue.insert(state_.job_queue.end(), name);
  state_.jobs_changed.wait(lock, [&] {
    return (cancel != nullptr && cancel->cancelled()) ||
           (state_.job_queue.begin() == mine && state_.jobs_running < state_.options.max_jobs);
  });
  state_.job_queue.erase(mine);
  if (cancel != nullptr && cancel->cancelled()) {
    state_.jobs_changed.notify_all();  // the next in the queue may be first now
    throw workflow::Cancelled();
  }
  ++state_.jobs_running;
  state_.jobs_changed.notify_all();  // another slot may be free for the next
}

JobSlot::~JobSlot() {
  {
    const std::lock_guard lock(state_.jobs_mutex);
    --state_.jobs_running;
  }
  state_.jobs_changed.notify_all();
}

Response listJobs(Api::State& s) {
  const std::lock_guard lock(s.jobs_mutex);
  Json queued = Json::array();
  for (const std::string& name : s.job_queue) queued.push_back(name);
  return json({{"running", s.jobs_running},
               {"queued", queued},
               {"max_jobs", s.options.max_jobs},
               {"max_queued", s.options.max_queued}});
}

NamedJob::NamedJob(Api::State& state, const std::string& name) : state_(state), name_(name) {
  if (name_.empty()) return;
  if (name_.size() > 64 || safeName(name_) != name_)
    throw HttpError(400, "\"job\" must be a plain name (letters, digits, '.', '-', '_')");
  const std::lock_guard lock(state_.mutex);
  if (!state_.running.emplace(name_, &token_).second)
    throw HttpError(409, fmt::format("a job named '{}' is running already", name_));
}

NamedJob::~NamedJob() {
  if (name_.empty()) return;
  const std::lock_guard lock(state_.mutex);
  state_.running.erase(name_);
}

workflow::RunControl NamedJob::control() const {
  workflow::RunControl c;
  c.cancel = &token_;
  return c;
}

Response cancelJob(Api::State& s, const std::string& name) {
  const std::lock_guard lock(s.mutex);
  const auto it = s.running.find(name);
  if (it == s.running.end())
    throw HttpError(404, fmt::format("no job named '{}' is running", name));
  it->second->cancel();
  s.jobs_changed.notify_all();  // it may be waiting in the queue
  return json({{"job", name}, {"cancelled", true}});
}

Json parseObject(const Request& request) {
  Json j = Json::parse(request.body, nullptr, false);
  if (j.is_discarded()) throw HttpError(400, "the request body is not valid JSON");
  if (!j.is_object()) throw HttpError(400, "the request body must be a JSON object");
  return j;
}

std::string stringField(const Json& j, const char* key, const std::string& fallback) {
  if (!j.contains(key) || j[key].is_null()) return fallback;
  if (!j[key].is_string()) throw HttpError(400, fmt::format("\"{}\" must be a string", key));
  return j[key].get<std::string>();
}

std::string requiredString(const Json& j, const char* key) {
  if (!j.contains(key)) throw HttpError(400, fmt::format("\"{}\" is missing", key));
  return stringField(j, key, "");
}

std::optional<double> numberField(const Json& j, const char* key) {
  if (!j.contains(key) || j[key].is_null()) return std::nullopt;
  if (!j[key].is_number() || !std::isfinite(j[key].get<double>()))
    throw HttpError(400, fmt::format("\"{}\" must be a finite number", key));
  return j[key].get<double>();
}

std::optional<std::size_t> countField(const Json& j, const char* key, std::size_t max) {
  const std::optional<double> v = numberField(j, key);
  if (!v) return std::nullopt;
  if (*v < 0 || *v > static_cast<double>(max) || std::floor(*v) != *v)
    throw HttpError(400, fmt::format("\"{}\" must be a whole number from 0 to {}", key, max));
  return static_cast<std::size_t>(*v);
}

std::string safeName(const std::string& name) {
  std::string out;
  for (char c : name.substr(
           name.find_last_of("/\\") == std::string::npos ? 0 : name.find_last_of("/\\") + 1)) {
    if (out.size() >= 64) break;
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_';
    out += ok ? c : '_';
  }
  while (!out.empty() && out.front() == '.') out.erase(0, 1);
  return out.empty() ? "upload" : out;
}

Response json(const Json& j, int status) {
  return {status, "application/json", j.dump() + "\n", "", "", ""};
}

Response error(int status, const std::string& message) {
  Json j{{"error", message}};
  static const std::regex located(R"(^([^:\n]+):(\d+):)");
  std::smatch m;
  if (std::regex_search(message, m, located)) {
    j["name"] = m[1].str();
    j["line"] = std::stoull(m[2].str());
  }
  return json(j, status);
}

}  // namespace pkm::server::detail
