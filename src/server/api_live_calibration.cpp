// POST /api/live/calibration (server-sent events), GET /api/live/calibration and POST
// /api/live/calibration/{cancel,confirm} (docs/web.md, "The automated calibration"): Lee et al.'s
// calibration by constrained motion (live::calibrateLive) run by the server on the followed
// LinuxCNC. Safety: the token on every route that commands; an explicit "confirm"; LinuxCNC
// checked ready before anything moves; one routine at a time; a heartbeat that stops the machine
// when the page's connection drops; install only on the page's answer.
#include <fmt/format.h>

#include "api_state.hpp"
#include "pkm/core/error.hpp"

namespace pkm::server {

void LiveRoutine::stop() {
  cancel.cancel();
  const std::lock_guard lock(mutex);
  if (cnc) cnc->abort();
  changed.notify_all();
}

}  // namespace pkm::server

namespace pkm::server::detail {
namespace {

/// The three gauge pins of the request ("gauges": three HAL pin names).
std::array<std::string, 3> gaugePins(const Json& body) {
  const auto it = body.find("gauges");
  if (it == body.end() || !it->is_array() || it->size() != 3)
    throw HttpError(400, "\"gauges\" must list the three gauges' HAL pins");
  std::array<std::string, 3> pins;
  for (std::size_t k = 0; k < 3; ++k) {
    if (!(*it)[k].is_string() || (*it)[k].get<std::string>().empty())
      throw HttpError(400, "\"gauges\" must list the three gauges' HAL pins");
    pins[k] = (*it)[k].get<std::string>();
  }
  return pins;
}

/// The routine's request from the page's JSON (the names of `pkm calibrate hexapod --live`'s
/// options, docs/web.md); the INI is the followed LinuxCNC's, the output folder the server's.
live::LiveCalibrationRequest routineRequest(Api::State& s, const Json& body, int id) {
  const auto confirm = body.find("confirm");
  if (confirm == body.end() || !confirm->is_boolean() || !confirm->get<bool>())
    throw HttpError(400,
                    "a routine that moves the machine needs \"confirm\": true (the page asks "
                    "before it sends this)");
  live::LiveCalibrationRequest r;
  r.gauges = gaugePins(body);
  r.laser = stringField(body, "laser", "");
  if (const auto v = countField(body, "stations", 400)) r.stations.count = static_cast<int>(*v);
  if (const auto v = countField(body, "holdout_stations", 100))
    r.stations.holdout = static_cast<int>(*v);
  if (const auto v = numberField(body, "reach")) r.stations.reach = *v;
  if (const auto v = numberField(body, "approach")) r.approach = *v;
  if (const auto v = numberField(body, "tolerance")) r.tolerance = *v;
  if (const auto v = numberField(body, "settle")) r.settle_s = *v;
  if (const auto v = countField(body, "gauge_samples", 1000))
    r.gauge_samples = static_cast<int>(*v);
  if (const auto v = numberField(body, "laser_length")) r.laser_length = *v;
  r.ini = followedIni(s);
  r.out = (s.dir / fmt::format("live-calibration-{}", id)).string();
  try {
    r.validate();
  } catch (const InvalidArgument& e) {
    throw HttpError(400, e.what());
  }
  return r;
}

/// Starts the commander and refuses (409) unless LinuxCNC may move now.
void startCommander(Api::State& s, LiveRoutine& routine) {
  try {
    routine.cnc = std::make_unique<live::LinuxcncCommander>(s.options.commander);
    const std::string why = live::motionRefusal(routine.cnc->status());
    if (!why.empty())
      throw HttpError(409, fmt::format("LinuxCNC cannot be moved: {}; nothing was sent", why));
  } catch (const IoError& e) {
    throw HttpError(409, e.what());
  }
}

std::shared_ptr<LiveRoutine> runningRoutine(Api::State& s) {
  const std::lock_guard lock(s.mutex);
  if (!s.routine) throw HttpError(404, "no calibration is running");
  return s.routine;
}

}  // namespace

void prepareLiveCalibration(Api::State& s, const Request& r, LiveCalibrationJob& job) {
  requireCommandToken(r, s);
  const Json body = parseObject(r);
  auto routine = std::make_shared<LiveRoutine>();
  {
    const std::lock_guard lock(s.mutex);
    if (s.routine)
      throw HttpError(409,
                      fmt::format("calibration {} is running already: cancel it first (POST "
                                  "/api/live/calibration/cancel)",
                                  s.routine->id));
    routine->id = s.next_routine++;
    s.routine = routine;  // holds the place while the commander starts
  }
  try {
    routine->request = routineRequest(s, body, routine->id);
    startCommander(s, *routine);
  } catch (...) {
    const std::lock_guard lock(s.mutex);
    s.routine.reset();
    throw;
  }
  job.routine = std::move(routine);
}

Response liveCalibrationState(Api::State& s) {
  std::shared_ptr<LiveRoutine> routine;
  {
    const std::lock_guard lock(s.mutex);
    routine = s.routine;
  }
  if (!routine) return json({{"running", false}});
  const std::lock_guard lock(routine->mutex);
  return json({{"running", true},
               {"id", routine->id},
               {"stage", routine->stage},
               {"asking", routine->answer == LiveRoutine::Answer::kAsked}});
}

Response cancelLiveCalibration(Api::State& s, const Request& r) {
  requireCommandToken(r, s);
  const std::shared_ptr<LiveRoutine> routine = runningRoutine(s);
  routine->stop();
  return json({{"id", routine->id}, {"cancelled", true}});
}

Response confirmLiveCalibration(Api::State& s, const Request& r) {
  requireCommandToken(r, s);
  const Json body = parseObject(r);
  const auto install = body.find("install");
  if (install == body.end() || !install->is_boolean())
    throw HttpError(400, "\"install\" must be true or false");
  const std::shared_ptr<LiveRoutine> routine = runningRoutine(s);
  {
    const std::lock_guard lock(routine->mutex);
    if (routine->answer != LiveRoutine::Answer::kAsked)
      throw HttpError(409, "the calibration is not asking now");
    routine->answer =
        install->get<bool>() ? LiveRoutine::Answer::kInstall : LiveRoutine::Answer::kKeep;
  }
  routine->changed.notify_all();
  return json({{"id", routine->id}, {"install", install->get<bool>()}});
}

}  // namespace pkm::server::detail
