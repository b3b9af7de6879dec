// The HTTP transport of `pkm serve` (pkm/server/http_server.hpp), on cpp-httplib.
#include "pkm/server/http_server.hpp"

#include <fmt/format.h>
#include <httplib.h>
#include <sys/socket.h>

#include <functional>
#include <memory>

#include "connection_gate.hpp"
#include "pkm/core/error.hpp"

namespace pkm::server {
namespace {

/// Connections the kernel queues before they are accepted.
constexpr int kListenBacklog = 1024;

/// Threads that hand accepted sockets to the gate (each returns at once).
constexpr std::size_t kAcceptThreads = 2;

/// httplib's server with its connection handling replaced by the gate (connection_gate.hpp):
/// httplib accepts and processes requests; the gate decides when a connection has one.
class GuardedServer : public httplib::Server {
 public:
  detail::ConnectionGate* gate = nullptr;

  /// Serves the one request whose header `c`'s buffer holds; true when the connection may be kept.
  bool serveOne(detail::Connection& c, httplib::Stream& stream, bool last) {
    bool closed = false;
    const bool ok = process_request(stream, last, closed, [&c](httplib::Request& req) {
      req.remote_addr = c.peer_ip;
      req.remote_port = c.peer_port;
      req.local_addr = c.local_ip;
      req.local_port = c.local_port;
    });
    return ok && !closed;
  }

  /// httplib listens with a backlog of 5: a burst of connections (a page's, or hundreds a local
  /// process opens) saw their SYNs dropped and retried after a second. Listening again on the
  /// bound socket widens the queue (Linux keeps the socket and takes the new backlog).
  void widenBacklog(int backlog) {
    if (const socket_t sock = svr_sock_.load(); sock != INVALID_SOCKET) ::listen(sock, backlog);
  }

 private:
  bool process_and_close_socket(socket_t sock) override {
    gate->admit(sock);
    return true;
  }
};

Request requestOf(const httplib::Request& req) {
  return {req.method,
          req.path,
          req.body,
          req.get_header_value("Host"),
          req.get_header_value("Origin"),
          req.get_param_value("token"),
          req.get_header_value("Cookie")};
}

void answer(const Response& r, httplib::Response& res) {
  res.status = r.status;
  res.set_content(r.body, r.content_type.c_str());
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_header("Cache-Control", r.cache_control.empty() ? "no-store" : r.cache_control);
  if (!r.set_cookie.empty()) res.set_header("Set-Cookie", r.set_cookie);
  if (!r.retry_after.empty()) res.set_header("Retry-After", r.retry_after);
}

using EventWriter = std::function<bool(const std::string&)>;

/// Answers with server-sent events: `run` writes them (a write returns false once the client has
/// gone); `stop` is called when the connection ends, however it ends.
void streamEvents(httplib::Response& res,
                  std::function<void(const EventWriter&)> run,
                  std::function<void()> stop) {
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_chunked_content_provider(
      "text/event-stream",
      [run = std::move(run)](std::size_t, httplib::DataSink& sink) {
        run([&sink](const std::string& chunk) {
          return sink.is_writable() && sink.write(chunk.data(), chunk.size());
        });
        sink.done();
        return true;
      },
      [stop = std::move(stop)](bool) { stop(); });
}

/// POST /api/live/calibration: the routine's events as they come; the connection's end stops it.
void streamLiveCalibration(Api& api, const httplib::Request& req, httplib::Response& res) {
  auto job = std::make_shared<LiveCalibrationJob>();
  const Response admitted = api.startLiveCalibration(requestOf(req), *job);
  if (admitted.status != 200) return answer(admitted, res);
  streamEvents(
      res,
      [&api, job](const EventWriter& write) { api.runLiveCalibration(*job, write); },
      [job] { Api::stopLiveCalibration(*job); });
}

/// POST /api/campaign: the campaign's events; the connection's end cancels it.
void streamCampaign(Api& api, const httplib::Request& req, httplib::Response& res) {
  auto job = std::make_shared<CampaignJob>();
  const Response admitted = api.startCampaign(requestOf(req), *job);
  if (admitted.status != 200) return answer(admitted, res);
  streamEvents(
      res,
      [&api, job](const EventWriter& write) { api.runCampaign(*job, write); },
      [job] { job->cancel.cancel(); });
}

}  // namespace

struct HttpServer::Impl {
  explicit Impl(ServerOptions o)
      : options(o),
        api(std::move(o)),
        gate({}, [this](detail::Connection& c, httplib::Stream& stream) {
          return http.serveOne(
              c, stream, c.requests + 1 >= detail::GateOptions{}.max_requests_per_connection);
        }) {
    http.gate = &gate;
  }
  ServerOptions options;
  Api api;
  GuardedServer http;
  detail::ConnectionGate gate;  // last: stopped and destroyed first
};

HttpServer::HttpServer(ServerOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {
  httplib::Server& http = impl_->http;
  Api& api = impl_->api;
  http.set_payload_max_length(impl_->options.max_body);
  // httplib serves each open connection on a worker thread of its own, so idle connections (a
  // browser's, or 200 a local process opens) held every worker and new requests waited up to a
  // minute. Accepted sockets go to the gate instead, which gives a worker only a complete request.
  http.new_task_queue = [] { return new httplib::ThreadPool(kAcceptThreads); };
  // httplib compresses a response with Brotli whenever the client accepts it, at Brotli's slowest
  // quality: seconds for the 2 MB of a run with frames or the 1.7 MB of app.js, where gzip takes
  // milliseconds. The browser's Accept-Encoding is narrowed to gzip before the response is written
  // (httplib hands handlers the request as const; it owns it and reads this header afterwards).
  http.set_pre_routing_handler([](const httplib::Request& req, httplib::Response&) {
    auto& headers = const_cast<httplib::Request&>(req).headers;
    const bool gzip = req.get_header_value("Accept-Encoding").find("gzip") != std::string::npos;
    headers.erase("Accept-Encoding");
    if (gzip) headers.emplace("Accept-Encoding", "gzip");
    return httplib::Server::HandlerResponse::Unhandled;
  });
  // Every method and path goes to the Api (it answers 404/405 itself); handlers, not a
  // pre-routing hook, so that the body has been read (and limited to max_body: 413).
  auto handle = [&api](const httplib::Request& req, httplib::Response& res) {
    answer(api.handle(requestOf(req)), res);
  };
  http.Get(".*", handle);
  http.Put(".*", handle);
  http.Delete(".*", handle);
  http.Patch(".*", handle);
  http.Options(".*", handle);
  http.Post(".*", [&api, handle](const httplib::Request& req, httplib::Response& res) {
    if (req.path == "/api/live/calibration") return streamLiveCalibration(api, req, res);
    if (req.path == "/api/campaign") return streamCampaign(api, req, res);
    handle(req, res);
  });
}

HttpServer::~HttpServer() { stop(); }

int HttpServer::bind() {
  const ServerOptions& o = impl_->options;
  int port = o.port;
  if (port == 0) {
    port = impl_->http.bind_to_any_port(o.host);
  } else if (!impl_->http.bind_to_port(o.host, port)) {
    port = -1;
  }
  if (port < 0)
    throw IoError(fmt::format(
        "cannot listen on {}:{} (in use, or not an address of this machine)", o.host, o.port));
  impl_->http.widenBacklog(kListenBacklog);
  impl_->api.setPort(port);
  return port;
}

void HttpServer::listen() { impl_->http.listen_after_bind(); }

void HttpServer::stop() {
  impl_->http.stop();
  impl_->gate.stop();
}

Api& HttpServer::api() { return impl_->api; }

}  // namespace pkm::server
