// The API's front door (pkm/server/api.hpp): the server's folder, the security checks every
// request passes (Host, token, Origin, size) and the routing to the route files.
#include "pkm/server/api.hpp"

#include <fmt/format.h>
#include <stdlib.h>

#include <regex>

#include "api_state.hpp"
#include "pkm/core/error.hpp"

namespace pkm::server {
namespace {

/// The Host values a request may carry: the loopback names and the bound address, with the port.
bool allowedHost(const std::string& host, const Api::State& s) {
  const std::string port = std::to_string(s.port.load());
  for (const std::string& h :
       {std::string("127.0.0.1"), std::string("localhost"), std::string("[::1]"), s.options.host})
    if (host == h + ":" + port) return true;
  return false;
}

/// A refusal for a request from a foreign page (DNS rebinding, cross-origin POST), a body above
/// the limit, or nothing.
std::optional<Response> admit(const Request& r, const Api::State& s) {
  if (!allowedHost(r.host, s))
    return detail::error(403,
                         fmt::format("Host '{}' refused: this server answers only to "
                                     "127.0.0.1:{} or localhost:{}",
                                     r.host,
                                     s.port.load(),
                                     s.port.load()));
  // On a loopback address only the routes that command the machine need the token (they check it
  // themselves): a stale cookie of an earlier launch does not lock the user out of the rest.
  if (const detail::TokenUse use = detail::tokenUse(r, s.token);
      !isLoopbackHost(s.options.host) &&
      (use == detail::TokenUse::kMissing || use == detail::TokenUse::kWrong))
    return detail::error(401,
                         use == detail::TokenUse::kWrong
                             ? "wrong token: this server was started again, or the link is not "
                               "the one `pkm serve` printed; open the URL it printed"
                             : "this server is reachable from other machines and needs its "
                               "token: open the URL `pkm serve` printed (…/?token=…)");
  const bool reads = r.method == "GET" || r.method == "HEAD";
  if (!reads && !r.origin.empty() &&
      !(r.origin.starts_with("http://") && allowedHost(r.origin.substr(7), s)))
    return detail::error(403,
                         fmt::format("Origin '{}' refused: cross-origin requests may not "
                                     "change anything",
                                     r.origin));
  if (r.body.size() > s.options.max_body)
    return detail::error(413,
                         fmt::format("request body of {} bytes is above the limit of {}",
                                     r.body.size(),
                                     s.options.max_body));
  return std::nullopt;
}

/// `path` without `prefix` when it starts with it.
std::optional<std::string> after(const std::string& path, std::string_view prefix) {
  if (!path.starts_with(prefix) || path.size() == prefix.size()) return std::nullopt;
  return path.substr(prefix.size());
}

void requireMethod(const Request& r, const char* method) {
  if (r.method != method)
    throw detail::HttpError(405, fmt::format("{} {}: use {}", r.method, r.path, method));
}

/// The routes of the followed LinuxCNC (GET /api/live, ...; api_live.cpp,
/// api_live_calibration.cpp).
Response routeLive(const Request& r, Api::State& s) {
  const std::string& p = r.path;
  if (p == "/api/live") {
    requireMethod(r, "GET");
    return detail::liveStatus(s);
  }
  if (p == "/api/live/program") {
    requireMethod(r, "GET");
    return detail::liveProgram(s);
  }
  if (p == "/api/live/connect") {
    requireMethod(r, "POST");
    return detail::liveConnect(s);
  }
  if (p == "/api/live/disconnect") {
    requireMethod(r, "POST");
    return detail::liveDisconnect(s);
  }
  if (p == "/api/live/calibration") {
    if (r.method == "POST")
      throw detail::HttpError(400,
                              "POST /api/live/calibration answers with server-sent events: call "
                              "it through the HTTP server");
    requireMethod(r, "GET");
    return detail::liveCalibrationState(s);
  }
  if (p == "/api/live/calibration/cancel") {
    requireMethod(r, "POST");
    return detail::cancelLiveCalibration(s, r);
  }
  if (p == "/api/live/calibration/confirm") {
    requireMethod(r, "POST");
    return detail::confirmLiveCalibration(s, r);
  }
  throw detail::HttpError(404, fmt::format("{} {}: no such route (docs/web.md)", r.method, p));
}

Response route(const Request& r, Api::State& s) {
  const std::string& p = r.path;
  if (p == "/api/machines") {
    if (r.method == "POST") return detail::uploadMachine(s, r);
    requireMethod(r, "GET");
    return detail::listMachines(s);
  }
  if (const auto name = after(p, "/api/machines/")) {
    requireMethod(r, "GET");
    return detail::getMachine(s, *name);
  }
  if (p == "/api/ik") {
    requireMethod(r, "POST");
    return detail::checkPoses(s, r);
  }
  if (p == "/api/gcode/run") {
    requireMethod(r, "POST");
    return detail::runGcode(s, r);
  }
  if (p == "/api/gcode/shape") {
    requireMethod(r, "POST");
    return detail::makeShape(r);
  }
  if (p == "/api/gcode/compensate") {
    requireMethod(r, "POST");
    return detail::compensateGcode(s, r);
  }
  static const std::regex cancel(R"(^/api/jobs/([A-Za-z0-9._-]{1,64})/cancel$)");
  std::smatch job;
  if (std::regex_match(p, job, cancel)) {
    requireMethod(r, "POST");
    return detail::cancelJob(s, job[1].str());
  }
  if (p == "/api/jobs") {
    requireMethod(r, "GET");
    return detail::listJobs(s);
  }
  if (p == "/api/live" || p.starts_with("/api/live/")) return routeLive(r, s);
  if (p == "/api/campaigns") {
    requireMethod(r, "GET");
    return detail::listCampaigns();
  }
  static const std::regex report(R"(^/api/campaign/(\d{1,9})/report\.html$)");
  std::smatch m;
  if (std::regex_match(p, m, report)) {
    requireMethod(r, "GET");
    return detail::campaignReport(s, m[1].str());
  }
  if (p == "/api/campaign")
    throw detail::HttpError(400,
                            "POST /api/campaign answers with server-sent events: call it "
                            "through the HTTP server");
  if (!p.starts_with("/api/") && (r.method == "GET" || r.method == "HEAD"))
    if (const Response* a = Api::asset(p)) return *a;
  throw detail::HttpError(404, fmt::format("{} {}: no such route (docs/web.md)", r.method, p));
}

/// The response for an exception a route let out.
Response failure(const Api::State& s) {
  try {
    throw;
  } catch (const detail::HttpError& e) {
    Response out = detail::error(e.status, s.clean(e.what()));
    if (e.status == 503) out.retry_after = "2";
    return out;
  } catch (const workflow::Cancelled&) {
    return detail::error(
        409, "stopped: the job was cancelled (the stop button, or POST /api/jobs/NAME/cancel)");
  } catch (const IoError& e) {
    return detail::error(422, s.clean(e.what()));
  } catch (const InvalidArgument& e) {
    // A violated precondition of a program or file ("NAME:LINE: ...") is the input's error.
    static const std::regex located(R"(^[^:\n]+:\d+:)");
    const std::string message = s.clean(e.what());
    return detail::error(std::regex_search(message, located) ? 422 : 400, message);
  } catch (const std::exception& e) {
    return detail::error(500, fmt::format("internal error: {}", s.clean(e.what())));
  }
}

}  // namespace

void ServerOptions::validate() const {
  PKM_CHECK(port >= 0 && port <= 65535, "--port must be 0..65535, got {}", port);
  PKM_CHECK(max_body > 0 && max_jobs > 0 && max_uploads > 0 && max_run_points > 0,
            "server limits must be > 0");
  PKM_CHECK(!host.empty(), "--host must not be empty");
  live.validate();
  commander.validate();
  PKM_CHECK(heartbeat_s > 0.0 && heartbeat_s <= 10.0, "heartbeat must be in (0, 10] s");
  PKM_CHECK(linuxcnc_ini.empty() || std::filesystem::is_regular_file(linuxcnc_ini),
            "--linuxcnc {}: no such INI file",
            linuxcnc_ini);
}

Api::Api(ServerOptions options) : state_(std::make_unique<State>()) {
  options.validate();
  state_->options = std::move(options);
  state_->port = state_->options.port;
  std::string dir = (std::filesystem::temp_directory_path() / "pkm-serve-XXXXXX").string();
  if (::mkdtemp(dir.data()) == nullptr)
    throw IoError(fmt::format("{}: cannot create the server's folder", dir));
  state_->dir = dir;
  state_->token = detail::newToken();
  if (state_->options.linuxcnc) (void)detail::liveConnect(*state_);
}

Api::~Api() {
  std::error_code ec;
  std::filesystem::remove_all(state_->dir, ec);
}

void Api::setPort(int port) { state_->port = port; }

const std::string& Api::token() const { return state_->token; }

Response Api::handle(const Request& request) {
  try {
    if (std::optional<Response> refused = admit(request, *state_)) return *refused;
    Response out = route(request, *state_);
    // The token came in the URL: a cookie keeps it for the page's own requests.
    if (detail::tokenUse(request, state_->token) == detail::TokenUse::kQuery)
      out.set_cookie = detail::tokenCookie(state_->token);
    return out;
  } catch (...) {
    return failure(*state_);
  }
}

Response Api::startLiveCalibration(const Request& request, LiveCalibrationJob& job) {
  try {
    if (std::optional<Response> refused = admit(request, *state_)) return *refused;
    requireMethod(request, "POST");
    detail::prepareLiveCalibration(*state_, request, job);
    return {200, "text/event-stream", "", "", "", ""};
  } catch (...) {
    return failure(*state_);
  }
}

Response Api::startCampaign(const Request& request, CampaignJob& job) {
  try {
    if (std::optional<Response> refused = admit(request, *state_)) return *refused;
    requireMethod(request, "POST");
    detail::prepareCampaign(*state_, request, job);
    return {200, "text/event-stream", "", "", "", ""};
  } catch (...) {
    return failure(*state_);
  }
}

}  // namespace pkm::server
