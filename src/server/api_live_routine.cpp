// Api::runLiveCalibration (pkm/server/api.hpp): an admitted calibration by constrained motion run
// with its event stream (docs/web.md, "The automated calibration"). A heartbeat thread writes to
// the stream every options.heartbeat_s; when a write fails (the page closed, the network dropped)
// the routine is stopped and LinuxCNC's motion aborted at once, not at the routine's next step.
#include <fmt/format.h>

#include <chrono>
#include <thread>

#include "api_state.hpp"
#include "pkm/core/error.hpp"

namespace pkm::server {
namespace {

using detail::finiteOrNull;
using detail::Json;

std::string routineEvent(const char* name, const Json& data) {
  return fmt::format("event: {}\ndata: {}\n\n", name, data.dump());
}

Json optionalNumber(const std::optional<double>& v) { return v ? finiteOrNull(*v) : Json(nullptr); }

/// What the page shows of a result, so far or final.
Json resultJson(const LiveRoutine& routine, const live::LiveCalibrationResult& r) {
  return {{"id", routine.id},
          {"ini", routine.request.ini},
          {"stations", r.plan.fit.size()},
          {"held_out", r.plan.holdout.size()},
          {"identifiable", r.plan.identifiable},
          {"holdout_rms_before", finiteOrNull(r.holdout_rms_before)},
          {"holdout_rms_after", finiteOrNull(r.holdout_rms_after)},
          {"laser_error_before", optionalNumber(r.laser_error_before)},
          {"laser_error_after", optionalNumber(r.laser_error_after)},
          {"installed", r.install.has_value() && r.install->written},
          {"backups", r.install ? Json(r.install->backups) : Json::array()},
          {"applied", r.applied},
          {"commands", r.log.size()},
          {"seconds", r.seconds},
          {"report", live::liveCalibrationText(routine.request, r)}};
}

/// The stream's writer: serialised between the routine and the heartbeat; the first failed write
/// stops the routine.
class Stream {
 public:
  Stream(LiveRoutine& routine, const std::function<bool(const std::string&)>& write)
      : routine_(routine), write_(write) {}

  void send(const std::string& chunk) {
    const std::lock_guard lock(mutex_);
    if (!connected_) return;
    if (!write_(chunk)) {
      connected_ = false;
      routine_.stop();  // the page is gone: nobody can watch or stop the machine
    }
  }

 private:
  LiveRoutine& routine_;
  const std::function<bool(const std::string&)>& write_;
  std::mutex mutex_;
  bool connected_ = true;
};

/// Writes a heartbeat every `period` until destroyed.
class Heartbeat {
 public:
  Heartbeat(Stream& stream, double period_s)
      : thread_([this, &stream, period_s] {
          std::unique_lock lock(mutex_);
          const auto period = std::chrono::duration<double>(period_s);
          while (!done_) {
            if (done_changed_.wait_for(lock, period, [this] { return done_; })) break;
            lock.unlock();
            stream.send(": heartbeat\n\n");
            lock.lock();
          }
        }) {}
  ~Heartbeat() {
    {
      const std::lock_guard lock(mutex_);
      done_ = true;
    }
    done_changed_.notify_all();
    thread_.join();
  }
  Heartbeat(const Heartbeat&) = delete;
  Heartbeat& operator=(const Heartbeat&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable done_changed_;
  bool done_ = false;
  std::thread thread_;  // last: started once the rest exists
};

/// The confirmation: the result so far to the page, then the page's answer (or cancellation).
live::ConfirmInstall askPage(LiveRoutine& routine, Stream& stream) {
  return [&routine, &stream](const live::LiveCalibrationResult& so_far) {
    {
      const std::lock_guard lock(routine.mutex);
      routine.answer = LiveRoutine::Answer::kAsked;
      routine.stage = "waiting for the answer: install?";
    }
    stream.send(routineEvent("confirm", resultJson(routine, so_far)));
    std::unique_lock lock(routine.mutex);
    routine.changed.wait(lock, [&routine] {
      return routine.cancel.cancelled() || routine.answer == LiveRoutine::Answer::kInstall ||
             routine.answer == LiveRoutine::Answer::kKeep;
    });
    routine.cancel.check();
    return routine.answer == LiveRoutine::Answer::kInstall;
  };
}

}  // namespace

void Api::stopLiveCalibration(LiveCalibrationJob& job) {
  if (job.routine) job.routine->stop();
}

void Api::runLiveCalibration(LiveCalibrationJob& job,
                             const std::function<bool(const std::string&)>& write) {
  State& s = *state_;
  LiveRoutine& routine = *job.routine;
  Stream stream(routine, write);
  workflow::RunControl control;
  control.cancel = &routine.cancel;
  control.progress = [&](const workflow::ProgressEvent& e) {
    {
      const std::lock_guard lock(routine.mutex);
      routine.stage = e.message;
    }
    stream.send(routineEvent("progress",
                             {{"stage", e.stage},
                              {"index", e.index},
                              {"count", e.count},
                              {"elapsed", e.elapsed},
                              {"message", s.clean(e.message)}}));
  };
  stream.send(routineEvent("started", {{"id", routine.id}, {"ini", routine.request.ini}}));
  try {
    const Heartbeat heartbeat(stream, s.options.heartbeat_s);
    const live::LiveCalibrationResult r =
        live::calibrateLive(routine.request, *routine.cnc, control, askPage(routine, stream));
    stream.send(routineEvent("result", resultJson(routine, r)));
  } catch (const std::exception& e) {
    // An abort from the page (cancel, a dropped connection) reaches the routine as LinuxCNC's
    // "aborted" error or as Cancelled: both are the cancellation the user asked for.
    if (routine.cancel.cancelled())
      stream.send(routineEvent("cancelled", {{"id", routine.id}, {"message", s.clean(e.what())}}));
    else
      stream.send(routineEvent("error", {{"error", s.clean(e.what())}}));
  }
  std::unique_ptr<live::LinuxcncCommander> cnc;
  {
    const std::lock_guard lock(routine.mutex);  // stop() may be aborting through it
    cnc = std::move(routine.cnc);
  }
  cnc.reset();  // its end aborts any motion it started
  const std::lock_guard lock(s.mutex);
  if (s.routine == job.routine) s.routine.reset();
}

}  // namespace pkm::server
