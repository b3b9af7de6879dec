// The shared state and helpers of the API's route files (pkm/server/api.hpp): the server's own
// folder, the uploaded machines, the job slots, JSON field readers and error responses.
#pragma once

#include <atomic>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <list>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "pkm/live/live_calibration.hpp"
#include "pkm/live/live_view.hpp"
#include "pkm/server/api.hpp"
#include "pkm/workflow/pose_checks.hpp"

namespace pkm::server::detail {

using Json = nlohmann::ordered_json;

/// An answer other than 200, thrown by the routes.
class HttpError : public std::runtime_error {
 public:
  HttpError(int status, const std::string& message) : std::runtime_error(message), status(status) {}
  int status;
};

/// A machine the client uploaded, kept in the server's folder.
struct Upload {
  std::string name;            ///< the name requests use ("upload-3-kinematics")
  std::filesystem::path path;  ///< the machine file (.json or .hal)
  std::filesystem::path ini;   ///< its INI ("" : none)
  std::string type;            ///< "hexapod" or "exechon"
};

/// A machine as a workflow takes it: a built-in name or an uploaded file, and its INI.
struct MachineSpec {
  std::string spec;
  std::string ini;
};

}  // namespace pkm::server::detail

namespace pkm::server {

/// A calibration by constrained motion the server runs (api_live_calibration.cpp): one at a time.
struct LiveRoutine {
  /// What the page answered to "install?" (kAsked: the routine waits for it).
  enum class Answer { kNone, kAsked, kInstall, kKeep };
  int id = 0;
  live::LiveCalibrationRequest request;
  workflow::CancellationToken cancel;
  std::unique_ptr<live::LinuxcncCommander> cnc;  ///< set before the routine is admitted
  std::mutex mutex;                              ///< guards answer and stage
  std::condition_variable changed;               ///< answer given, or cancelled
  Answer answer = Answer::kNone;
  std::string stage;  ///< the last progress message
  /// Cancels the routine and aborts LinuxCNC's motion now (any thread).
  void stop();
};

struct Api::State {
  ServerOptions options;
  std::atomic<int> port{0};
  std::string token;                    ///< the per-launch secret ("" : none needed), Api::token()
  std::filesystem::path dir;            ///< the server's own folder (uploads, campaign outputs)
  std::mutex mutex;                     ///< guards uploads, campaigns and the counters
  std::vector<detail::Upload> uploads;  ///< oldest first
  std::map<int, std::filesystem::path> campaign_reports;
  /// The running jobs that a client named ("job" field), by name: POST /api/jobs/NAME/cancel.
  std::map<std::string, workflow::CancellationToken*> running;
  int next_upload = 1;
  int next_campaign = 1;
  std::mutex jobs_mutex;                     ///< guards the job counters and queue
  std::condition_variable jobs_changed;      ///< a slot freed, or a queued job was cancelled
  std::size_t jobs_running = 0;              ///< long jobs holding a slot
  std::list<std::string> job_queue;          ///< the waiting jobs' names, first served first
  std::mutex live_mutex;                     ///< guards link and the live machine's three fields
  std::shared_ptr<live::LinuxcncLink> link;  ///< the running LinuxCNC followed (null: none)
  /// Its machine, read once per INI (not copied per request), or why it could not be read
  /// (remembered too: a failing INI is not read again 20 times a second).
  std::shared_ptr<const live::LiveMachine> live_machine;
  std::string live_machine_ini;
  std::string live_machine_error;
  std::shared_ptr<LiveRoutine> routine;  ///< the calibration running (null: none), under mutex
  int next_routine = 1;

  /// A built-in machine name or an uploaded machine's name as a workflow spec. Throws HttpError
  /// 400 for anything else (a request never names a path).
  detail::MachineSpec resolveMachine(const std::string& name);
  /// `message` with the server's folder removed from the paths it names.
  [[nodiscard]] std::string clean(std::string message) const;
};

}  // namespace pkm::server

namespace pkm::server::detail {

/// A long job's slot, released on destruction: when max_jobs run already the job waits in a
/// queue (first come, first served; its place by `name`: GET /api/jobs) until one has finished.
/// Throws HttpError 503 (with Retry-After) when max_queued wait already, workflow::Cancelled when
/// `cancel` is cancelled while it waits.
class JobSlot {
 public:
  explicit JobSlot(Api::State& state,
                   const std::string& name = "",
                   const workflow::CancellationToken* cancel = nullptr);
  ~JobSlot();
  JobSlot(const JobSlot&) = delete;
  JobSlot& operator=(const JobSlot&) = delete;

 private:
  Api::State& state_;
};

/// GET /api/jobs: {"running", "queued": [names, first first], "max_jobs", "max_queued"}.
[[nodiscard]] Response listJobs(Api::State& s);

/// A job registered under the name a request gave it ("job"; none: not cancellable by name) for
/// as long as it runs. Throws HttpError 409 when a job of that name runs already, 400 for a name
/// that is not a short plain word.
class NamedJob {
 public:
  NamedJob(Api::State& state, const std::string& name);
  ~NamedJob();
  NamedJob(const NamedJob&) = delete;
  NamedJob& operator=(const NamedJob&) = delete;
  /// The job's control: its cancellation token.
  [[nodiscard]] workflow::RunControl control() const;
  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] const workflow::CancellationToken& token() const { return token_; }

 private:
  Api::State& state_;
  std::string name_;
  workflow::CancellationToken token_;
};

/// POST /api/jobs/NAME/cancel: cancels a running named job. Throws HttpError 404 when none runs.
[[nodiscard]] Response cancelJob(Api::State& s, const std::string& name);

/// The request body as a JSON object. Throws HttpError 400 for malformed JSON or another type.
[[nodiscard]] Json parseObject(const Request& request);
/// Field `key` of `j` as a string: the default when absent, HttpError 400 for another type.
[[nodiscard]] std::string stringField(const Json& j, const char* key, const std::string& fallback);
/// A required string field. Throws HttpError 400 when absent or not a string.
[[nodiscard]] std::string requiredString(const Json& j, const char* key);
/// An optional finite number. Throws HttpError 400 for another type or a non-finite value.
[[nodiscard]] std::optional<double> numberField(const Json& j, const char* key);
/// An optional count in [0, max]. Throws HttpError 400 otherwise.
[[nodiscard]] std::optional<std::size_t> countField(const Json& j,
                                                    const char* key,
                                                    std::size_t max);
/// A name an upload or program may carry: letters, digits, '.', '-', '_' (others become '_'),
/// at most 64 characters, never empty ("upload").
[[nodiscard]] std::string safeName(const std::string& name);
/// `v` as JSON, with +infinity (a disabled limit) and NaN (not evaluated) as null.
[[nodiscard]] inline Json finiteOrNull(double v) {
  return std::isfinite(v) ? Json(v) : Json(nullptr);
}
/// A JSON response.
[[nodiscard]] Response json(const Json& j, int status = 200);
/// An error response {"error": message} (with "name" and "line" when the message starts with
/// "NAME:LINE:").
[[nodiscard]] Response error(int status, const std::string& message);

/// How a request carried the server's token (api_token.cpp).
enum class TokenUse { kNotNeeded, kCookie, kQuery, kMissing, kWrong };
/// A new per-launch token: 32 bytes of the system's random source as 64 hex digits.
[[nodiscard]] std::string newToken();
/// What `r` carries of `token` ("" : none needed): its query parameter or its cookie, compared in
/// constant time.
[[nodiscard]] TokenUse tokenUse(const Request& r, const std::string& token);
/// The Set-Cookie value that keeps `token` for the page's later requests.
[[nodiscard]] std::string tokenCookie(const std::string& token);
/// Refuses (HttpError 401) a request that commands the machine without this launch's token,
/// whatever address the server listens on.
void requireCommandToken(const Request& r, const Api::State& s);

/// A checked pose as JSON (docs/web.md, POST /api/ik).
[[nodiscard]] Json poseRowJson(const workflow::PoseCheckRow& row);

// The routes (one file each).
[[nodiscard]] Response listMachines(Api::State& s);
[[nodiscard]] Response getMachine(Api::State& s, const std::string& name);
[[nodiscard]] Response uploadMachine(Api::State& s, const Request& r);
[[nodiscard]] Response checkPoses(Api::State& s, const Request& r);
[[nodiscard]] Response runGcode(Api::State& s, const Request& r);
[[nodiscard]] Response compensateGcode(Api::State& s, const Request& r);
[[nodiscard]] Response makeShape(const Request& r);
[[nodiscard]] Response listCampaigns();
/// Checks a campaign request ({"campaign": NAME}) and sets `job` up with a job slot and a number.
void prepareCampaign(Api::State& s, const Request& r, CampaignJob& job);
[[nodiscard]] Response campaignReport(Api::State& s, const std::string& id);
/// The name under which the followed LinuxCNC's machine is a machine of every route.
inline constexpr const char* kLiveMachine = "linuxcnc";
/// GET /api/live/program: the program the followed LinuxCNC has loaded, {"file", "text"}; 404
/// when none (api_live.cpp).
[[nodiscard]] Response liveProgram(Api::State& s);
/// GET /api/live: the followed LinuxCNC's state checked on its machine (api_live.cpp).
[[nodiscard]] Response liveStatus(Api::State& s);
/// POST /api/live/connect: starts following the LinuxCNC on this host (no-op when following).
[[nodiscard]] Response liveConnect(Api::State& s);
/// POST /api/live/disconnect: stops following it.
[[nodiscard]] Response liveDisconnect(Api::State& s);
/// The INI of the followed LinuxCNC (--linuxcnc INI, else the one it reports); HttpError 409 when
/// none is followed.
[[nodiscard]] std::string followedIni(Api::State& s);
/// GET /api/live/calibration: whether a calibration runs, its stage, whether it waits for an
/// answer (api_live_calibration.cpp).
[[nodiscard]] Response liveCalibrationState(Api::State& s);
/// POST /api/live/calibration/cancel (token): stops the running calibration and the machine.
[[nodiscard]] Response cancelLiveCalibration(Api::State& s, const Request& r);
/// POST /api/live/calibration/confirm {"install": bool} (token): the answer the routine waits for.
[[nodiscard]] Response confirmLiveCalibration(Api::State& s, const Request& r);
/// Checks a calibration request and sets `job` up: the commander started, LinuxCNC ready.
void prepareLiveCalibration(Api::State& s, const Request& r, LiveCalibrationJob& job);

}  // namespace pkm::server::detail
