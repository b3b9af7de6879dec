/// @file
/// @brief The JSON API of `pkm serve` (docs/web.md), independent of the HTTP transport: every
/// request is checked (Host, Origin, size), routed and answered by a workflow function; the HTTP
/// adapter (http_server.hpp) only moves bytes. Thread-safe: one Api serves concurrent requests.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "pkm/io/linuxcnc_samples.hpp"
#include "pkm/live/linuxcnc_commander.hpp"
#include "pkm/live/linuxcnc_link.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::server {

/// Where a server listens and what it allows.
struct ServerOptions {
  std::string host = "127.0.0.1";    ///< the address to bind (another host only when asked)
  int port = 8787;                   ///< 0: any free port
  std::size_t max_body = 32u << 20;  ///< largest request body, bytes (413 above)
  std::size_t max_jobs = 2;     ///< long jobs at once (runs, compensations, campaigns); more wait
  std::size_t max_queued = 16;  ///< long jobs waiting for a slot; 503 with Retry-After above
  /// Interpolated points (and motions) one run may make: a runaway loop's memory stays bounded
  /// (about 0.2 GB per million; the CLI's default of 10 million is for whole CAM programs).
  std::size_t max_run_points = 1'000'000;
  std::size_t max_uploads = 32;  ///< machines one server holds (the oldest is dropped)
  /// Where LinuxCNC's sample configurations are (io::installedLinuxcncSamples): those pkm reads
  /// join the machine list.
  std::string sample_root = io::kLinuxcncSampleRoot;
  /// Follow the LinuxCNC running on this host from the start (`pkm serve --linuxcnc`); the page's
  /// Connect does the same later (POST /api/live/connect).
  bool linuxcnc = false;
  /// That LinuxCNC's INI ("": the one LinuxCNC reports it was started with).
  std::string linuxcnc_ini;
  live::LinkOptions live;  ///< how the link reads LinuxCNC (rate; the reader, for tests)
  /// How a calibration routine commands LinuxCNC (POST /api/live/calibration; a stand-in, for
  /// tests).
  live::CommanderOptions commander;
  /// Seconds between the heartbeats of a routine's event stream; a heartbeat that cannot be
  /// written (the page's connection dropped) stops the routine and the machine (> 0).
  double heartbeat_s = 0.25;
  /// Throws pkm::InvalidArgument for a port outside 0..65535, a zero limit or bad live options.
  void validate() const;
};

/// A request as the transport received it.
struct Request {
  std::string method;  ///< "GET", "POST", ...
  std::string path;    ///< without the query string
  std::string body;
  std::string host;    ///< the Host header ("" when absent)
  std::string origin;  ///< the Origin header ("" when absent)
  std::string token;   ///< the query string's `token` parameter ("" when absent)
  std::string cookie;  ///< the Cookie header ("" when absent)
};

/// A complete answer.
struct Response {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  /// A Set-Cookie header value ("" : none): the server's token after the page opened its URL.
  std::string set_cookie;
  /// A Retry-After header value, seconds ("" : none): a 503 says when to try again.
  std::string retry_after;
  /// The Cache-Control header ("" : no-store): the content-hashed bundle is kept a year.
  std::string cache_control;
};

/// Whether `host` (an address or name to bind) is a loopback address: localhost, ::1 or 127.x.y.z.
[[nodiscard]] bool isLoopbackHost(const std::string& host);

/// The name of the cookie that carries the server's token.
inline constexpr const char* kTokenCookie = "pkm_token";

/// A campaign admitted by Api::startCampaign, run by Api::runCampaign.
struct CampaignJob {
  std::string campaign;  ///< built-in campaign name
  int id = 0;            ///< its number: GET /api/campaign/ID/report.html
  workflow::CancellationToken cancel;
  std::shared_ptr<void> slot;  ///< the job slot it holds, released with the job
};

struct LiveRoutine;  ///< the server's record of a running calibration (src/server/api_state.hpp)

/// A calibration by constrained motion admitted by Api::startLiveCalibration, run by
/// Api::runLiveCalibration (docs/web.md, "The automated calibration").
struct LiveCalibrationJob {
  std::shared_ptr<LiveRoutine> routine;
};

/// The API. Uploaded machines and campaign reports live in a folder of the server's own (removed
/// when the Api is destroyed); a request never names a file system path.
class Api {
 public:
  /// Throws as ServerOptions::validate and pkm::IoError when its folder cannot be made.
  explicit Api(ServerOptions options);
  ~Api();
  Api(const Api&) = delete;
  Api& operator=(const Api&) = delete;

  /// The port the transport bound (for the Host and Origin checks when options.port was 0).
  void setPort(int port);

  /// The per-launch secret: 64 hex digits from the system's random source, new at every launch.
  /// Every route that commands the machine needs it, and every route at all when the server is
  /// reachable from other machines (options.host not a loopback address). A request carries it as
  /// `?token=` (the URL `pkm serve` prints; answered with a cookie) or as the cookie kTokenCookie;
  /// compared in constant time; 401 without it.
  [[nodiscard]] const std::string& token() const;

  /// Answers every route but the campaign stream (docs/web.md): 200 with JSON, 400 for malformed
  /// JSON or a bad field, 401 without the server's token (token()), 403 for a foreign Host or
  /// Origin, 404 for an unknown path, 405 for a
  /// wrong method, 413 for a body above max_body, 422 {"error", "name", "line"} for a program or
  /// file with an error, 503 when max_jobs long jobs run already. Never throws.
  [[nodiscard]] Response handle(const Request& request);

  /// POST /api/campaign: checks the request and takes a job slot. Returns status 200 with `job`
  /// set up, or the error response (as handle()). A job that was admitted must be run.
  [[nodiscard]] Response startCampaign(const Request& request, CampaignJob& job);
  /// Runs an admitted campaign, passing each server-sent event (`event: NAME\ndata: JSON\n\n`) to
  /// `write`; `write` returning false (the client left) cancels the campaign. Never throws.
  void runCampaign(CampaignJob& job, const std::function<bool(const std::string&)>& write);

  /// POST /api/live/calibration: checks the request (token, Origin, "confirm": true, the gauges)
  /// and that LinuxCNC may move (409 with the reason: E-stop, not homed, busy, another routine),
  /// then starts the commander. Returns status 200 with `job` set up, or the error response (as
  /// handle()); nothing is sent to LinuxCNC but status requests unless it returns 200. A job that
  /// was admitted must be run.
  [[nodiscard]] Response startLiveCalibration(const Request& request, LiveCalibrationJob& job);
  /// Runs an admitted calibration (live::calibrateLive), passing its server-sent events to
  /// `write` and a heartbeat every options.heartbeat_s; `write` returning false (the page's
  /// connection dropped) stops the routine and aborts the machine's motion. After the fit it asks
  /// the page ("confirm" event) and waits for POST /api/live/calibration/confirm. Never throws.
  void runLiveCalibration(LiveCalibrationJob& job,
                          const std::function<bool(const std::string&)>& write);

  /// Stops `job`'s routine and LinuxCNC's motion (the transport: its connection ended).
  static void stopLiveCalibration(LiveCalibrationJob& job);

  /// The embedded front-end asset at `path` ("/" is "/index.html"), if there is one.
  [[nodiscard]] static const Response* asset(const std::string& path);

  struct State;  ///< the implementation's (src/server/api_state.hpp)

 private:
  std::unique_ptr<State> state_;
};

}  // namespace pkm::server
