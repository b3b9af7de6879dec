// The HTTP transport of `pkm serve` (pkm/server/http_server.hpp), on cpp-httplib.
#include "pkm/server/http_server.hpp"

#include <fmt/format.h>
#include <httplib.h>

#include "pkm/core/error.hpp"

namespace pkm::server {
namespace {

/// Worker threads of the server (open connections, including a browser's idle ones).
constexpr std::size_t kWorkerThreads = 32;

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
  res.set_header("Cache-Control", "no-store");
  if (!r.set_cookie.empty()) res.set_header("Set-Cookie", r.set_cookie);
}

}  // namespace

struct HttpServer::Impl {
  explicit Impl(ServerOptions o) : options(o), api(std::move(o)) {}
  ServerOptions options;
  Api api;
  httplib::Server http;
};

HttpServer::HttpServer(ServerOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {
  httplib::Server& http = impl_->http;
  Api& api = impl_->api;
  http.set_payload_max_length(impl_->options.max_body);
  // A browser keeps up to six connections open between requests, and httplib serves each open
  // connection on a worker thread of its own: with its default pool (8 threads on this machine)
  // new requests waited for idle connections to time out (seconds). A larger pool serves them at
  // once; long jobs are limited separately (max_jobs).
  http.new_task_queue = [] { return new httplib::ThreadPool(kWorkerThreads); };
  http.set_keep_alive_max_count(1000);
  http.set_keep_alive_timeout(10);
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
    if (req.path != "/api/campaign") return handle(req, res);
    auto job = std::make_shared<CampaignJob>();
    const Response admitted = api.startCampaign(requestOf(req), *job);
    if (admitted.status != 200) return answer(admitted, res);
    res.set_header("Cache-Control", "no-store");
    res.set_chunked_content_provider(
        "text/event-stream",
        [&api, job](std::size_t, httplib::DataSink& sink) {
          api.runCampaign(*job, [&sink](const std::string& chunk) {
            return sink.is_writable() && sink.write(chunk.data(), chunk.size());
          });
          sink.done();
          return true;
        },
        [job](bool) { job->cancel.cancel(); });
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
  impl_->api.setPort(port);
  return port;
}

void HttpServer::listen() { impl_->http.listen_after_bind(); }

void HttpServer::stop() { impl_->http.stop(); }

Api& HttpServer::api() { return impl_->api; }

}  // namespace pkm::server
